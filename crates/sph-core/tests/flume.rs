//! Wave-maker paddles, damping zone and gauges on small flumes.

use sph_core::{Scene, Simulation};

/// A flume `length` m long with 0.2 m of water (debug builds run these tests: keep them small).
fn flume(length: f64, paddle: &str, gauges: &str) -> Box<dyn Simulation> {
    let json = format!(
        r#"{{"dim": 2, "dp": 0.02, "coefh": 1.2, "tank": {{"min": [-0.1, 0], "max": [{length}, 0.4]}},
            "fluid": [{{"min": [0, 0], "max": [{length}, 0.2]}}],
            "viscosity": {{"model": "artificial", "alpha": 0.01}},
            "paddle": {paddle}, "gauges": [{gauges}]}}"#
    );
    sph_core::build(Scene::from_json(&json).expect("valid scene")).expect("built")
}

/// (x, z, u, w) of the moving particles.
fn paddle_particles(sim: &dyn Simulation) -> Vec<[f64; 4]> {
    let (pos, vel, kinds) = (sim.positions(), sim.velocities(), sim.kinds());
    (0..sim.n_particles())
        .filter(|&i| kinds[i] == 2)
        .map(|i| [pos[2 * i], pos[2 * i + 1], vel[2 * i], vel[2 * i + 1]])
        .collect()
}

#[test]
fn piston_follows_its_table_and_pushes_water() {
    let law = r#"{"kind": "piston", "x": 0.0, "law": {"type": "table", "t": [0, 0.5, 10], "x": [0, 0.05, 0.05]}}"#;
    // 0.6 m of water is enough to see the push next to the paddle
    let mut sim = flume(0.6, law, "");
    let rest = paddle_particles(sim.as_ref());
    assert!(!rest.is_empty());
    assert!(rest.iter().all(|p| p[0] < 0.0 && p[0] > -0.1), "plate behind the face");
    sim.run_until(0.25).expect("stable");
    let t = sim.time();
    let moved = paddle_particles(sim.as_ref());
    let xmax_rest = rest.iter().map(|p| p[0]).fold(f64::MIN, f64::max);
    let xmax = moved.iter().map(|p| p[0]).fold(f64::MIN, f64::max);
    assert!((xmax - xmax_rest - 0.1 * t).abs() < 1e-12, "displacement {}", xmax - xmax_rest);
    assert!(moved.iter().all(|p| (p[2] - 0.1).abs() < 1e-12 && p[3] == 0.0));
    // water next to the paddle moves with it
    let (pos, vel, kinds) = (sim.positions(), sim.velocities(), sim.kinds());
    let near: Vec<f64> =
        (0..sim.n_particles()).filter(|&i| kinds[i] == 0 && pos[2 * i] < 0.1).map(|i| vel[2 * i]).collect();
    let mean = near.iter().sum::<f64>() / near.len() as f64;
    assert!(mean > 0.05, "mean u near the paddle {mean}");
}

#[test]
fn flap_rotates_about_its_hinge() {
    let law = r#"{"kind": "flap", "x": 0.0, "hinge_z": 0.05,
                  "law": {"type": "harmonic", "components": [[0.02, 6.0, 0.0]], "ramp_duration": 0}}"#;
    let mut sim = flume(2.0, law, "");
    sim.step(50).expect("stable");
    let t = sim.time();
    // the face point at the still-water level (0.2 m) has moved by X(t) horizontally up to the arc
    let x_swl = 0.02 * (6.0 * t).sin();
    let theta = (x_swl / 0.15f64).atan();
    for p in paddle_particles(sim.as_ref()) {
        assert!(p[1] >= 0.05 - 0.02, "flap particles sit above the hinge");
        let (rx, rz) = (p[0], p[1] - 0.05);
        let r0 = (rx * rx + rz * rz).sqrt();
        assert!(r0 > 0.0);
        // angular velocity times radius is the speed
        let speed = (p[2] * p[2] + p[3] * p[3]).sqrt();
        let omega = 0.02 * 6.0 * (6.0 * t).cos() * 0.15 / (0.15 * 0.15 + x_swl * x_swl);
        assert!((speed - omega.abs() * r0).abs() < 1e-9);
    }
    // below the hinge the plate is a fixed wall
    let kinds = sim.kinds();
    let pos = sim.positions();
    assert!((0..sim.n_particles()).any(|i| kinds[i] == 1 && pos[2 * i] < 0.0 && pos[2 * i + 1] < 0.05));
    assert!(theta.abs() < 0.2);
}

#[test]
fn gauges_read_still_water() {
    let paddle = r#"{"kind": "piston", "x": 0.0, "law": {"type": "harmonic", "components": []}}"#;
    let gauges = r#"{"type": "elevation", "name": "k", "position": [1.0, 0], "interval": 0.01},
                    {"type": "elevation", "name": "p", "position": [1.0, 0], "method": "particle", "interval": 0.01},
                    {"type": "velocity", "name": "u", "points": [[1.0, 0.1], [1.0, 0.35]], "interval": 0.02},
                    {"type": "window", "name": "w", "min": [0.5, 0.05], "max": [0.7, 0.15], "n": [3, 2], "interval": 0.05},
                    {"type": "runup", "name": "r", "start": [1.5, 0.03], "end": [1.9, 0.39], "interval": 0.01}"#;
    let mut sim = flume(2.0, paddle, gauges);
    sim.run_until(0.1).expect("stable");
    let g = sim.gauges();
    assert_eq!(g.len(), 5);
    let (k, p, u, w, r) = (&g[0], &g[1], &g[2], &g[3], &g[4]);
    assert_eq!(k.t[0], 0.0);
    assert!(k.t.len() >= 10 && k.t.len() <= 12, "{} samples", k.t.len());
    assert!(k.t.windows(2).all(|s| s[1] - s[0] >= 0.01 - 1e-3));
    for &z in &k.values {
        assert!((z - 0.2).abs() < 0.25 * 0.02, "kernel surface {z}");
    }
    for &z in &p.values {
        assert!((z - 0.2).abs() < 0.25 * 0.02, "particle surface {z}");
    }
    assert_eq!(u.width, 6);
    let first = &u.values[..6];
    assert!(first[2] > 0.9 && first[5] == 0.0, "wet point then dry point: {first:?}");
    assert_eq!(w.shape, vec![3, 2]);
    assert_eq!(w.points.len(), 12);
    // the run-up line crosses the still surface at z = 0.2
    assert!(r.values.iter().all(|z| (z - 0.2).abs() < 0.02), "{:?}", r.values);
}

/// The pressure gauge's columns, (pressure, kernel sum) per point, read the hydrostatic
/// pressure `rho0 g (d - z)` in still water and a dry point above it.
#[test]
fn pressure_gauge_reads_the_hydrostatic_pressure() {
    let paddle = r#"{"kind": "piston", "x": 0.0, "law": {"type": "harmonic", "components": []}}"#;
    let gauges = r#"{"type": "pressure", "name": "p", "points": [[1.0, 0.06], [1.0, 0.12], [1.0, 0.35]], "interval": 0.02}"#;
    let mut sim = flume(2.0, paddle, gauges);
    sim.run_until(0.1).expect("stable");
    let p = &sim.gauges()[0];
    assert_eq!((p.kind, p.width, p.points.len()), ("pressure", 6, 6));
    assert_eq!(p.columns.iter().map(|c| c.name).collect::<Vec<_>>(), ["pressure", "kernel_sum"]);
    assert!(p.t.len() >= 5, "{} samples", p.t.len());
    for sample in p.values.chunks(p.width) {
        for (k, z) in [0.06, 0.12].iter().enumerate() {
            let hydrostatic = 1000.0 * 9.81 * (0.2 - z);
            let (pressure, kernel_sum) = (sample[2 * k], sample[2 * k + 1]);
            assert!(kernel_sum > 0.9, "wet point {k}: kernel sum {kernel_sum}");
            assert!((pressure / hydrostatic - 1.0).abs() < 0.03, "point {k}: {pressure} Pa against {hydrostatic}");
        }
        assert_eq!(sample[5], 0.0, "the point above the water is dry");
    }
}

/// The kernel gauge reads still water at its depth next to a side wall and in a corner too:
/// there the walls' particles fill part of the kernel, and the plain fluid sum would put the
/// surface low (it reads a full column as half empty within 2h of a wall).
#[test]
fn kernel_gauges_read_still_water_next_to_walls() {
    let dp = 0.02;
    let gauge = |name: &str, x: f64, y: f64| {
        format!(r#"{{"type": "elevation", "name": "{name}", "position": [{x}, {y}, 0], "interval": 0.01}}"#)
    };
    let gauges = [gauge("centre", 0.1, 0.06), gauge("side", 0.1, 0.5 * dp), gauge("corner", 0.5 * dp, 0.5 * dp)];
    let json = format!(
        r#"{{"dim": 3, "dp": {dp}, "coefh": 1.2, "tank": {{"min": [0, 0, 0], "max": [0.2, 0.12, 0.2]}},
            "fluid": [{{"min": [0, 0, 0], "max": [0.2, 0.12, 0.1]}}],
            "viscosity": {{"model": "artificial", "alpha": 0.01}}, "gauges": [{}]}}"#,
        gauges.join(",")
    );
    let sim = sph_core::build(Scene::from_json(&json).expect("valid scene")).expect("built");
    let read: Vec<f64> = sim.gauges().iter().map(|g| g.values[0]).collect();
    for (g, z) in sim.gauges().iter().zip(&read) {
        assert!((z - 0.1).abs() < 0.25 * dp, "{} reads {z}, water is 0.1 m deep", g.name);
    }
    assert!((read[1] - read[0]).abs() < 0.1 * dp && (read[2] - read[0]).abs() < 0.1 * dp, "{read:?}");
}

#[test]
fn bad_flume_fields_are_named() {
    let cases = [
        (r#"{"kind": "piston", "x": 0.0, "law": {"type": "table", "t": [0, 1], "x": [0, 1, 2]}}"#, "paddle.law.x"),
        (r#"{"kind": "piston", "x": -0.05, "law": {"type": "harmonic", "components": []}}"#, "paddle.x"),
        (r#"{"kind": "piston", "x": 0.5, "law": {"type": "harmonic", "components": []}}"#, "fluid[0]"),
    ];
    for (paddle, field) in cases {
        let json = format!(
            r#"{{"dim": 2, "dp": 0.02, "tank": {{"min": [-0.1, 0], "max": [2.0, 0.4]}},
                "fluid": [{{"min": [0, 0], "max": [2.0, 0.2]}}], "paddle": {paddle}}}"#
        );
        match Scene::from_json(&json) {
            Err(sph_core::Error::InvalidScene { field: f, .. }) => assert_eq!(f, field),
            other => panic!("{field}: {other:?}"),
        }
    }
    let json = r#"{"dim": 2, "dp": 0.02, "tank": {"min": [0, 0], "max": [2.0, 0.4]},
        "fluid": [{"min": [0, 0], "max": [2.0, 0.2]}],
        "gauges": [{"type": "elevation", "name": "far", "position": [3.0, 0], "interval": 0.1}]}"#;
    assert!(matches!(Scene::from_json(json), Err(sph_core::Error::InvalidScene { field, .. }) if field == "gauges[0].position"));
}

/// The three run-up methods on a film one particle thick climbing the right-hand wall (x = 0.4)
/// from the still water (0.1 m) to z = 0.2 m (particles up to 0.19 m), with a detached drop at
/// z = 0.31 m, 2.5 dp off the wall: the wet front follows the film to its top and ignores the drop; the particle method,
/// which takes any particle near its line, reads the drop; the kernel method, whose line lies
/// 1.5 dp off the wall, does not see the film.
#[test]
fn wet_front_runup_follows_a_thin_film_and_ignores_a_drop() {
    let dp = 0.02;
    let x_line = 0.4 - 1.5 * dp;
    let gauge = |name: &str, method: &str| {
        format!(r#"{{"type": "runup", "name": "{name}", "start": [{x_line}, 0.02], "end": [{x_line}, 0.38], "method": "{method}", "interval": 0.01}}"#)
    };
    let gauges = [gauge("k", "kernel"), gauge("p", "particle"), gauge("w", "wet_front")].join(", ");
    let json = format!(
        r#"{{"dim": 2, "dp": {dp}, "coefh": 1.2, "h_swl": 0.1, "tank": {{"min": [0, 0], "max": [0.4, 0.4]}},
            "fluid": [{{"min": [0, 0], "max": [0.4, 0.1]}}, {{"min": [0.375, 0.1], "max": [0.4, 0.2]}},
                      {{"min": [0.335, 0.295], "max": [0.365, 0.325]}}],
            "viscosity": {{"model": "artificial", "alpha": 0.01}}, "gauges": [{gauges}]}}"#
    );
    let sim = sph_core::build(Scene::from_json(&json).expect("valid scene")).expect("built");
    let g = sim.gauges();
    let (k, p, w) = (g[0].values[0], g[1].values[0], g[2].values[0]);
    assert!((w - 0.19).abs() < 1e-9, "wet front at the film's top particle: {w}");
    assert!((p - 0.31).abs() < 1e-9, "the particle method reads the drop: {p}");
    assert!(k < 0.15, "the kernel line does not see the film: {k}");
}
