//! Behaviour of the physics terms on small scenes: signs of the diffusion terms, a still tank
//! staying still, and results independent of the thread count.

use sph_core::math::{Dim2, Vector};
use sph_core::{Scene, Solver, WendlandC2};

fn tank(extra: &str) -> Scene {
    tank_at(0.02, extra)
}

/// 0.3 m of water in a 0.6 m x 0.5 m tank at particle spacing `dp`.
fn tank_at(dp: f64, extra: &str) -> Scene {
    Scene::from_json(&format!(
        r#"{{"dim": 2, "dp": {dp}, "tank": {{"min": [0, 0], "max": [0.6, 0.5]}},
            "fluid": [{{"min": [0, 0], "max": [0.6, 0.3]}}] {extra}}}"#
    ))
    .expect("valid scene")
}

/// Index of the fluid particle nearest to `(x, z)`.
fn nearest<D: sph_core::Dim>(pos: &[D::V], from: usize, x: f64, z: f64) -> usize {
    (from..pos.len())
        .min_by(|&a, &b| {
            let da = (pos[a].get(0) - x).powi(2) + (pos[a].vertical() - z).powi(2);
            let db = (pos[b].get(0) - x).powi(2) + (pos[b].vertical() - z).powi(2);
            da.total_cmp(&db)
        })
        .expect("fluid particles")
}

#[test]
fn density_bump_spreads_under_molteni_diffusion() {
    // No gravity: uniform density, one particle denser. Diffusion must lower its density and
    // raise its neighbours'; without the bump every rate is zero.
    let scene = tank(r#", "gravity": 0.0, "diffusion": {"model": "molteni", "delta": 0.1}, "h_swl": 0.3"#);
    let mut s = Solver::<Dim2, WendlandC2>::new(scene).expect("solver");
    let fs = s.particles().fluid_start();
    let rho0 = s.constants().rho0;
    s.particles_mut().rho.iter_mut().for_each(|r| *r = rho0);
    s.compute_forces();
    let quiet = s.particles().drho[fs..].iter().fold(0.0f64, |m, d| m.max(d.abs()));
    assert!(quiet < 1e-9, "uniform density must not diffuse: {quiet}");

    let a = nearest::<Dim2>(&s.particles().pos, fs, 0.3, 0.15);
    s.particles_mut().rho[a] = rho0 * 1.01;
    let pa = s.particles().pos[a];
    s.compute_forces();
    // compute_forces re-sorts; find the particle again by position.
    let p = s.particles();
    let a2 = (fs..p.len()).find(|&i| p.pos[i] == pa).expect("bumped particle");
    // continuity is zero at rest, so drho is the diffusion term alone
    assert!(p.drho[a2] < 0.0, "bump must decay, drho = {}", p.drho[a2]);
    let support = s.constants().support;
    let neighbours: Vec<usize> =
        (fs..p.len()).filter(|&i| i != a2 && (p.pos[i] - pa).length() < support).collect();
    assert!(neighbours.iter().all(|&i| p.drho[i] > 0.0), "neighbours must gain density");
}

#[test]
fn fourtakas_diffusion_vanishes_on_a_hydrostatic_column() {
    let scene = tank(r#", "diffusion": {"model": "fourtakas", "delta": 0.1}"#);
    let mut s = Solver::<Dim2, WendlandC2>::new(scene.clone()).expect("solver");
    let scene_m = tank(r#", "diffusion": {"model": "molteni", "delta": 0.1}"#);
    let mut m = Solver::<Dim2, WendlandC2>::new(scene_m).expect("solver");
    s.compute_forces();
    m.compute_forces();
    // Interior particles (away from the walls and the free surface) at rest in hydrostatic
    // balance: Fourtakas' term is (almost) zero, Molteni's is not.
    let interior = |p: &sph_core::particles::Particles<Dim2>, i: usize| {
        let x = p.pos[i].x;
        let z = p.pos[i].y;
        x > 0.1 && x < 0.5 && z > 0.1 && z < 0.2
    };
    let max_rate = |p: &sph_core::particles::Particles<Dim2>| {
        (p.fluid_start()..p.len()).filter(|&i| interior(p, i)).map(|i| p.drho[i].abs()).fold(0.0, f64::max)
    };
    let (f, mo) = (max_rate(s.particles()), max_rate(m.particles()));
    assert!(f < 0.02 * mo, "Fourtakas {f} vs Molteni {mo}");
}

fn run_tank(threads: usize, extra: &str) -> (Vec<f64>, Vec<u32>) {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
    pool.install(|| {
        let mut sim = sph_core::build(tank(extra)).expect("build");
        sim.step(60).expect("stable");
        (sim.positions().to_vec(), sim.ids().to_vec())
    })
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    for extra in [
        "",
        r#", "shifting": {}"#,
        r#", "shifting": {"model": "delta_plus"}"#,
        r#", "boundary": {"model": "adami"}"#,
        r#", "force_precision": "f32""#,
        r#", "kernel": "wendland_c4""#,
        r#", "riemann": {}, "viscosity": {"model": "laminar"}, "diffusion": {"model": "none"}"#,
        r#", "riemann": {}, "viscosity": {"model": "laminar_sps"}, "diffusion": {"model": "none"}"#,
        r#", "kernel_correction": {}"#,
        r#", "kernel_correction": {}, "viscosity": {"model": "laminar_sps"}"#,
    ] {
        let (p1, i1) = run_tank(1, extra);
        let (p2, i2) = run_tank(2, extra);
        let (p3, i3) = run_tank(3, extra);
        assert_eq!(i1, i2);
        assert_eq!(i1, i3);
        assert!(p1.iter().zip(&p2).all(|(a, b)| a.to_bits() == b.to_bits()), "{extra}");
        assert!(p1.iter().zip(&p3).all(|(a, b)| a.to_bits() == b.to_bits()), "{extra}");
    }
}

#[test]
fn adami_walls_carry_the_hydrostatic_pressure() {
    // Adami et al. (2012) Eq. 27: under still water a wall particle's pressure is the fluid's
    // extrapolated to it, p = rho0 g (d - z_w), below the floor and behind the side walls alike;
    // wall particles above the water get rho0 (no pressure).
    let scene = tank(r#", "boundary": {"model": "adami"}"#);
    let mut s = Solver::<Dim2, WendlandC2>::new(scene).expect("solver");
    s.compute_forces();
    let (c, p) = (*s.constants(), s.particles());
    let (mut checked, mut dry) = (0, 0);
    // the two wall layers next to the floor (away from the corners) and the side walls
    let d2 = 2.0 * c.dp;
    let inner_layers = |x: f64, z: f64| {
        (z > -d2 && z < 0.0 && x > 0.1 && x < 0.5) || (z > 0.0 && ((x > -d2 && x < 0.0) || (x > 0.6 && x < 0.6 + d2)))
    };
    for w in 0..p.fluid_start() {
        let (x, z) = (p.pos[w].x, p.pos[w].y);
        let p_w = c.b_tait * ((p.rho[w] / c.rho0).powf(c.gamma) - 1.0);
        if z > 0.3 + c.support {
            assert_eq!(p.rho[w], c.rho0, "dry wall particle at ({x}, {z})");
            dry += 1;
        } else if inner_layers(x, z) && z < 0.25 {
            let hydro = c.rho0 * c.gravity * (0.3 - z);
            assert!((p_w - hydro).abs() < 0.01 * c.rho0 * c.gravity * 0.3, "({x}, {z}): {p_w} Pa vs {hydro} Pa");
            checked += 1;
        }
    }
    assert!(checked > 50 && dry > 10, "{checked} wet and {dry} dry wall particles checked");
}

/// Spread (standard deviation over mean) of the fluid's kernel volume sum at the fluid
/// particles at least `margin` inside the box `[lo, hi]` (away from walls and surface).
fn concentration_spread(sim: &dyn sph_core::Simulation, lo: [f64; 2], hi: [f64; 2], margin: f64) -> f64 {
    let (pos, kinds) = (sim.positions(), sim.kinds());
    let pts: Vec<f64> = (0..sim.n_particles())
        .filter(|&i| kinds[i] == 0)
        .filter(|&i| (0..2).all(|k| pos[2 * i + k] > lo[k] + margin && pos[2 * i + k] < hi[k] - margin))
        .flat_map(|i| [pos[2 * i], pos[2 * i + 1]])
        .collect();
    let c = sim.interpolate(&pts).expect("interpolate").kernel_sum;
    let mean = c.iter().sum::<f64>() / c.len() as f64;
    (c.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / c.len() as f64).sqrt() / mean
}

#[test]
fn shifting_evens_out_a_disordered_particle_set() {
    // Water circulating at 0.2 m/s, its particles displaced by up to 0.25 dp:
    // shifting (D = A h |u| dt) must leave the concentration more uniform than the flow alone.
    let dp = 0.03;
    let run = |extra: &str| {
        let scene = tank_at(dp, extra);
        let mut s = Solver::<Dim2, WendlandC2>::new(scene).expect("solver");
        let fs = s.particles().fluid_start();
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 0.5 * dp
        };
        let p = s.particles_mut();
        for (x, v) in p.pos[fs..].iter_mut().zip(&mut p.vel[fs..]) {
            *x += glam::DVec2::new(next(), next());
            // a divergence-free circulation of 0.2 m/s (Taylor-Green cells of the tank's size)
            let (kx, kz) = (std::f64::consts::PI / 0.6, std::f64::consts::PI / 0.3);
            *v = 0.2 * glam::DVec2::new((kx * x.x).sin() * (kz * x.y).cos(), -(kx / kz) * (kx * x.x).cos() * (kz * x.y).sin());
        }
        use sph_core::Simulation;
        let before = concentration_spread(&s, [0.0, 0.0], [0.6, 0.3], 0.08);
        s.step(150).expect("stable");
        (before, concentration_spread(&s, [0.0, 0.0], [0.6, 0.3], 0.08))
    };
    let (before, plain) = run("");
    let (same_start, shifted) = run(r#", "shifting": {"coefficient": 2}"#);
    assert_eq!(before.to_bits(), same_start.to_bits());
    assert!(shifted < 0.8 * plain, "spread: {before:.5} at the start, {plain:.5} without shifting, {shifted:.5} with");
    // the delta-plus-SPH shifting (Sun et al. 2017) evens it out as well
    let (_, delta_plus) = run(r#", "shifting": {"model": "delta_plus", "coefficient": 4}"#);
    assert!(delta_plus < 0.8 * plain, "spread: {plain:.5} without shifting, {delta_plus:.5} with delta-plus");
}

#[test]
fn still_tank_stays_still_for_half_a_second() {
    // dp 0.03 (10 layers): half a second is about 1,000 steps, which a debug build runs in seconds
    let runs = [
        r#", "integrator": {"scheme": "symplectic"}"#,
        r#", "integrator": {"scheme": "verlet"}"#,
        r#", "integrator": {"scheme": "verlet"}, "boundary": {"model": "adami"}"#,
        r#", "integrator": {"scheme": "symplectic"}, "riemann": {}, "viscosity": {"model": "laminar"}, "diffusion": {"model": "none"}"#,
        r#", "integrator": {"scheme": "verlet"}, "kernel_correction": {}"#,
    ];
    for integrator in runs {
        let mut sim = sph_core::build(tank_at(0.03, integrator)).expect("build");
        sim.run_until(0.5).expect("stable");
        let kinds = sim.kinds();
        let vel = sim.velocities();
        let vmax = (0..sim.n_particles())
            .filter(|&i| kinds[i] == 0)
            .map(|i| (vel[2 * i].powi(2) + vel[2 * i + 1].powi(2)).sqrt())
            .fold(0.0, f64::max);
        let scale = (9.81f64 * 0.3).sqrt();
        assert!(vmax < 0.02 * scale, "{integrator}: max speed {vmax} m/s");
    }
}

const RIEMANN: &str = r#", "riemann": {"limiter": LIMITER}, "viscosity": {"model": "laminar", "nu": 1e-4}, "diffusion": {"model": "none"}"#;

/// The Riemann solver (`physics/riemann.rs`) at uniform density, without its limiter, is the
/// classic loop: `U* - U_a = (U_b - U_a) / 2` and `P* = (P_a + P_b) / 2` there. With the limiter
/// it adds a repulsion to approaching pairs only.
#[test]
fn riemann_without_dissipation_is_the_classic_loop_at_uniform_density() {
    let classic = tank(r#", "gravity": 0.0, "h_swl": 0.3, "viscosity": {"model": "laminar", "nu": 1e-4}, "diffusion": {"model": "none"}"#);
    let run = |scene: Scene| {
        let mut s = Solver::<Dim2, WendlandC2>::new(scene).expect("solver");
        let fs = s.particles().fluid_start();
        let rho0 = s.constants().rho0;
        let p = s.particles_mut();
        p.rho.iter_mut().for_each(|r| *r = rho0 * 1.001);
        // a converging and shearing velocity field
        for i in fs..p.len() {
            let (x, z) = (p.pos[i].x, p.pos[i].y);
            p.vel[i] = sph_core::math::Vector::from_slice(&[-(x - 0.3) + 0.5 * z, 0.2 * (z - 0.15)]);
        }
        s.compute_forces();
        let p = s.particles();
        let mut by_pos: Vec<_> = (fs..p.len()).map(|i| (p.pos[i].x, p.pos[i].y, p.acc[i - fs].x, p.acc[i - fs].y, p.drho[i])).collect();
        by_pos.sort_by(|a, b| (a.0, a.1).partial_cmp(&(b.0, b.1)).expect("finite"));
        by_pos
    };
    let c = run(classic);
    let r0 = run(tank(&(r#", "gravity": 0.0, "h_swl": 0.3"#.to_string() + &RIEMANN.replace("LIMITER", "0"))));
    let r3 = run(tank(&(r#", "gravity": 0.0, "h_swl": 0.3"#.to_string() + &RIEMANN.replace("LIMITER", "3"))));
    let scale = c.iter().map(|q| q.2.abs().max(q.3.abs())).fold(0.0, f64::max);
    let dscale = c.iter().map(|q| q.4.abs()).fold(0.0, f64::max);
    assert!(scale > 0.0 && dscale > 0.0);
    for (a, b) in c.iter().zip(&r0) {
        assert!((a.2 - b.2).abs() < 1e-9 * scale && (a.3 - b.3).abs() < 1e-9 * scale, "{a:?} {b:?}");
        assert!((a.4 - b.4).abs() < 1e-9 * dscale, "{a:?} {b:?}");
    }
    // the limiter: continuity unchanged; in momentum a force against the approach of pairs,
    // which takes kinetic energy out (sum_a v_a . (a_a(eta) - a_a(0)) < 0)
    let vel = |x: f64, z: f64| (-(x - 0.3) + 0.5 * z, 0.2 * (z - 0.15));
    let power: f64 = c
        .iter()
        .zip(&r3)
        .zip(&r0)
        .map(|((_, b), z)| {
            let (u, w) = vel(b.0, b.1);
            u * (b.2 - z.2) + w * (b.3 - z.3)
        })
        .sum();
    let moved = r0.iter().zip(&r3).filter(|(a, b)| a.2 != b.2 || a.3 != b.3).count();
    assert!(power < 0.0 && moved > c.len() / 4, "power {power}, {moved} of {} particles", c.len());
    assert!(c.iter().zip(&r3).all(|(a, b)| (a.4 - b.4).abs() < 1e-9 * dscale));
}

/// The pressure jump of the Riemann solver's continuity diffuses density (a bump spreads) but,
/// its hydrostatic part removed, leaves a hydrostatic column at rest alone.
#[test]
fn riemann_continuity_spreads_a_bump_and_leaves_hydrostatics_alone() {
    let riemann = RIEMANN.replace("LIMITER", "3");
    let mut s = Solver::<Dim2, WendlandC2>::new(tank(&riemann)).expect("solver");
    s.compute_forces();
    let p = s.particles();
    let interior = |i: usize| {
        let (x, z) = (p.pos[i].x, p.pos[i].y);
        x > 0.1 && x < 0.5 && z > 0.1 && z < 0.2
    };
    let still = (p.fluid_start()..p.len()).filter(|&i| interior(i)).map(|i| p.drho[i].abs()).fold(0.0, f64::max);

    let mut b = Solver::<Dim2, WendlandC2>::new(tank(&(r#", "gravity": 0.0, "h_swl": 0.3"#.to_string() + &riemann))).expect("solver");
    let fs = b.particles().fluid_start();
    let rho0 = b.constants().rho0;
    b.particles_mut().rho.iter_mut().for_each(|r| *r = rho0);
    let a = nearest::<Dim2>(&b.particles().pos, fs, 0.3, 0.15);
    b.particles_mut().rho[a] = rho0 * 1.01;
    let pa = b.particles().pos[a];
    b.compute_forces();
    let p = b.particles();
    let a2 = (fs..p.len()).find(|&i| p.pos[i] == pa).expect("bumped particle");
    assert!(p.drho[a2] < 0.0, "the bump must decay, drho = {}", p.drho[a2]);
    let support = b.constants().support;
    assert!((fs..p.len()).filter(|&i| i != a2 && (p.pos[i] - pa).length() < support).all(|i| p.drho[i] > 0.0));
    assert!(still < 1e-3 * p.drho[a2].abs(), "hydrostatic column: {still} against the bump's {}", p.drho[a2]);
}

/// The kernel gradient correction (`physics/kgc.rs`) on disordered still water: the pressure
/// gradient balances gravity much better inside the water than the plain gradient does, and
/// particles at the free surface keep the plain gradient.
#[test]
fn kernel_correction_balances_hydrostatics_on_a_disordered_set() {
    let residual = |extra: &str| {
        let mut s = Solver::<Dim2, WendlandC2>::new(tank_at(0.01, extra)).expect("solver");
        let c = *s.constants();
        let fs = s.particles().fluid_start();
        let p = s.particles_mut();
        // move each fluid particle by up to 0.15 dp (a fixed pseudo-random sequence), then give
        // it the hydrostatic density of its new depth
        let mut seed: u64 = 12345;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 0.3 * c.dp
        };
        for i in fs..p.len() {
            let (dx, dz) = (next(), next());
            p.pos[i].x += dx;
            p.pos[i].y = (p.pos[i].y + dz).min(0.3);
            p.rho[i] = sph_core::physics::eos::density_at_pressure(&c, c.rho0 * c.gravity * (0.3 - p.pos[i].y));
        }
        s.compute_forces();
        let p = s.particles();
        let inner = |i: usize| {
            let (x, z) = (p.pos[i].x, p.pos[i].y);
            x > 0.15 && x < 0.45 && z > 0.1 && z < 0.2
        };
        let accs: Vec<f64> = (fs..p.len()).filter(|&i| inner(i)).map(|i| p.acc[i - fs].length()).collect();
        (accs.iter().sum::<f64>() / accs.len() as f64, c.gravity)
    };
    let plain = r#", "diffusion": {"model": "none"}"#;
    let corrected = r#", "diffusion": {"model": "none"}, "kernel_correction": {}"#;
    let ((off, g), (on, _)) = (residual(plain), residual(corrected));
    assert!(off > 0.02 * g, "the disorder must show in the plain gradient: {off}");
    assert!(on < 0.01 * g, "mean |acc| inside the water: {on} corrected against {off} plain");
}
