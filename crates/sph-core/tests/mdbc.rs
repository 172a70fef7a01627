//! Modified dynamic boundary condition (English et al. 2022): ghost nodes from the solids'
//! geometry, the hydrostatic wall pressure under still water, the slip modes' wall velocities,
//! a still tank staying still, and results independent of the thread count with a paddle.

use sph_core::geometry::ghost_offsets;
use sph_core::math::Dim2;
use sph_core::{Scene, Solver, WendlandC2};

type Tank2 = Solver<Dim2, WendlandC2>;

/// 0.3 m of water in a 0.6 m x 0.5 m tank at dp = 0.02 m, with a submerged box
/// [0.2, 0.4] x [0.1, 0.2] and what `extra` adds.
fn scene(boundary: &str, extra: &str) -> Scene {
    scene_from(0.0, boundary, extra)
}

/// [`scene`] with the water from `x0` (a paddle's face) on.
fn scene_from(x0: f64, boundary: &str, extra: &str) -> Scene {
    Scene::from_json(&format!(
        r#"{{"dim": 2, "dp": 0.02, "tank": {{"min": [0, 0], "max": [0.6, 0.5]}},
            "fluid": [{{"min": [{x0}, 0], "max": [0.6, 0.3]}}],
            "obstacles": [{{"shape": "box", "min": [0.2, 0.1], "max": [0.4, 0.2]}}],
            "boundary": {boundary} {extra}}}"#
    ))
    .expect("valid scene")
}

fn close(a: glam::DVec2, b: glam::DVec2) -> bool {
    (a - b).length() < 1e-12
}

#[test]
fn ghosts_mirror_each_wall_particle_through_its_fluid_facing_surface() {
    let s = scene(r#"{"model": "mdbc"}"#, "");
    let dp = 0.02;
    let v = glam::DVec2::new;
    let walls = [
        v(0.31, -0.01),  // floor, first layer: up by dp
        v(0.31, -0.05),  // floor, third layer: up by 5 dp
        v(-0.01, 0.11),  // left wall: right by dp
        v(0.61, 0.11),   // right wall: left by dp
        v(-0.01, -0.03), // bottom-left corner: mirrored through the corner
        v(0.29, 0.19),   // box, under its top face: up
        v(0.21, 0.15),   // box, inside its left face: left
        v(0.39, 0.11),   // box, nearest its bottom face: down
        v(0.31, 0.15),   // box, 2.5 dp deep: through the nearest face (the top or bottom)
    ];
    let expected = [
        v(0.0, dp),
        v(0.0, 5.0 * dp),
        v(dp, 0.0),
        v(-dp, 0.0),
        v(2.0 * 0.01, 2.0 * 0.03),
        v(0.0, dp),
        v(-dp, 0.0),
        v(0.0, -dp),
        v(0.0, 5.0 * dp),
    ];
    let got = ghost_offsets::<Dim2>(&s, &walls, false).expect("ghosts");
    for ((w, g), e) in walls.iter().zip(&got).zip(&expected) {
        let ok = close(*g, *e) || (w.x == 0.31 && w.y == 0.15 && close(*g, v(0.0, -5.0 * dp)));
        assert!(ok, "wall particle {w}: ghost offset {g}, expected {e}");
    }
    // a floor particle under the box (its ghost would sit in the box): still mirrored, the
    // floor being its only surface
    assert!(close(
        ghost_offsets::<Dim2>(&s, &[v(0.31, -0.01)], false).expect("ghosts")[0],
        v(0.0, dp)
    ));

    // the paddle's particles mirror through its face, whatever else is near
    let paddle = scene_from(
        0.1,
        r#"{"model": "mdbc"}"#,
        r#", "paddle": {"kind": "piston", "x": 0.1, "law": {"type": "harmonic", "components": [[0.0, 1.0, 0.0]]}}"#,
    );
    let got =
        ghost_offsets::<Dim2>(&paddle, &[v(0.09, 0.01), v(0.05, 0.25)], true).expect("ghosts");
    assert!(
        close(got[0], v(dp, 0.0)) && close(got[1], v(5.0 * dp, 0.0)),
        "{got:?}"
    );
}

#[test]
fn mdbc_walls_carry_the_hydrostatic_pressure() {
    // Under still water the density field is linear in depth, which the first-order corrected
    // interpolation at the ghost and the extrapolation back to the wall particle reproduce:
    // p_w = rho0 g (d - z_w) at the floor, the side walls, the corners and all around the
    // submerged box; wall particles above the water keep rho0.
    for slip in ["wall_velocity", "no_slip", "free_slip"] {
        let mut s = Tank2::new(scene(
            &format!(r#"{{"model": "mdbc", "slip": "{slip}"}}"#),
            "",
        ))
        .expect("solver");
        s.compute_forces();
        let (c, p) = (*s.constants(), s.particles());
        let scale = c.rho0 * c.gravity * 0.3;
        let (mut checked, mut dry, mut worst) = (0, 0, 0.0f64);
        for w in 0..p.fluid_start() {
            let (x, z) = (p.pos[w].x, p.pos[w].y);
            let p_w = c.b_tait * ((p.rho[w] / c.rho0).powf(c.gamma) - 1.0);
            if z > 0.3 + c.support {
                assert_eq!(p.rho[w], c.rho0, "dry wall particle at ({x}, {z})");
                dry += 1;
            } else if z < 0.3 - c.support {
                let hydro = c.rho0 * c.gravity * (0.3 - z);
                worst = worst.max((p_w - hydro).abs() / scale);
                checked += 1;
            }
            // still water: every slip mode shows the fluid a wall at rest
            assert!(
                p.vel[w].length() < 1e-12,
                "{slip}: wall velocity {} at ({x}, {z})",
                p.vel[w]
            );
        }
        assert!(
            worst < 0.005,
            "{slip}: wall pressure off by {worst} rho0 g d"
        );
        assert!(
            checked > 200 && dry > 10,
            "{checked} wet and {dry} dry wall particles checked"
        );
    }
}

#[test]
fn slip_modes_set_the_wall_velocity_from_the_fluid_at_the_ghost() {
    // No gravity, the fluid sliding along +x and sinking at 0.1 m/s: under the middle of the
    // floor the wall shows the fluid -v (no slip: the velocity halfway, on the surface, is the
    // wall's zero), the tangential part with the normal part reversed (free slip), or its own
    // zero.
    let (u, w) = (0.3, -0.1);
    for (slip, expect) in [
        ("wall_velocity", [0.0, 0.0]),
        ("no_slip", [-u, -w]),
        ("free_slip", [u, -w]),
    ] {
        let sc = Scene::from_json(&format!(
            r#"{{"dim": 2, "dp": 0.02, "gravity": 0, "h_swl": 0.3, "tank": {{"min": [0, 0], "max": [0.6, 0.5]}},
                "fluid": [{{"min": [0, 0], "max": [0.6, 0.3]}}], "boundary": {{"model": "mdbc", "slip": "{slip}"}}}}"#
        ))
        .expect("scene");
        let mut s = Tank2::new(sc).expect("solver");
        let fs = s.particles().fluid_start();
        s.particles_mut().vel[fs..]
            .iter_mut()
            .for_each(|v| *v = glam::DVec2::new(u, w));
        s.compute_forces();
        let p = s.particles();
        let floor: Vec<usize> = (0..fs)
            .filter(|&i| p.pos[i].y < 0.0 && p.pos[i].x > 0.15 && p.pos[i].x < 0.45)
            .collect();
        assert!(!floor.is_empty());
        for i in floor {
            let v = p.vel[i];
            assert!(
                (v.x - expect[0]).abs() < 1e-12 && (v.y - expect[1]).abs() < 1e-12,
                "{slip}: {v} at {}",
                p.pos[i]
            );
        }
    }
}

#[test]
fn a_still_tank_with_mdbc_walls_stays_still() {
    // no-slip walls, the mode that changes the walls' velocities most
    let mut sim = sph_core::build(scene(r#"{"model": "mdbc", "slip": "no_slip"}"#, "")).expect("build");
    sim.run_until(0.3).expect("stable");
    let (kinds, vel) = (sim.kinds(), sim.velocities());
    let vmax = (0..sim.n_particles())
        .filter(|&i| kinds[i] == 0)
        .map(|i| (vel[2 * i].powi(2) + vel[2 * i + 1].powi(2)).sqrt())
        .fold(0.0, f64::max);
    assert!(vmax < 0.02 * (9.81f64 * 0.3).sqrt(), "max speed {vmax} m/s");
}

#[test]
fn a_paddle_with_mdbc_walls_gives_the_same_bits_on_any_thread_count() {
    let run = |threads: usize, slip: &str| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        pool.install(|| {
            let sc = scene_from(
                0.1,
                &format!(r#"{{"model": "mdbc", "slip": "{slip}"}}"#),
                r#", "paddle": {"kind": "flap", "x": 0.1, "law": {"type": "harmonic", "components": [[0.02, 6.0, 0.0]]}}"#,
            );
            let mut sim = sph_core::build(sc).expect("build");
            sim.step(60).expect("stable");
            (sim.positions().to_vec(), sim.velocities().to_vec(), sim.densities().to_vec())
        })
    };
    for slip in ["wall_velocity", "free_slip"] {
        let one = run(1, slip);
        let two = run(2, slip);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert!(
            bits(&one.0) == bits(&two.0)
                && bits(&one.1) == bits(&two.1)
                && bits(&one.2) == bits(&two.2),
            "{slip}"
        );
    }
}
