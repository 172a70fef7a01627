//! The solver: a scene's particles advanced in time, one monomorphised step per combination of
//! dimension, kernel, viscosity model and density diffusion.
//!
//! `mod.rs` holds the solver's state and its object-safe face ([`Simulation`]); `build.rs`
//! builds it from a scene ([`Solver::new`]); one step reads top to bottom in `step.rs`
//! (`Solver::step_once`: sort by cell, equation of state, (SPS stress), forces, time step,
//! integration, monitors, gauges); `advance.rs` is the integrator's sweep and `checkpoint.rs`
//! saves and restores the state.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use rayon::prelude::*;

mod advance;
mod build;
mod checkpoint;
#[cfg(feature = "flop-count")]
mod flops;
mod snapshot;
mod step;

pub use checkpoint::Checkpoint;
#[cfg(feature = "flop-count")]
pub use flops::PairFlops;
pub use snapshot::{Snapshot, SnapshotExchange};

use crate::boundary::WallModel;
use crate::diagnostics::Diagnostics;
use crate::absorption::AbsorberState;
use crate::error::{Error, Result};
use crate::kernel::Kernel;
use crate::math::{Dim, Real, Vector};
use crate::neighbours::{CellGrid, GROUP_FIXED, GROUP_FLUID, GROUP_MOVING};
use crate::phases::{self, Phase};
use crate::particles::{mark_moved_blocks, permute_carried, Carried, Particles, KIND_EXCLUDED};
use crate::probes::{GaugeRecord, ProbeView};
use crate::threads::with_workers_polling;
use crate::physics::eos::pressure;
use crate::physics::forces::{Fields, FluidForceLoop};
use crate::physics::split_positions::SplitPositions;
use crate::physics::Constants;
use crate::scene::{Integrator, Scene, ShiftingModel};

/// Cells of half the kernel support: fewer candidate pairs than `2h` cells (see `neighbours.rs`).
const NEIGHBOUR_REACH: usize = 2;

/// Derived parameters of a run, for reports.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Params {
    pub dim: usize,
    pub dp: Real,
    pub h: Real,
    pub support: Real,
    pub cell_size: Real,
    pub n_cells: usize,
    pub mass: Real,
    pub rho0: Real,
    pub c0: Real,
    pub b_tait: Real,
    pub gamma: Real,
    pub boundary_layers: usize,
    pub kernel: &'static str,
    pub viscosity: &'static str,
    pub diffusion: &'static str,
    pub integrator: &'static str,
    /// Wall boundary model: "dbc" or "adami".
    pub boundary: &'static str,
    /// Particle shifting's coefficient `A` (none without shifting).
    pub shifting: Option<Real>,
    /// Particle shifting's law, "lind" or "delta_plus" (none without shifting).
    pub shifting_model: Option<&'static str>,
    /// Monaghan's (2000) tensile correction: "monaghan", or none without it.
    pub tensile_correction: Option<&'static str>,
    /// The Riemann solver: "acoustic", or none for the classic formulation.
    pub riemann: Option<&'static str>,
    /// The kernel gradient correction's threshold eigenvalue (none without the correction).
    pub kernel_correction: Option<Real>,
    /// Arithmetic of the force loop's pair terms: "f64" or "f32".
    pub force_precision: &'static str,
    /// Smallest time step allowed before the run is declared unstable [s].
    pub dt_floor: Real,
}

/// Shepard-normalised SPH interpolation at a set of points (DESIGN.md section 4).
#[derive(Clone, Debug, Default)]
pub struct Interpolated {
    /// `sum_b V_b W` (about 1 inside the fluid, 0 far outside).
    pub kernel_sum: Vec<Real>,
    pub density: Vec<Real>,
    pub pressure: Vec<Real>,
    /// Flattened `(M, dim)`.
    pub velocity: Vec<Real>,
}

/// The object-safe face of a solver, whatever its compile-time options.
pub trait Simulation: Send + Sync {
    fn dim(&self) -> usize;
    fn time(&self) -> Real;
    fn steps(&self) -> u64;
    /// Last time step taken [s] (0 before the first step).
    fn dt(&self) -> Real;
    fn n_particles(&self) -> usize;
    fn n_fluid(&self) -> usize;
    /// Advances `n` steps.
    fn step(&mut self, n: u64) -> Result<()>;
    /// Advances until `time >= until` (the last step is not shortened).
    fn run_until(&mut self, until: Real) -> Result<()>;
    /// Flattened `(N, dim)` positions in storage order.
    fn positions(&self) -> &[Real];
    fn velocities(&self) -> &[Real];
    fn densities(&self) -> &[Real];
    /// Pressures from the equation of state, computed from the densities (not stored).
    fn pressures(&self) -> Vec<Real>;
    fn kinds(&self) -> &[u8];
    fn ids(&self) -> &[u32];
    /// Bytes of the solver's own arrays (particles, integrator history, grid, optional fields).
    fn memory_bytes(&self) -> usize;
    /// See [`Solver::fluid_pair_count`].
    fn fluid_pairs(&self) -> u64;
    /// See [`Solver::force_evaluations_per_step`].
    fn force_evaluations_per_step(&self) -> u32;
    /// [`Solver::pair_flops`]: the roofline's counts and times (feature `flop-count`).
    #[cfg(feature = "flop-count")]
    fn pair_flops(&mut self, repeats: u32) -> Option<PairFlops>;
    fn params(&self) -> Params;
    /// Interpolates fluid fields at flattened `(M, dim)` points.
    fn interpolate(&self, points: &[Real]) -> Result<Interpolated>;
    /// Gauge records, in the scene's order.
    fn gauges(&self) -> &[GaugeRecord];
    /// Fluid particles excluded after leaving the domain.
    fn n_excluded(&self) -> usize;
    fn checkpoint(&self) -> Checkpoint;
    /// Continues from a checkpoint of a run of the same scene.
    fn restore(&mut self, checkpoint: &Checkpoint) -> Result<()>;
    /// The run's stop flag: while it is set, [`Simulation::step`] and
    /// [`Simulation::run_until`] return [`Error::Interrupted`] before their next step (the
    /// binding sets it from another thread on Ctrl-C and clears it before each call).
    fn stop_flag(&self) -> Arc<AtomicBool>;
    /// Where another thread asks for a [`Snapshot`] while [`Simulation::step`] or
    /// [`Simulation::run_until`] runs: answered between two steps.
    fn snapshot_exchange(&self) -> Arc<SnapshotExchange>;
    /// Copies of the present state.
    fn snapshot(&self) -> Snapshot {
        Snapshot {
            time: self.time(),
            steps: self.steps(),
            dt: self.dt(),
            positions: self.positions().to_vec(),
            velocities: self.velocities().to_vec(),
            densities: self.densities().to_vec(),
            kinds: self.kinds().to_vec(),
            ids: self.ids().to_vec(),
            n_excluded: self.n_excluded(),
        }
    }
}

/// Integrator history.
#[derive(Debug, Clone)]
enum History<D: Dim> {
    /// Velocities and densities at the start of the step (the corrector advances positions
    /// from the predictor's half step, so no copy of them is needed).
    Symplectic { vel0: Vec<D::V>, rho0: Vec<Real> },
    /// Velocities and densities one step back, and the step counter for the Euler restart.
    Verlet { vel_prev: Vec<D::V>, rho_prev: Vec<Real>, euler_every: u32 },
}

impl<D: Dim> History<D> {
    /// The history's velocity and density arrays, whichever the scheme.
    fn arrays_mut(&mut self) -> (&mut Vec<D::V>, &mut Vec<Real>) {
        match self {
            History::Symplectic { vel0, rho0 } => (vel0, rho0),
            History::Verlet { vel_prev, rho_prev, .. } => (vel_prev, rho_prev),
        }
    }
}

/// Particle shifting's per-fluid-particle fields (see [`crate::scene::Shifting`]), computed
/// after the step's last force evaluation (no cell sort comes between them and their use).
#[derive(Debug, Clone)]
struct ShiftState<D: Dim> {
    model: ShiftingModel,
    /// `A h` of Skillen et al.'s `D = A h |u| dt` (`lind`) or of `A h U_max dt` (`delta_plus`).
    a_h: Real,
    /// `lind`: free-surface threshold of the particle divergence (the bulk's is `dim`).
    threshold: Real,
    /// `lind`: the concentration gradient; `delta_plus`: the shift direction.
    grad: Vec<D::V>,
    /// `lind`: the particle divergence; `delta_plus`: the renormalisation matrix's smallest
    /// eigenvalue.
    div: Vec<Real>,
    /// `delta_plus`: the outward surface normal's scratch (empty for `lind`).
    normal: Vec<D::V>,
    /// `delta_plus`: the largest fluid speed at the last shifting pass.
    u_max: Real,
}

#[derive(Debug, Clone, Default)]
struct Scratch {
    perm: Vec<u32>,
    /// One entry per [`PERMUTE_BLOCK`] slots: the block's rank among those the last sort moved
    /// a particle in, or `NOT_MOVED` (see `mark_moved_blocks`).
    ranks: Vec<u32>,
    /// The blocks the last sort moved a particle in.
    moved: Vec<u32>,
    /// Gather buffer of `permute_carried`, shared by all arrays (see there). Empty when the fluid
    /// accelerations are large enough to serve instead (`Solver::sort_group`).
    gather: Vec<u64>,
    /// The positions split for the single-precision candidate scan; empty in a
    /// double-precision scene.
    split: SplitPositions,
}

pub struct Solver<D: Dim, K: Kernel> {
    scene: Scene,
    c: Constants,
    kernel: K,
    /// The fluid force loop of the scene's viscosity model and density diffusion.
    fluid_loop: FluidForceLoop<D, K>,
    p: Particles<D>,
    grid: CellGrid<D>,
    history: History<D>,
    /// SPS stress per fluid particle; empty without the SPS closure.
    tau: Vec<D::Sym>,
    /// Kernel gradient correction per fluid particle; empty without the correction.
    kgc: Vec<D::Sym>,
    shift: Option<ShiftState<D>>,
    scratch: Scratch,
    time: Real,
    steps: u64,
    dt: Real,
    dt_floor: Real,
    /// Rest positions of the paddle particles, indexed by `id - n_fixed` (ids travel with the
    /// particles through the cell sort, so this array never needs permuting). Empty without a
    /// paddle.
    moving_ref: Vec<D::V>,
    /// Resolved hinge height and still-water level of the paddle.
    paddle_levels: (Real, Real),
    /// Time of the paddle's current pose (the last `move_boundaries`).
    paddle_time: Real,
    /// Active absorption's correction of the paddle's displacement; None without absorption.
    absorber: Option<AbsorberState>,
    /// The wall model, chosen by the scene's `boundary`.
    walls: Box<dyn WallModel<D, K>>,
    gauges: Vec<GaugeRecord>,
    /// Per fixed wall slot, the obstacle it was sampled from (see [`ProbeView::wall_body`]);
    /// empty without force gauges. The fixed walls are sorted once, at the build.
    wall_body: Vec<u16>,
    /// Box outside which fluid particles are excluded.
    domain: (D::V, D::V),
    n_excluded: usize,
    /// Initial mechanical energy and potential energy above the floor [J] (energy monitor).
    energy0: (Real, Real),
    /// See [`Simulation::stop_flag`]; read once per step, never inside a particle loop.
    stop: Arc<AtomicBool>,
    /// See [`Simulation::snapshot_exchange`]; its request flag is read once per step.
    snapshots: Arc<SnapshotExchange>,
}

impl<D: Dim, K: Kernel> Solver<D, K> {
    /// Pairs one fluid force evaluation sums over: each fluid particle that is not excluded with
    /// every other particle, of any group, closer than the support, at the present positions.
    /// The cost of a step is about proportional to it; per particle it depends on how much of a
    /// scene lies within a support of a wall or of the free surface (`watersim bench` reports
    /// the time per pair next to the time per particle). A diagnostic, not for every step: it
    /// sorts a copy of the positions into a copy of the grid (the solver's own grid was sorted
    /// at the last force evaluation, before the positions moved) and holds, while it runs, 9
    /// bytes per particle, a copy of the positions and a copy of the grid (cell starts, and 4
    /// to 6 bytes per particle: the cell of each slot and the movers' scratch).
    pub fn fluid_pair_count(&self) -> u64 {
        let mut grid = self.grid.clone();
        let n = self.p.len();
        let (mut perm, mut keys): (Vec<u32>, _) = ((0..n as u32).collect(), vec![0u32; n]);
        for g in [GROUP_FIXED, GROUP_MOVING, GROUP_FLUID] {
            let range = self.group_range(g);
            if grid.has_group(g) {
                grid.sort_group(g, range.clone(), &self.p.pos, &mut perm[range.clone()], &mut keys);
            }
        }
        let sorted: Vec<D::V> = perm.iter().map(|&i| self.p.pos[i as usize]).collect();
        let kinds: Vec<u8> = perm.iter().map(|&i| self.p.kind[i as usize]).collect();
        let support2 = self.c.support * self.c.support;
        (self.p.fluid_start()..n)
            .into_par_iter()
            .filter(|&a| kinds[a] != KIND_EXCLUDED)
            .map(|a| {
                let x = sorted[a];
                let mut pairs = 0u64;
                for g in [GROUP_FIXED, GROUP_MOVING, GROUP_FLUID] {
                    grid.for_each_near(g, x, |b| pairs += (b != a && (x - sorted[b]).length_squared() < support2) as u64);
                }
                pairs
            })
            .sum()
    }

    /// Fluid force evaluations per time step: two with Symplectic (predictor and corrector),
    /// one with Verlet.
    pub fn force_evaluations_per_step(&self) -> u32 {
        match self.history {
            History::Symplectic { .. } => 2,
            History::Verlet { .. } => 1,
        }
    }

    fn group_range(&self, g: usize) -> std::ops::Range<usize> {
        let (nf, fs) = (self.p.n_fixed, self.p.fluid_start());
        match g {
            GROUP_FIXED => 0..nf,
            GROUP_MOVING => nf..fs,
            _ => fs..self.p.len(),
        }
    }

    /// Sorts one group by cell and carries every per-particle array along.
    fn sort_group(&mut self, g: usize) {
        let range = self.group_range(g);
        if range.is_empty() {
            return;
        }
        let Scratch { perm, gather, ranks, moved, .. } = &mut self.scratch;
        let Particles { pos, vel, rho, id, kind, acc, .. } = &mut self.p;
        // The gather buffer: the fluid accelerations where they are large enough (8 bytes a
        // particle less to hold). They are dead here: every sort comes right before a force
        // evaluation, which overwrites all of them, and nothing reads them in between.
        let gather: &mut [u64] = if gather.is_empty() { bytemuck::cast_slice_mut(acc.as_mut_slice()) } else { gather };
        let perm = &mut perm[..range.len()];
        // the cell keys live in the gather buffer: they are dead before `permute` reuses it
        let keys = bytemuck::cast_slice_mut::<u64, u32>(gather);
        let mut timer = phases::Timer::start();
        self.grid.sort_group(g, range.clone(), pos, perm, keys);
        timer.lap(Phase::SortGrid);
        let perm = &*perm;
        let moved_blocks = mark_moved_blocks(perm, range.start, ranks, moved);
        timer.lap(Phase::SortMark);
        if moved_blocks == 0 {
            return;
        }
        phases::count_moved_blocks(moved_blocks);
        let (hist_v, hist_r) = self.history.arrays_mut();
        let arrays = Carried { vectors: [pos, vel, hist_v], reals: [rho, hist_r], id, kind };
        permute_carried(arrays, range, perm, ranks, moved, gather);
        timer.lap(Phase::SortPermute);
    }

    /// The gauges' view of the present state.
    fn probes(&self) -> ProbeView<'_, D, K> {
        ProbeView { p: &self.p, grid: &self.grid, kernel: &self.kernel, c: &self.c, tank: &self.scene.tank, wall_body: &self.wall_body }
    }

    /// Kinetic plus potential energy of the fluid still in the domain [J].
    pub fn fluid_energy(&self) -> Real {
        self.diagnostics().fluid_energy()
    }

    /// The checks' view of the present state.
    fn diagnostics(&self) -> Diagnostics<'_, D> {
        Diagnostics { p: &self.p, c: &self.c, step: self.steps, time: self.time }
    }

    /// The particle arrays (storage order).
    pub fn particles(&self) -> &Particles<D> {
        &self.p
    }

    /// Mutable particle arrays, for tests and injected perturbations. Do not resize them.
    pub fn particles_mut(&mut self) -> &mut Particles<D> {
        &mut self.p
    }

    pub fn constants(&self) -> &Constants {
        &self.c
    }

    /// Between two steps, where the state is whole: answers a snapshot request, then
    /// [`Error::Interrupted`] if the stop flag is set.
    fn between_steps(&self) -> Result<()> {
        self.snapshots.serve(|| Simulation::snapshot(self));
        if self.stop.load(Ordering::Relaxed) {
            return Err(Error::Interrupted { step: self.steps, time: self.time });
        }
        Ok(())
    }
}

/// Runs `op` on a thread of rayon's pool. A step has some 80 parallel loops; called from
/// outside the pool, each one is a job injected into it that the calling thread sleeps on (a
/// futex wake-up and sleep per loop, about a tenth of a 2D step on two threads). On a pool
/// thread each loop is a fork-join among the workers. Results do not change: how a loop is
/// split depends on the thread count only. The other threads poll for work while `op` runs
/// ([`with_workers_polling`]), so that none falls asleep between two loops of a step.
fn on_pool<R: Send>(op: impl FnOnce() -> R + Send) -> R {
    rayon::scope(|_| with_workers_polling(op))
}

/// The read-only fields of a force or shifting pass over the particles `p`.
fn fields_of<'a, D: Dim>(p: &'a Particles<D>, tau: &'a [D::Sym]) -> Fields<'a, D> {
    Fields { pos: &p.pos, vel: &p.vel, rho: &p.rho, kind: &p.kind, tau, kgc: &[], fluid_start: p.fluid_start(), split: None }
}

fn flat<V: Vector>(v: &[V]) -> &[Real] {
    bytemuck::cast_slice(v)
}

impl<D: Dim, K: Kernel> Simulation for Solver<D, K> {
    fn dim(&self) -> usize {
        D::DIM
    }
    fn time(&self) -> Real {
        self.time
    }
    fn steps(&self) -> u64 {
        self.steps
    }
    fn dt(&self) -> Real {
        self.dt
    }
    fn n_particles(&self) -> usize {
        self.p.len()
    }
    fn n_fluid(&self) -> usize {
        self.p.n_fluid()
    }
    fn step(&mut self, n: u64) -> Result<()> {
        on_pool(|| {
            for _ in 0..n {
                self.between_steps()?;
                let mut timer = phases::Timer::start();
                self.step_once()?;
                timer.lap(Phase::Step);
            }
            Ok(())
        })
    }
    fn run_until(&mut self, until: Real) -> Result<()> {
        if !until.is_finite() {
            return Err(Error::invalid("until", format!("must be finite, got {until}")));
        }
        on_pool(|| {
            while self.time < until {
                self.between_steps()?;
                self.step_once()?;
            }
            Ok(())
        })
    }
    fn positions(&self) -> &[Real] {
        flat(&self.p.pos)
    }
    fn velocities(&self) -> &[Real] {
        flat(&self.p.vel)
    }
    fn densities(&self) -> &[Real] {
        &self.p.rho
    }
    fn pressures(&self) -> Vec<Real> {
        let fs = self.p.fluid_start();
        let (c, walls) = (&self.c, &self.walls);
        self.p.rho.par_iter().enumerate().map(|(i, &r)| if i < fs { walls.pressure(c, r) } else { pressure(c, r) }).collect()
    }
    fn kinds(&self) -> &[u8] {
        &self.p.kind
    }
    fn ids(&self) -> &[u32] {
        &self.p.id
    }
    fn fluid_pairs(&self) -> u64 {
        self.fluid_pair_count()
    }
    fn force_evaluations_per_step(&self) -> u32 {
        Solver::force_evaluations_per_step(self)
    }
    #[cfg(feature = "flop-count")]
    fn pair_flops(&mut self, repeats: u32) -> Option<PairFlops> {
        Solver::pair_flops(self, repeats)
    }
    fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        let v = size_of::<D::V>();
        let r = size_of::<Real>();
        let history = match &self.history {
            History::Symplectic { vel0, rho0 } => vel0.capacity() * v + rho0.capacity() * r,
            History::Verlet { vel_prev, rho_prev, .. } => vel_prev.capacity() * v + rho_prev.capacity() * r,
        };
        let s = &self.scratch;
        let scratch = s.perm.capacity() * 4 + s.gather.capacity() * 8 + (s.ranks.capacity() + s.moved.capacity()) * 4 + s.split.memory_bytes();
        self.p.memory_bytes()
            + history
            + self.tau.capacity() * size_of::<D::Sym>()
            + self.shift.as_ref().map_or(0, |s| (s.grad.capacity() + s.normal.capacity()) * v + s.div.capacity() * r)
            + self.moving_ref.capacity() * v
            + self.wall_body.capacity() * size_of::<u16>()
            + self.walls.memory_bytes()
            + self.grid.memory_bytes()
            + scratch
    }
    fn params(&self) -> Params {
        use crate::scene::{Diffusion, Viscosity};
        let s = &self.scene;
        Params {
            dim: D::DIM,
            dp: self.c.dp,
            h: self.c.h,
            support: self.c.support,
            cell_size: self.c.support / NEIGHBOUR_REACH as Real,
            n_cells: self.grid.n_cells(),
            mass: self.c.mass,
            rho0: self.c.rho0,
            c0: self.c.c0,
            b_tait: self.c.b_tait,
            gamma: self.c.gamma,
            boundary_layers: s.layers(),
            kernel: K::KIND.name(),
            viscosity: match s.viscosity {
                Viscosity::Artificial { .. } => "artificial",
                Viscosity::Laminar { .. } => "laminar",
                Viscosity::LaminarSps { .. } => "laminar_sps",
            },
            diffusion: match s.diffusion {
                Diffusion::None => "none",
                Diffusion::Molteni { .. } => "molteni",
                Diffusion::Fourtakas { .. } => "fourtakas",
            },
            integrator: match s.integrator {
                Integrator::Symplectic => "symplectic",
                Integrator::Verlet { .. } => "verlet",
            },
            force_precision: if self.c.pair_f32 { "f32" } else { "f64" },
            boundary: self.walls.name(),
            shifting: s.shifting.map(|sh| sh.coefficient),
            shifting_model: s.shifting.map(|sh| sh.model.name()),
            tensile_correction: s.tensile_correction.map(|t| t.model.name()),
            riemann: s.riemann.map(|r| r.model.name()),
            kernel_correction: s.kernel_correction.map(|k| k.min_eigenvalue),
            dt_floor: self.dt_floor,
        }
    }
    fn interpolate(&self, points: &[Real]) -> Result<Interpolated> {
        if !points.len().is_multiple_of(D::DIM) {
            return Err(Error::invalid("points", format!("length {} is not a multiple of dim = {}", points.len(), D::DIM)));
        }
        if let Some(x) = points.iter().find(|x| !x.is_finite()) {
            return Err(Error::invalid("points", format!("coordinates must be finite, got {x}")));
        }
        let m = points.len() / D::DIM;
        let probes = self.probes();
        let rows: Vec<(Real, Real, Real, D::V)> = (0..m)
            .into_par_iter()
            .map(|i| probes.shepard(D::V::from_slice(&points[i * D::DIM..(i + 1) * D::DIM])))
            .collect();
        let mut out = Interpolated::default();
        for (w, rho, pr, v) in rows {
            out.kernel_sum.push(w);
            out.density.push(rho);
            out.pressure.push(pr);
            out.velocity.extend_from_slice(v.as_slice());
        }
        Ok(out)
    }
    fn gauges(&self) -> &[GaugeRecord] {
        &self.gauges
    }
    fn n_excluded(&self) -> usize {
        self.n_excluded
    }
    fn checkpoint(&self) -> Checkpoint {
        self.checkpoint_state()
    }
    fn restore(&mut self, c: &Checkpoint) -> Result<()> {
        self.restore_state(c)
    }
    fn stop_flag(&self) -> Arc<AtomicBool> {
        Arc::clone(&self.stop)
    }
    fn snapshot_exchange(&self) -> Arc<SnapshotExchange> {
        Arc::clone(&self.snapshots)
    }
}

#[cfg(test)]
mod tests;
