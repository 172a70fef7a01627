//! Stopping a run from outside, gauge intervals below the time step, and checkpoints whose state
//! no run can reach: each one stops or is refused with the field named, none hangs or panics.

use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use proptest::prelude::*;
use sph_core::{Checkpoint, Error, Simulation};

fn tank_with_gauge(interval: f64) -> sph_core::Result<Box<dyn Simulation>> {
    let json = format!(
        r#"{{"dim": 2, "dp": 0.02, "tank": {{"min": [0, 0], "max": [0.6, 0.5]}},
            "fluid": [{{"min": [0, 0], "max": [0.3, 0.3]}}],
            "gauges": [{{"type": "elevation", "name": "g", "position": [0.1, 0], "interval": {interval:e}}}]}}"#
    );
    sph_core::build_from_json(&json)
}

fn sim() -> Box<dyn Simulation> {
    tank_with_gauge(0.01).expect("build")
}

fn refused_field<T>(result: sph_core::Result<T>) -> String {
    match result {
        Err(Error::InvalidScene { field, .. }) => field,
        Err(other) => panic!("expected a refusal, got {other:?}"),
        Ok(_) => panic!("expected a refusal, it was accepted"),
    }
}

#[test]
fn stop_flag_stops_between_steps_and_the_run_continues_bit_for_bit() {
    let mut whole = sim();
    whole.step(10).expect("stable");
    let mut parts = sim();
    parts.step(4).expect("stable");
    let stop = parts.stop_flag();
    stop.store(true, Ordering::Relaxed);
    assert_eq!(parts.step(3), Err(Error::Interrupted { step: 4, time: parts.time() }));
    assert!(matches!(parts.run_until(1.0), Err(Error::Interrupted { step: 4, .. })));
    stop.store(false, Ordering::Relaxed);
    let saved = parts.checkpoint();
    let mut resumed = sim();
    resumed.restore(&saved).expect("restore");
    resumed.step(6).expect("stable");
    assert_eq!(whole.time().to_bits(), resumed.time().to_bits());
    assert_eq!(whole.positions(), resumed.positions());
    assert_eq!(whole.gauges()[0].t, resumed.gauges()[0].t);
}

#[test]
fn stop_flag_set_from_another_thread_ends_a_long_run() {
    let mut s = sim();
    let stop = s.stop_flag();
    let setter = std::thread::spawn(move || {
        std::thread::sleep(Duration::from_millis(200));
        stop.store(true, Ordering::Relaxed);
        Instant::now()
    });
    let result = s.run_until(1e6);
    let stopped = Instant::now();
    let set = setter.join().expect("setter");
    assert!(matches!(result, Err(Error::Interrupted { .. })), "{result:?}");
    assert!(stopped.duration_since(set) < Duration::from_secs(1));
}

#[test]
fn gauge_interval_below_the_time_step_floor_is_refused() {
    for interval in [1e-20, 1e-12, 1e-300] {
        assert_eq!(refused_field(tank_with_gauge(interval)), "gauges[0].interval");
    }
    // just above the floor it samples every step, with a bounded catch-up
    let floor = sim().params().dt_floor;
    let mut s = tank_with_gauge(1.01 * floor).expect("build");
    s.step(5).expect("stable");
    assert_eq!(s.gauges()[0].t.len(), 6);
}

/// The checkpoint of a short run, mutated by `spoil`, restored into a fresh run of the scene.
fn restore_spoiled(spoil: impl FnOnce(&mut Checkpoint)) -> String {
    let mut s = sim();
    s.step(3).expect("stable");
    let mut c = s.checkpoint();
    spoil(&mut c);
    refused_field(sim().restore(&c))
}

fn first_fluid(c: &Checkpoint) -> usize {
    c.kinds.iter().position(|&k| k == 0).expect("fluid")
}

#[test]
fn inconsistent_checkpoints_are_refused_naming_the_field() {
    assert_eq!(restore_spoiled(|c| c.time = f64::NAN), "checkpoint.time");
    assert_eq!(restore_spoiled(|c| c.time = f64::INFINITY), "checkpoint.time");
    assert_eq!(restore_spoiled(|c| c.dt = f64::NAN), "checkpoint.dt");
    assert_eq!(restore_spoiled(|c| c.energy0.0 = f64::NAN), "checkpoint.energy0");
    assert_eq!(restore_spoiled(|c| c.n_excluded = c.kinds.len() + 1), "checkpoint.n_excluded");
    assert_eq!(restore_spoiled(|c| c.gauges[0].next_time = f64::NEG_INFINITY), "checkpoint.gauges[0].next_time");
    assert_eq!(restore_spoiled(|c| c.gauges[0].next_time = f64::NAN), "checkpoint.gauges[0].next_time");
    assert_eq!(restore_spoiled(|c| c.gauges[0].t.push(1.0)), "checkpoint.gauges[0].values");
    assert_eq!(restore_spoiled(|c| c.gauges[0].values.clear()), "checkpoint.gauges[0].values");
    assert_eq!(restore_spoiled(|c| c.gauges[0].t[0] = f64::NAN), "checkpoint.gauges[0].t");
    assert_eq!(
        restore_spoiled(|c| {
            let slot = first_fluid(c);
            c.kinds[slot] = 3;
        }),
        "checkpoint.n_excluded"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn duplicate_ids_are_refused(a in 0usize..10_000, b in 0usize..10_000) {
        let field = restore_spoiled(|c| {
            let n = c.ids.len();
            let (a, b) = (a % n, b % n);
            let b = if a == b { (b + 1) % n } else { b };
            c.ids[b] = c.ids[a];
        });
        prop_assert_eq!(field, "checkpoint.ids");
    }

    #[test]
    fn unknown_or_misplaced_kinds_are_refused(slot in 0usize..10_000, kind in 0u8..=255) {
        let field = restore_spoiled(|c| {
            let slot = slot % c.kinds.len();
            let fluid = slot >= first_fluid(c);
            // a kind no slot of this group may hold
            c.kinds[slot] = if fluid { kind.max(1).min(2) } else if kind == 1 { 0 } else { kind };
        });
        prop_assert_eq!(field, "checkpoint.kinds");
    }
}
