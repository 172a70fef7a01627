//! Force gauges: the fluid's force on a submerged box in still water is its buoyancy
//! (Archimedes: `rho0 g V` upwards, no horizontal force), with DBC and Adami walls.

use sph_core::math::Dim2;
use sph_core::physics::{DIFF_FOURTAKAS, VISC_ARTIFICIAL};
use sph_core::{Scene, Simulation, Solver, WendlandC2};

/// The submerged box [m]: 10 x 6 dp, its top 8 dp below the surface, its bottom 6 dp above the
/// floor, so that no kernel support reaches from the box to the floor or the surface.
const BOX: ([f64; 2], [f64; 2]) = ([0.2, 0.12], [0.4, 0.24]);

fn tank_with_box(boundary: &str) -> Scene {
    let ([x0, z0], [x1, z1]) = BOX;
    Scene::from_json(&format!(
        r#"{{"dim": 2, "dp": 0.02, "tank": {{"min": [0, 0], "max": [0.6, 0.5]}},
            "fluid": [{{"min": [0, 0], "max": [0.6, 0.4]}}],
            "diffusion": {{"model": "fourtakas"}}, "boundary": {{"model": "{boundary}"}},
            "obstacles": [{{"shape": "box", "min": [{x0}, {z0}], "max": [{x1}, {z1}]}}],
            "gauges": [{{"type": "force", "name": "box", "obstacle": 0, "point": [0.3, 0.18], "interval": 0.01}}]}}"#
    ))
    .expect("valid scene")
}

/// Mean force and moment over the samples from `from` [s] on.
fn mean_after(sim: &dyn Simulation, from: f64) -> (f64, f64, f64) {
    let g = &sim.gauges()[0];
    let rows: Vec<&[f64]> = g.t.iter().zip(g.values.chunks_exact(g.width)).filter(|(t, _)| **t >= from).map(|(_, v)| v).collect();
    let n = rows.len() as f64;
    let mean = |k: usize| rows.iter().map(|v| v[k]).sum::<f64>() / n;
    (mean(0), mean(1), mean(2))
}

#[test]
fn a_submerged_box_feels_its_buoyancy() {
    let ([x0, z0], [x1, z1]) = BOX;
    let buoyancy = 1000.0 * 9.81 * (x1 - x0) * (z1 - z0);
    for boundary in ["dbc", "adami"] {
        let mut sim = Solver::<Dim2, WendlandC2, VISC_ARTIFICIAL, DIFF_FOURTAKAS>::new(tank_with_box(boundary)).expect("solver");
        sim.run_until(0.1).expect("stable");
        let g = &sim.gauges()[0];
        assert_eq!((g.kind, g.width), ("force", 3));
        let (fx, fz, my) = mean_after(&sim, 0.02);
        println!("{boundary}: Fx {fx:.3} N/m, Fz {fz:.3} N/m ({:+.2} % of rho g V = {buoyancy:.3}), My {my:.4} N m/m", 100.0 * (fz / buoyancy - 1.0));
        assert!((fz / buoyancy - 1.0).abs() < 0.02, "{boundary}: Fz {fz} against {buoyancy}");
        assert!(fx.abs() < 0.01 * buoyancy && my.abs() < 0.01 * buoyancy * 0.1, "{boundary}: Fx {fx}, My {my}");
    }
}

#[test]
fn a_force_gauge_must_name_an_existing_obstacle() {
    let json = tank_with_box("dbc").to_json();
    let none = json.replace(r#""obstacle":0,"#, "");
    let unknown = json.replace(r#""obstacle":0,"#, r#""obstacle":3,"#);
    for (text, reason) in [(none, "needs the index"), (unknown, "no obstacle 3")] {
        match Scene::from_json(&text) {
            Err(sph_core::Error::InvalidScene { field, reason: r }) => {
                assert_eq!(field, "gauges[0].obstacle");
                assert!(r.contains(reason), "{r}");
            }
            other => panic!("expected a refusal, got {other:?}"),
        }
    }
}
