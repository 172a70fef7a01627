//! The batched (SIMD) force loop against the pair-at-a-time loop on moving dam breaks: the
//! same sums in another order, so equal to rounding.
use super::advance::Rule;
use super::*;
use crate::error::InstabilityKind;
use crate::particles::KIND_FLUID;
use crate::kernel::{CubicSpline, WendlandC2};
use crate::math::{Dim2, Dim3};
use glam::DVec2;
use crate::physics::batched::{fluid_forces_batched, fluid_forces_variant};
use crate::physics::eos::sound_speed;
use crate::physics::forces::fluid_forces_scalar;
use crate::physics::{DIFF_FOURTAKAS, DIFF_MOLTENI, DIFF_NONE, DIFF_RIEMANN, VISC_ARTIFICIAL, VISC_LAMINAR};

fn check<D: Dim, K: Kernel, const VISC: u8, const DIFF: u8>(json: &str) {
    let mut s = Solver::<D, K>::new(Scene::from_json(json).expect("scene")).expect("solver");
    s.step(40).expect("stable");
    s.compute_forces();
    let n = s.p.n_fluid();
    let fields = fields_of(&s.p, &[]);
    let (mut acc_s, mut drho_s) = (vec![D::V::ZERO; n], vec![0.0; n]);
    let (mut acc_b, mut drho_b) = (vec![D::V::ZERO; n], vec![0.0; n]);
    // the loop `fluid_forces` would run for the scene (the batched loop chooses for itself)
    let scalar = if s.c.tensile.on { fluid_forces_scalar::<D, K, VISC, DIFF, true, false> } else { fluid_forces_scalar::<D, K, VISC, DIFF, false, false> };
    let lim_s = scalar(&s.c, &s.kernel, &s.grid, fields, &mut acc_s, &mut drho_s);
    let lim_b = fluid_forces_batched::<D, K, VISC, DIFF>(&s.c, &s.kernel, &s.grid, fields, &mut acc_b, &mut drho_b);
    let acc_scale = acc_s.iter().map(|a| a.length()).fold(0.0, f64::max);
    let drho_scale = drho_s.iter().map(|d| d.abs()).fold(0.0, f64::max);
    assert!(acc_scale > s.c.gravity && drho_scale > 0.0, "the scene must move");
    for i in 0..n {
        assert!((acc_s[i] - acc_b[i]).length() <= 1e-11 * acc_scale, "acc of fluid particle {i}");
        assert!((drho_s[i] - drho_b[i]).abs() <= 1e-11 * drho_scale, "drho of fluid particle {i}");
    }
    assert!((lim_s.max_acc - lim_b.max_acc).abs() <= 1e-11 * lim_s.max_acc);
    assert!((lim_s.min_dt_cv - lim_b.min_dt_cv).abs() <= 1e-11 * lim_s.min_dt_cv);

    // Pair terms in f32: the same sums to f32's precision. The pressure terms of a pair are
    // about as large as the sum over a particle's neighbours (hydrostatic balance), so the
    // error is a few f32 roundings of the largest force.
    let mut c32 = s.c;
    c32.pair_f32 = true;
    let (mut acc_f, mut drho_f) = (vec![D::V::ZERO; n], vec![0.0; n]);
    let lim_f = fluid_forces_batched::<D, K, VISC, DIFF>(&c32, &s.kernel, &s.grid, fields, &mut acc_f, &mut drho_f);
    let acc_err = (0..n).map(|i| (acc_s[i] - acc_f[i]).length()).fold(0.0, f64::max) / acc_scale;
    let drho_err = (0..n).map(|i| (drho_s[i] - drho_f[i]).abs()).fold(0.0, f64::max) / drho_scale;
    // measured: up to 1.5e-6 (acc) and 9e-7 (drho) of the largest value
    assert!(acc_err < 5e-6 && drho_err < 5e-6, "f32 pair terms: acc error {acc_err:e}, drho error {drho_err:e}");
    assert!((lim_s.max_acc - lim_f.max_acc).abs() <= 5e-6 * lim_s.max_acc);
    assert!((lim_s.min_dt_cv - lim_f.min_dt_cv).abs() <= 5e-6 * lim_s.min_dt_cv);

    // The AVX2 variant (intrinsic candidate scan, wide arithmetic) and the portable one
    // give the same bits.
    if crate::physics::batched::uses_avx2() {
        let (mut acc_p, mut drho_p) = (vec![D::V::ZERO; n], vec![0.0; n]);
        let (mut acc_x, mut drho_x) = (vec![D::V::ZERO; n], vec![0.0; n]);
        let lim_p = fluid_forces_variant::<D, K, VISC, DIFF>(&s.c, &s.kernel, &s.grid, fields, &mut acc_p, &mut drho_p, false);
        let lim_x = fluid_forces_variant::<D, K, VISC, DIFF>(&s.c, &s.kernel, &s.grid, fields, &mut acc_x, &mut drho_x, true);
        assert!(acc_p == acc_x && drho_p == drho_x, "AVX2 and portable variants differ");
        assert!(lim_p.max_acc == lim_x.max_acc && lim_p.min_dt_cv == lim_x.min_dt_cv);
        let (mut acc_p, mut drho_p) = (vec![D::V::ZERO; n], vec![0.0; n]);
        let (mut acc_x, mut drho_x) = (vec![D::V::ZERO; n], vec![0.0; n]);
        fluid_forces_variant::<D, K, VISC, DIFF>(&c32, &s.kernel, &s.grid, fields, &mut acc_p, &mut drho_p, false);
        fluid_forces_variant::<D, K, VISC, DIFF>(&c32, &s.kernel, &s.grid, fields, &mut acc_x, &mut drho_x, true);
        assert!(acc_p == acc_x && drho_p == drho_x, "AVX2 and portable variants differ in f32");
    }
}

/// The Riemann solver's formulation (`riemann.rs`, one pair function for both loops); its
/// batched loop runs f64 pair terms even where `pair_f32` is set (the scene's check refuses f32).
#[test]
fn riemann_batched_loop_matches_the_scalar_loop() {
    let extra = r#", "riemann": {}, "viscosity": {"model": "laminar", "nu": 1e-4, "wall_factor": 0.5}, "diffusion": {"model": "none"}"#;
    check::<Dim2, WendlandC2, VISC_LAMINAR, DIFF_RIEMANN>(&dambreak(2, extra));
    check::<Dim3, WendlandC2, VISC_LAMINAR, DIFF_RIEMANN>(&dambreak(3, extra));
    let cubic = format!(r#"{extra}, "kernel": "cubic_spline", "boundary": {{"model": "adami"}}"#);
    check::<Dim2, CubicSpline, VISC_LAMINAR, DIFF_RIEMANN>(&dambreak(2, &cubic));
    let gamma = format!(r#"{extra}, "gamma": 6.5"#);
    check::<Dim2, WendlandC2, VISC_LAMINAR, DIFF_RIEMANN>(&dambreak(2, &gamma));
}

/// Still water starts hydrostatic, at rest: density diffusion with the hydrostatic part
/// removed must add nothing, at the free surface and next to the bed as in the bulk.
/// (Fourtakas' density form, Eq. 13, gives every pair a positive leftover here, of order
/// 1 kg/m^3/s per particle by the estimate in docs/wave-flume.md, "The mean water level":
/// still water expanded.)
#[test]
fn fourtakas_diffusion_leaves_still_water_alone() {
    // f32 pair terms round each pressure to about 1e-7 of itself; what is left is noise of
    // that order (measured: 5e-5 kg/m^3/s), not Eq. 13's systematic gain
    for (boundary, precision, bound) in [("dbc", "f64", 1e-6), ("adami", "f64", 1e-6), ("dbc", "f32", 1e-3), ("adami", "f32", 1e-3)] {
        let json = format!(
            r#"{{"dim": 2, "dp": 0.0375, "coefsound": 10, "tank": {{"min": [0, 0], "max": [1.5, 0.5]}},
                "fluid": [{{"min": [0, 0], "max": [1.5, 0.3]}}], "boundary": {{"model": "{boundary}"}},
                "diffusion": {{"model": "fourtakas", "delta": 0.1}}, "force_precision": "{precision}"}}"#
        );
        let mut s = Solver::<Dim2, WendlandC2>::new(Scene::from_json(&json).expect("scene"))
            .expect("solver");
        s.compute_forces();
        let fs = s.p.fluid_start();
        let worst = s.p.drho[fs..].iter().fold(0.0 as Real, |m, d| m.max(d.abs()));
        assert!(worst < bound, "{boundary} {precision}: |drho/dt| up to {worst} kg/m^3/s in still water");
    }
}

fn dambreak(dim: usize, extra: &str) -> String {
    if dim == 2 {
        format!(
            r#"{{"dim": 2, "dp": 0.02, "tank": {{"min": [0, 0], "max": [1.0, 0.6]}},
                "fluid": [{{"min": [0, 0], "max": [0.3, 0.4]}}] {extra}}}"#
        )
    } else {
        format!(
            r#"{{"dim": 3, "dp": 0.04, "tank": {{"min": [0, 0, 0], "max": [1.0, 0.3, 0.5]}},
                "fluid": [{{"min": [0, 0, 0], "max": [0.3, 0.3, 0.4]}}] {extra}}}"#
        )
    }
}

#[test]
fn wendland_artificial_fourtakas_2d_and_3d() {
    let extra = r#", "viscosity": {"model": "artificial", "alpha": 0.1}, "diffusion": {"model": "fourtakas", "delta": 0.1}"#;
    check::<Dim2, WendlandC2, VISC_ARTIFICIAL, DIFF_FOURTAKAS>(&dambreak(2, extra));
    check::<Dim3, WendlandC2, VISC_ARTIFICIAL, DIFF_FOURTAKAS>(&dambreak(3, extra));
}

#[test]
fn cubic_laminar_molteni_and_no_diffusion() {
    let lam = r#", "kernel": "cubic_spline", "viscosity": {"model": "laminar", "nu": 1e-4}, "diffusion": {"model": "molteni", "delta": 0.1}"#;
    check::<Dim2, CubicSpline, VISC_LAMINAR, DIFF_MOLTENI>(&dambreak(2, lam));
    check::<Dim3, CubicSpline, VISC_LAMINAR, DIFF_MOLTENI>(&dambreak(3, lam));
    let none = r#", "kernel": "cubic_spline", "diffusion": {"model": "none"}"#;
    check::<Dim2, CubicSpline, VISC_ARTIFICIAL, DIFF_NONE>(&dambreak(2, none));
}

#[test]
fn the_monitor_names_the_lowest_id_among_bad_particles_in_any_chunk() {
    type S = Solver<Dim2, WendlandC2>;
    // 2D dam break of dp 0.005: 4,800 fluid particles, three of the sweep's chunks
    let json = r#"{"dim": 2, "dp": 0.005, "tank": {"min": [0, 0], "max": [1.0, 0.6]}, "fluid": [{"min": [0, 0], "max": [0.3, 0.4]}]}"#;
    let mut s = S::new(Scene::from_json(json).expect("scene")).expect("solver");
    // a sweep over no time is the monitor alone: nothing moves, every slot is tested
    let monitor = |s: &mut S| s.sweep(Rule::Verlet { euler: true }, 0.0, true).bad.map(|(id, _, kind)| (kind, id));
    assert_eq!(monitor(&mut s), None);
    let n = s.p.len();
    assert!(n > 2 * 2048, "{n} particles");
    let slot_of = |s: &S, id: u32| s.p.id.iter().position(|&i| i == id).unwrap();
    // a density out of band on the highest id, then a NaN on a lower id in another chunk,
    // then an infinity on the lowest id: the lowest bad id is reported wherever its slot is
    let (lowest, highest) = (s.p.id.iter().copied().min().unwrap(), s.p.id.iter().copied().max().unwrap());
    let high = slot_of(&s, highest);
    s.p.rho[high] = s.c.rho0 * (1.0 + 2.0 * s.c.density_band);
    assert_eq!(monitor(&mut s), Some((InstabilityKind::DensityOutOfRange, highest)));
    let other = if high < n / 2 { n - 10 } else { 10 };
    let id_other = s.p.id[other];
    assert!(id_other != lowest && id_other != highest);
    s.p.pos[other].x = Real::NAN;
    assert_eq!(monitor(&mut s), Some((InstabilityKind::NonFinite, id_other)));
    let low = slot_of(&s, lowest);
    s.p.vel[low].y = Real::INFINITY;
    assert_eq!(monitor(&mut s), Some((InstabilityKind::NonFinite, lowest)));
}

/// The pair count against every pair tested, after steps that moved the particles since
/// the grid's last sort, and the evaluations per step of both integrators.
#[test]
fn fluid_pair_count_is_every_pair_within_the_support() {
    for (dim, integrator, evaluations) in [(2, "symplectic", 2), (3, "verlet", 1)] {
        let extra = format!(r#", "integrator": {{"scheme": "{integrator}"}}"#);
        let json = dambreak(dim, &extra);
        let count = |s: &dyn super::Simulation| -> u64 {
            let (pos, kind, d) = (s.positions(), s.kinds(), s.dim());
            let support2 = s.params().support.powi(2);
            let mut pairs = 0;
            for a in (0..kind.len()).filter(|&a| kind[a] == KIND_FLUID) {
                for b in (0..kind.len()).filter(|&b| b != a) {
                    let r2: Real = (0..d).map(|k| (pos[d * a + k] - pos[d * b + k]).powi(2)).sum();
                    pairs += (r2 < support2) as u64;
                }
            }
            pairs
        };
        let mut s: Box<dyn super::Simulation> = if dim == 2 {
            Box::new(Solver::<Dim2, WendlandC2>::new(Scene::from_json(&json).expect("scene")).expect("solver"))
        } else {
            Box::new(Solver::<Dim3, WendlandC2>::new(Scene::from_json(&json).expect("scene")).expect("solver"))
        };
        assert_eq!(s.fluid_pairs(), count(s.as_ref()));
        s.step(150).expect("stable");
        let moved = s.fluid_pairs();
        assert_eq!(moved, count(s.as_ref()));
        // a full support holds some 20 (2D) to 100 (3D) neighbours; the walls and the surface fewer
        assert!(moved > 5 * s.n_fluid() as u64, "{dim}D: {moved} pairs for {} fluid particles", s.n_fluid());
        assert_eq!(s.force_evaluations_per_step(), evaluations);
    }
}

/// Monaghan's (2000) tensile correction in both force loops: scalar, batched, f32 and AVX2
/// agree as without it (`check`).
#[test]
fn cubic_with_the_tensile_correction_2d_and_3d() {
    let extra = r#", "kernel": "cubic_spline", "tensile_correction": {}, "viscosity": {"model": "artificial", "alpha": 0.1}"#;
    check::<Dim2, CubicSpline, VISC_ARTIFICIAL, DIFF_FOURTAKAS>(&dambreak(2, extra));
    check::<Dim3, CubicSpline, VISC_ARTIFICIAL, DIFF_FOURTAKAS>(&dambreak(3, extra));
    let lam = r#", "kernel": "cubic_spline", "tensile_correction": {"epsilon_neg": 0.3}, "viscosity": {"model": "laminar", "nu": 1e-4}, "diffusion": {"model": "none"}"#;
    check::<Dim2, CubicSpline, VISC_LAMINAR, DIFF_NONE>(&dambreak(2, lam));
}

/// The correction the loops add, against a sum over every particle written from the formula
/// (`physics/tensile.rs`): `-m sum_b (R_a + R_b) (W_ab / W(h/1.5))^4 grad_a W_ab` over fluid and
/// wall neighbours, `R = eps |P| / rho^2`, eps 0.01 for P > 0 and 0.2 for P < 0. The state: a
/// cubic-spline dam break after 40 steps, its densities spread by +-0.3 % so that both signs of
/// pressure occur among fluid and wall particles.
#[test]
fn tensile_correction_adds_monaghans_term_to_every_fluid_and_wall_pair() {
    let json = dambreak(2, r#", "kernel": "cubic_spline", "tensile_correction": {}"#);
    let mut s = Solver::<Dim2, CubicSpline>::new(Scene::from_json(&json).expect("scene")).expect("solver");
    s.step(40).expect("stable");
    s.compute_forces();
    for (i, rho) in s.p.rho.iter_mut().enumerate() {
        *rho *= 1.0 + 0.003 * (i as Real * 0.7).sin();
    }
    let n = s.p.n_fluid();
    let fields = fields_of(&s.p, &[]);
    let negative = (0..s.p.len()).filter(|&b| crate::physics::eos::pressure(&s.c, s.p.rho[b]) < 0.0).count();
    assert!(negative > s.p.len() / 10 && negative < 9 * s.p.len() / 10, "{negative} of {} at negative pressure", s.p.len());
    let mut off = s.c;
    off.tensile.on = false;
    for precision_f32 in [false, true] {
        let (mut c_on, mut c_off) = (s.c, off);
        c_on.pair_f32 = precision_f32;
        c_off.pair_f32 = precision_f32;
        let (mut acc_on, mut acc_off, mut drho_on, mut drho_off) = (vec![DVec2::ZERO; n], vec![DVec2::ZERO; n], vec![0.0; n], vec![0.0; n]);
        fluid_forces_batched::<Dim2, CubicSpline, VISC_ARTIFICIAL, DIFF_FOURTAKAS>(&c_on, &s.kernel, &s.grid, fields, &mut acc_on, &mut drho_on);
        fluid_forces_batched::<Dim2, CubicSpline, VISC_ARTIFICIAL, DIFF_FOURTAKAS>(&c_off, &s.kernel, &s.grid, fields, &mut acc_off, &mut drho_off);
        let (mut acc_s, mut drho_s) = (vec![DVec2::ZERO; n], vec![0.0; n]);
        fluid_forces_scalar::<Dim2, CubicSpline, VISC_ARTIFICIAL, DIFF_FOURTAKAS, true, false>(&s.c, &s.kernel, &s.grid, fields, &mut acc_s, &mut drho_s);
        assert_eq!(drho_on, drho_off, "the correction is in the momentum equation only");
        // the formula, pair by pair over all particles
        let k = CubicSpline::new(s.c.h, 2);
        let w_dp = k.w(s.c.h / 1.5);
        let r_of = |b: usize| {
            let p = crate::physics::eos::pressure(&s.c, s.p.rho[b]);
            p / (s.p.rho[b] * s.p.rho[b]) * if p > 0.0 { 0.01 } else { -0.2 }
        };
        let fs = s.p.fluid_start();
        let expected: Vec<DVec2> = (0..n)
            .map(|i| {
                let a = fs + i;
                let mut sum = DVec2::ZERO;
                for b in (0..s.p.len()).filter(|&b| b != a) {
                    let r = s.p.pos[a] - s.p.pos[b];
                    let d = r.length();
                    if d < 2.0 * s.c.h {
                        sum -= r * (k.grad_factor(d) * s.c.mass * (r_of(a) + r_of(b)) * (k.w(d) / w_dp).powi(4));
                    }
                }
                sum
            })
            .collect();
        let scale = expected.iter().map(|e| e.length()).fold(0.0, Real::max);
        let acc_scale = acc_on.iter().map(|e| e.length()).fold(0.0, Real::max);
        assert!(scale > 1e-3 * acc_scale, "the correction must matter here: {scale} against accelerations up to {acc_scale}");
        // f64: the difference of two sums of terms up to acc_scale; f32: a few roundings of them
        let tol = if precision_f32 { 1e-5 } else { 1e-11 } * acc_scale;
        for i in 0..n {
            let added = acc_on[i] - acc_off[i];
            assert!((added - expected[i]).length() <= tol, "{}: fluid particle {i}: added {added:?}, formula {:?}", if precision_f32 { "f32" } else { "f64" }, expected[i]);
            assert!((acc_s[i] - acc_on[i]).length() <= if precision_f32 { tol } else { 1e-11 * acc_scale }, "scalar loop, particle {i}");
        }
    }
}

/// A cubic-spline dam break with the correction on runs stably through the collapse and the
/// impact on the far wall, where water is under tension (negative pressures), and ends in
/// another state than without it.
#[test]
fn dam_break_with_the_tensile_correction_is_stable_and_differs() {
    // dp 0.03: 130 fluid particles, the front at the far wall by t = 0.25 s
    let run = |extra: &str| {
        let json = format!(
            r#"{{"dim": 2, "dp": 0.03, "kernel": "cubic_spline", "tank": {{"min": [0, 0], "max": [0.8, 0.6]}},
                "fluid": [{{"min": [0, 0], "max": [0.3, 0.4]}}] {extra}}}"#
        );
        let mut s = Solver::<Dim2, CubicSpline>::new(Scene::from_json(&json).expect("scene")).expect("solver");
        let mut tension = 0usize;
        while s.time < 0.35 {
            s.step(20).expect("stable");
            let fs = s.p.fluid_start();
            tension += s.p.rho[fs..].iter().filter(|&&r| r < s.c.rho0).count();
        }
        (s.p.pos[s.p.fluid_start()..].to_vec(), tension)
    };
    let (with, tension) = run(r#", "tensile_correction": {}"#);
    let (without, _) = run("");
    assert!(tension > 0, "no fluid particle went below rho0: nothing for the correction to act on");
    let moved = with.iter().zip(&without).filter(|(a, b)| (**a - **b).length() > 1e-6).count();
    assert!(moved > with.len() / 10, "{moved} of {} fluid particles moved differently", with.len());
}

/// The viscous wall factor (`Viscosity::wall_factor`, DualSPHysics' ViscoBoundFactor) scales
/// the viscous term of fluid-wall pairs and nothing else: on a moving dam break, the change it
/// makes is, particle by particle, Monaghan's artificial viscosity summed over wall neighbours
/// (written here from the formula); continuity and particles away from walls are untouched; in
/// every loop (scalar, batched f64 and f32) and for laminar viscosity too.
#[test]
fn the_wall_factor_scales_the_viscous_term_of_wall_pairs_only() {
    let run = |visc: &str| {
        let json = dambreak(2, &format!(r#", "viscosity": {visc}"#));
        let mut s = Solver::<Dim2, WendlandC2>::new(Scene::from_json(&json).expect("scene")).expect("solver");
        s.step(40).expect("stable");
        s.compute_forces();
        s
    };
    for (visc, laminar) in [(r#"{"model": "artificial", "alpha": 0.1}"#, false), (r#"{"model": "laminar", "nu": 1e-3}"#, true)] {
        let s = run(visc);
        let n = s.p.n_fluid();
        let fs = s.p.fluid_start();
        let fields = fields_of(&s.p, &[]);
        let forces = |factor: Real, f32_pairs: bool, scalar: bool| {
            let mut c = s.c;
            c.visc_wall_factor = factor;
            c.pair_f32 = f32_pairs;
            let (mut acc, mut drho) = (vec![DVec2::ZERO; n], vec![0.0; n]);
            match (laminar, scalar) {
                (false, false) => fluid_forces_batched::<Dim2, WendlandC2, VISC_ARTIFICIAL, DIFF_FOURTAKAS>(&c, &s.kernel, &s.grid, fields, &mut acc, &mut drho),
                (false, true) => fluid_forces_scalar::<Dim2, WendlandC2, VISC_ARTIFICIAL, DIFF_FOURTAKAS, false, false>(&c, &s.kernel, &s.grid, fields, &mut acc, &mut drho),
                (true, false) => fluid_forces_batched::<Dim2, WendlandC2, VISC_LAMINAR, DIFF_FOURTAKAS>(&c, &s.kernel, &s.grid, fields, &mut acc, &mut drho),
                (true, true) => fluid_forces_scalar::<Dim2, WendlandC2, VISC_LAMINAR, DIFF_FOURTAKAS, false, false>(&c, &s.kernel, &s.grid, fields, &mut acc, &mut drho),
            };
            (acc, drho)
        };
        // the formula: the viscous term of every fluid-wall pair
        let near_wall = |a: usize| (0..fs).any(|w| (s.p.pos[a] - s.p.pos[w]).length() < s.c.support);
        let wall_viscous: Vec<DVec2> = (0..n)
            .map(|i| {
                let a = fs + i;
                let mut sum = DVec2::ZERO;
                for w in 0..fs {
                    let r = s.p.pos[a] - s.p.pos[w];
                    let d = r.length();
                    if d >= s.c.support || d == 0.0 {
                        continue;
                    }
                    let gw = r * s.kernel.grad_factor(d);
                    let v = s.p.vel[a] - s.p.vel[w];
                    let (rhoa, rhow) = (s.p.rho[a], s.p.rho[w]);
                    sum += if laminar {
                        v * (4.0 * s.c.nu * r.dot(gw) / ((r.dot(r) + s.c.eta2) * (rhoa + rhow)))
                    } else {
                        let cbar_rhobar = (sound_speed(&s.c, rhoa) + sound_speed(&s.c, rhow)) / (rhoa + rhow);
                        gw * (s.c.alpha * cbar_rhobar * s.c.h * v.dot(r).min(0.0) / (r.dot(r) + s.c.eta2))
                    };
                }
                sum * s.c.mass
            })
            .collect();
        let scale = wall_viscous.iter().map(|v| v.length()).fold(0.0, Real::max);
        assert!(scale > 0.0, "{visc}: no viscous force from the walls to scale");
        for (f32_pairs, scalar) in [(false, false), (false, true), (true, false)] {
            let (acc1, drho1) = forces(1.0, f32_pairs, scalar);
            let (acc0, drho0) = forces(0.0, f32_pairs, scalar);
            let (acc_half, _) = forces(0.5, f32_pairs, scalar);
            assert_eq!(drho1, drho0, "{visc}: continuity does not depend on the wall factor");
            let acc_scale = acc1.iter().map(|a| a.length()).fold(0.0, Real::max);
            let tol = if f32_pairs { 1e-5 } else { 1e-11 } * acc_scale;
            for i in 0..n {
                let removed = acc1[i] - acc0[i];
                assert!((removed - wall_viscous[i]).length() <= tol, "{visc} f32 {f32_pairs} scalar {scalar}: particle {i}: {removed:?} against {:?}", wall_viscous[i]);
                assert!(((acc1[i] + acc0[i]) * 0.5 - acc_half[i]).length() <= tol, "{visc}: linear in the factor, particle {i}");
                if !near_wall(fs + i) {
                    assert_eq!(acc1[i], acc0[i], "{visc}: particle {i} has no wall neighbour");
                }
            }
        }
    }
}
