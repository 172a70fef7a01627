//! Wall time per phase of a step, for profiling: built with `--features phase-timers`
//! (`cargo run --release --features phase-timers --example step_scene -- scene.json 300 3000`
//! prints the table). Without the feature every call here compiles to nothing.
//!
//! Why a feature and not a profiler: perf samples say where the CPU goes, not where a two-thread
//! step waits. The phases that were slower on two threads than on one (the permutation, the
//! sort of a developed flow) showed only with timers around each phase.

/// The timed phases of a step, in the order of the report.
#[derive(Clone, Copy, Debug)]
pub enum Phase {
    /// The cell sort's key pass and merge or counting sort (`CellGrid::sort_group`).
    SortGrid,
    /// Marking the blocks of slots the sort moved.
    SortMark,
    /// Permuting the arrays the sort carries.
    SortPermute,
    /// Wall densities, SPS stress, the fluid's forces and the walls' continuity.
    Forces,
    /// The integrator's sweeps (the Symplectic predictor's and every step's last).
    Sweep,
    /// The whole step.
    Step,
}

#[cfg(feature = "phase-timers")]
mod imp {
    use std::sync::atomic::{AtomicU64, Ordering};
    use std::time::Instant;

    use super::Phase;

    const NAMES: [&str; 6] = ["sort: grid", "sort: mark", "sort: permute", "forces", "sweep", "step"];

    static NANOS: [AtomicU64; NAMES.len()] = [const { AtomicU64::new(0) }; NAMES.len()];
    static MOVED_BLOCKS: AtomicU64 = AtomicU64::new(0);

    /// A running lap timer.
    pub struct Timer(Instant);

    impl Timer {
        #[inline(always)]
        pub fn start() -> Self {
            Timer(Instant::now())
        }

        /// Adds the time since the start or the last lap to `phase` and starts the next lap.
        #[inline(always)]
        pub fn lap(&mut self, phase: Phase) {
            let now = Instant::now();
            NANOS[phase as usize].fetch_add((now - self.0).as_nanos() as u64, Ordering::Relaxed);
            self.0 = now;
        }
    }

    #[inline(always)]
    pub fn count_moved_blocks(n: usize) {
        MOVED_BLOCKS.fetch_add(n as u64, Ordering::Relaxed);
    }

    pub fn reset() {
        NANOS.iter().for_each(|n| n.store(0, Ordering::Relaxed));
        MOVED_BLOCKS.store(0, Ordering::Relaxed);
    }

    pub fn report(steps: u64) -> Option<String> {
        let per_step = |ns: u64| ns as f64 / 1e3 / steps.max(1) as f64;
        let mut lines: Vec<String> =
            NAMES.iter().zip(&NANOS).map(|(name, ns)| format!("{name:>14}: {:10.1} us per step", per_step(ns.load(Ordering::Relaxed)))).collect();
        lines.push(format!("{:>14}: {:10.1} per step", "moved blocks", MOVED_BLOCKS.load(Ordering::Relaxed) as f64 / steps.max(1) as f64));
        Some(lines.join("\n"))
    }
}

#[cfg(not(feature = "phase-timers"))]
mod imp {
    use super::Phase;

    pub struct Timer;

    impl Timer {
        #[inline(always)]
        pub fn start() -> Self {
            Timer
        }

        #[inline(always)]
        pub fn lap(&mut self, _phase: Phase) {}
    }

    #[inline(always)]
    pub fn count_moved_blocks(_n: usize) {}

    pub fn reset() {}

    pub fn report(_steps: u64) -> Option<String> {
        None
    }
}

/// Lap timer: [`Timer::start`], then [`Timer::lap`] at the end of each phase.
pub use imp::Timer;
/// Counts the blocks of slots a sort moved.
pub use imp::count_moved_blocks;
/// Zeroes the totals.
pub use imp::reset;
/// The totals per step over `steps` steps since the last [`reset`], one phase a line; `None`
/// without the feature.
pub use imp::report;

#[cfg(all(test, feature = "phase-timers"))]
mod tests {
    use super::*;

    /// The value of a report line, per step.
    fn value(text: &str, name: &str) -> f64 {
        let line = text.lines().find(|l| l.trim_start().starts_with(name)).expect("the phase's line");
        line.split(':').nth(1).and_then(|v| v.split_whitespace().next()).and_then(|v| v.parse().ok()).expect("a number")
    }

    /// Laps add to their phase. The totals are process-wide and other tests step simulations
    /// at the same time, so they can only be bounded from below here.
    #[test]
    fn laps_add_up_per_phase() {
        reset();
        let mut t = Timer::start();
        std::thread::sleep(std::time::Duration::from_millis(2));
        t.lap(Phase::Forces);
        count_moved_blocks(6);
        let text = report(2).expect("feature on");
        assert!(value(&text, "forces") >= 1000.0, "{text}");
        assert!(value(&text, "moved blocks") >= 3.0, "{text}");
        assert_eq!(text.lines().count(), 7, "{text}");
    }
}
