//! Overtopping gauges: a block of water released towards a section (a dam break) has sent
//! across it exactly the volume of the particles that end past it, the discharge adds up to
//! that volume, and a run resumed from a checkpoint records the same volumes bit for bit.

use sph_core::math::Dim2;
use sph_core::particles::{KIND_EXCLUDED, KIND_FLUID};
use sph_core::{Scene, Simulation, Solver, WendlandC2};

const DP: f64 = 0.04;
const SECTION: f64 = 0.7;

type DamBreak = Solver<Dim2, WendlandC2>;

fn dam_break() -> DamBreak {
    let scene = Scene::from_json(&dam_break_json_with_section(SECTION)).expect("valid scene");
    DamBreak::new(scene).expect("solver")
}

/// The fluid particles past the section now.
fn past_section(sim: &dyn Simulation) -> usize {
    let (pos, kind) = (sim.positions(), sim.kinds());
    kind.iter()
        .enumerate()
        .filter(|&(i, &k)| (k == KIND_FLUID || k == KIND_EXCLUDED) && pos[2 * i] > SECTION)
        .count()
}

#[test]
fn the_crossed_volume_is_the_volume_of_the_particles_past_the_section() {
    let mut sim = dam_break();
    sim.run_until(0.6).expect("stable");
    let g = &sim.gauges()[0];
    assert_eq!((g.kind, g.width), ("overtopping", 2));
    let volume: Vec<f64> = g.values.chunks_exact(2).map(|v| v[0]).collect();
    let discharge: Vec<f64> = g.values.chunks_exact(2).map(|v| v[1]).collect();
    let past = past_section(&sim);
    let expected = past as f64 * DP * DP;
    let last = *volume.last().expect("samples");
    println!("{past} particles past x = {SECTION}: {expected:.5} m^2/m; gauge {last:.5} m^2/m over {} samples", g.t.len());
    assert!(past > 20, "the surge must have crossed the section, {past} particles did");
    assert!((last - expected).abs() < 1e-12 * expected, "{last} against {expected}");
    assert_eq!(volume[0], 0.0);
    // each sample's discharge is over the interval since the one before
    let summed: f64 = discharge[1..].iter().zip(g.t.windows(2)).map(|(q, w)| q * (w[1] - w[0])).sum();
    assert!((summed - last).abs() < 1e-9, "the discharge adds up to {summed}, not {last}");
}

#[test]
fn a_resumed_run_records_the_same_overtopping() {
    let mut whole = dam_break();
    whole.run_until(0.5).expect("stable");
    let mut first = dam_break();
    first.run_until(0.3).expect("stable");
    let checkpoint = first.checkpoint();
    assert!(!checkpoint.gauges[0].crossings.past.is_empty());
    let mut resumed = dam_break();
    resumed.restore(&checkpoint).expect("restore");
    resumed.run_until(0.5).expect("stable");
    let (a, b) = (&whole.gauges()[0], &resumed.gauges()[0]);
    assert_eq!(a.t, b.t);
    assert_eq!(a.values.iter().map(|v| v.to_bits()).collect::<Vec<_>>(), b.values.iter().map(|v| v.to_bits()).collect::<Vec<_>>());
    assert_eq!(a.crossings, b.crossings);
}

#[test]
fn a_section_outside_the_tank_is_refused() {
    let json = dam_break_json_with_section(5.0);
    match Scene::from_json(&json) {
        Err(sph_core::Error::InvalidScene { field, .. }) => assert_eq!(field, "gauges[0].x"),
        other => panic!("expected a refusal, got {other:?}"),
    }
}

fn dam_break_json_with_section(x: f64) -> String {
    format!(
        r#"{{"dim": 2, "dp": {DP}, "tank": {{"min": [0, 0], "max": [1.6, 0.8]}},
            "fluid": [{{"min": [0, 0], "max": [0.4, 0.4]}}],
            "gauges": [{{"type": "overtopping", "name": "q", "x": {x}, "interval": 0.02}}]}}"#
    )
}
