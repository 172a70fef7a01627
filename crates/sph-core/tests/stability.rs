//! Monitors that stop a run, and checkpoints that continue it exactly.

use sph_core::{Error, InstabilityKind, Scene, Simulation};

fn tank(dim: usize, extra: &str) -> Scene {
    let json = if dim == 2 {
        format!(
            r#"{{"dim": 2, "dp": 0.02, "tank": {{"min": [0, 0], "max": [0.6, 0.5]}},
                "fluid": [{{"min": [0, 0], "max": [0.3, 0.3]}}] {extra}}}"#
        )
    } else {
        format!(
            r#"{{"dim": 3, "dp": 0.04, "tank": {{"min": [0, 0, 0], "max": [0.6, 0.2, 0.5]}},
                "fluid": [{{"min": [0, 0, 0], "max": [0.3, 0.2, 0.3]}}] {extra}}}"#
        )
    };
    Scene::from_json(&json).expect("valid scene")
}

fn state_bits(sim: &dyn Simulation) -> Vec<u64> {
    let mut order: Vec<usize> = (0..sim.n_particles()).collect();
    order.sort_by_key(|&i| sim.ids()[i]);
    let d = sim.dim();
    let mut out = Vec::new();
    for &i in &order {
        out.extend(sim.positions()[i * d..(i + 1) * d].iter().map(|x| x.to_bits()));
        out.extend(sim.velocities()[i * d..(i + 1) * d].iter().map(|x| x.to_bits()));
        out.push(sim.densities()[i].to_bits());
    }
    out
}

#[test]
fn restart_continues_bit_for_bit() {
    for dim in [2, 3] {
        for integrator in [r#"{"scheme": "symplectic"}"#, r#"{"scheme": "verlet", "euler_every": 7}"#] {
            // a collapsing column, so that the state changes a lot between the halves
            let scene = tank(dim, &format!(r#", "integrator": {integrator}"#));
            let mut whole = sph_core::build(scene.clone()).expect("build");
            whole.step(40).expect("stable");
            let mut first = sph_core::build(scene.clone()).expect("build");
            first.step(23).expect("stable");
            let saved = first.checkpoint();
            drop(first);
            let mut second = sph_core::build(scene).expect("build");
            second.restore(&saved).expect("restore");
            second.step(17).expect("stable");
            assert_eq!(whole.time().to_bits(), second.time().to_bits(), "dim {dim} {integrator}");
            assert!(state_bits(whole.as_ref()) == state_bits(second.as_ref()), "dim {dim} {integrator}");
        }
    }
}

#[test]
fn checkpoint_from_another_scene_is_refused() {
    let mut a = sph_core::build(tank(2, "")).expect("build");
    let b = sph_core::build(tank(3, "")).expect("build");
    match a.restore(&b.checkpoint()) {
        Err(Error::InvalidScene { field, .. }) => assert!(field.starts_with("checkpoint.")),
        other => panic!("{other:?}"),
    }
}

fn expect_instability(result: sph_core::Result<()>, want: InstabilityKind) -> (u32, Vec<f64>, u64) {
    match result {
        Err(Error::Instability { kind, particle, position, step, .. }) => {
            assert_eq!(kind, want);
            (particle, position, step)
        }
        other => panic!("expected {want:?}, got {other:?}"),
    }
}

#[test]
fn injected_nan_stops_the_run_naming_the_particle() {
    let mut sim = sph_core::build(tank(2, "")).expect("build");
    sim.step(3).expect("stable");
    let mut c = sim.checkpoint();
    let slot = c.kinds.iter().position(|&k| k == 0).expect("fluid") + 5;
    let id = c.ids[slot];
    c.velocities[2 * slot] = f64::NAN;
    sim.restore(&c).expect("restore");
    let (particle, _, step) = expect_instability(sim.step(5), InstabilityKind::NonFinite);
    assert_eq!(step, 4);
    // the NaN spreads to neighbours within the step; the lowest id among them is reported
    assert!(particle <= id);
}

#[test]
fn a_particle_outside_the_domain_is_excluded_or_stops_the_run() {
    for (limit, stops) in [(0.0, true), (0.01, false)] {
        let mut sim = sph_core::build(tank(2, &format!(r#", "lost_fraction_limit": {limit}"#))).expect("build");
        let mut c = sim.checkpoint();
        let slot = c.kinds.iter().rposition(|&k| k == 0).expect("fluid");
        c.positions[2 * slot] = 5.0;
        sim.restore(&c).expect("restore");
        let result = sim.step(2);
        if stops {
            let (particle, position, _) = expect_instability(result, InstabilityKind::OutOfDomain);
            assert_eq!(particle, c.ids[slot]);
            assert_eq!(position[0], 5.0);
        } else {
            result.expect("one lost particle is within the limit");
            assert_eq!(sim.n_excluded(), 1);
            let i = sim.ids().iter().position(|&id| id == c.ids[slot]).expect("still there");
            assert_eq!(sim.kinds()[i], 3);
            assert_eq!(sim.positions()[2 * i], 5.0, "frozen");
        }
    }
}

#[test]
fn energy_growing_without_forcing_stops_the_run() {
    let mut sim = sph_core::build(tank(2, "")).expect("build");
    let mut c = sim.checkpoint();
    for (i, k) in c.kinds.iter().enumerate() {
        if *k == 0 {
            c.velocities[2 * i + 1] = 0.6;
        }
    }
    sim.restore(&c).expect("restore");
    expect_instability(sim.step(60), InstabilityKind::EnergyGrowth);
}
