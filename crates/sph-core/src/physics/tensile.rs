//! Monaghan's (2000) artificial pressure against the tensile instability (J. J. Monaghan, "SPH
//! without a tensile instability", J. Comput. Phys. 159, 290-311, section 4: the pair's pressure
//! term gains `R_ab f_ab^n`, `f_ab = W(r_ab) / W(dp)`), in DualSPHysics 5.4's form for the cubic
//! spline (`GetKernelCubic_Tensil` in `src/source/FunSphKernel.h`, added to every fluid-fluid and
//! fluid-wall pair of the momentum equation in `JSphCpu::InteractionForcesFluid`):
//!
//! `dv_a/dt = -sum_b m (P_a/rho_a^2 + P_b/rho_b^2 + Pi_ab + (R_a + R_b) f_ab^4) grad_a W_ab`,
//! `R_a = eps |P_a| / rho_a^2`, with `eps = epsilon_neg` (0.2) where `P_a < 0` and `epsilon_pos`
//! (0.01) where `P_a > 0` (DualSPHysics: `(P/rho^2) (P > 0 ? 0.01 : -0.2)`): both signs repel,
//! the larger push where water is under tension, where pairs would otherwise clump. `n = 4`.
//!
//! `W(dp)`: DualSPHysics takes it at `q = r/h = 1/1.5` (`deltap = 1./1.5` in
//! `GetKernelCubic_Ctes`), whatever the scene's `h/dp`, so `f_ab = W(r_ab) / W(h/1.5)` here too.
//! Monaghan's `dp` is the initial spacing; the two agree at `h = 1.5 dp` (DualSPHysics'
//! `CaseDambreak` has `h = sqrt(3) dp`, where `W(dp) / W(h/1.5) = 1.15`).
//!
//! Applied like DualSPHysics: momentum only (the continuity equation has no such term), every
//! neighbour group (walls, paddle, fluid), in both force loops (`forces.rs`, `batched.rs`),
//! where it is a compile-time flag: a scene without it runs the loops it ran before.
//!
//! The cubic spline only: DualSPHysics has the correction for that kernel alone, and its
//! epsilons and `W(h/1.5)` are set for that kernel's shape. A scene asking for it with
//! another kernel is refused ([`TensileCorrection::validate`]).

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::kernel::KernelKind;
use crate::math::{PairFloat, Real};
use crate::scene::serde_default as default;
use crate::scene::Scene;

/// The scene's `tensile_correction` table (absent: off). Defaults in `scene/defaults.rs`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TensileCorrection {
    /// The law: `monaghan` (the only one).
    #[serde(default = "default::tensile_model")]
    pub model: TensileModel,
    /// `eps` of `R_a = eps |P_a| / rho_a^2` for a particle at positive pressure.
    #[serde(default = "default::tensile_epsilon_pos")]
    pub epsilon_pos: Real,
    /// `eps` for a particle at negative pressure (under tension).
    #[serde(default = "default::tensile_epsilon_neg")]
    pub epsilon_neg: Real,
}

/// The law of [`TensileCorrection`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TensileModel {
    /// Monaghan (2000), as DualSPHysics 5.4 (module docs).
    Monaghan,
}

impl TensileModel {
    pub fn name(self) -> &'static str {
        match self {
            TensileModel::Monaghan => "monaghan",
        }
    }
}

/// `n` of `f_ab^n` (Monaghan 2000 and DualSPHysics: 4).
pub const EXPONENT: i32 = 4;

/// `q = r/h` at which DualSPHysics evaluates `W(dp)` (`deltap = 1./1.5`).
pub const Q_DP: Real = 1.0 / 1.5;

/// Whether the correction exists for a kernel: a constant of the force loops, so that a
/// kernel without it compiles no variant with it.
pub const fn corrects(kind: KernelKind) -> bool {
    matches!(kind, KernelKind::CubicSpline)
}

impl TensileCorrection {
    /// Checks the table against the scene's kernel; errors name the key.
    pub fn validate(&self, kernel: KernelKind) -> Result<()> {
        for (field, v) in [("tensile_correction.epsilon_pos", self.epsilon_pos), ("tensile_correction.epsilon_neg", self.epsilon_neg)] {
            if !v.is_finite() || v < 0.0 {
                return Err(Error::invalid(field, format!("must be a finite number >= 0, got {v}")));
            }
        }
        if !corrects(kernel) {
            return Err(Error::invalid(
                "tensile_correction",
                format!(
                    "Monaghan's (2000) correction is defined for kernel = \"cubic_spline\" only (DualSPHysics applies it to that kernel alone, with epsilons and W(h/1.5) set for its shape), not for kernel = \"{}\"; leave tensile_correction out or use the cubic spline",
                    kernel.name()
                ),
            ));
        }
        Ok(())
    }
}

/// The correction's constants of a run ([`super::Constants::tensile`]); `on` is false without
/// the scene's table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TensileConstants {
    pub on: bool,
    pub epsilon_pos: Real,
    pub epsilon_neg: Real,
    /// `1/h`.
    pub inv_h: Real,
    /// `1 / w(Q_DP)` with `W = alpha_D w(q)`: `f_ab = w(q_ab) / w(Q_DP)` (1.8 for the cubic
    /// spline, in 2D and 3D alike).
    pub inv_w_dp: Real,
}

impl TensileConstants {
    pub fn new(scene: &Scene) -> Self {
        let (on, epsilon_pos, epsilon_neg) = match scene.tensile_correction {
            Some(TensileCorrection { model: TensileModel::Monaghan, epsilon_pos, epsilon_neg }) => (true, epsilon_pos, epsilon_neg),
            None => (false, 0.0, 0.0),
        };
        Self { on, epsilon_pos, epsilon_neg, inv_h: 1.0 / scene.h(), inv_w_dp: 1.0 / cubic_shape(Q_DP) }
    }
}

/// The cubic spline's shape `w(q) = W / alpha_D` (Monaghan & Lattanzio 1985): `1 - 3/2 q^2 +
/// 3/4 q^3` for `q < 1`, `(2 - q)^3 / 4` for `1 <= q < 2`, in DualSPHysics' form
/// `1 + (3/4 q - 3/2) q^2` (`GetKernelCubic_Wab`). Both parts computed and one selected, as the
/// pair loop's kernel gradient does.
#[inline(always)]
fn cubic_shape<F: PairFloat>(q: F) -> F {
    let inner = F::of(1.0) + (F::of(0.75) * q - F::of(1.5)) * (q * q);
    let t = F::of(2.0) - q;
    let t = if t > F::of(0.0) { t } else { F::of(0.0) };
    let outer = F::of(0.25) * (t * t * t);
    if q < F::of(1.0) {
        inner
    } else {
        outer
    }
}

/// The correction in the pair float type `F` of a force loop, its constants rounded once.
#[derive(Clone, Copy)]
pub struct TensilePair<F: PairFloat> {
    inv_h: F,
    inv_w_dp: F,
    epsilon_pos: F,
    /// `-epsilon_neg`: `R = (P/rho^2) (-epsilon_neg) = epsilon_neg |P|/rho^2` for `P <= 0`.
    neg_epsilon_neg: F,
}

impl<F: PairFloat> TensilePair<F> {
    #[inline(always)]
    pub fn new(t: &TensileConstants) -> Self {
        Self { inv_h: F::of(t.inv_h), inv_w_dp: F::of(t.inv_w_dp), epsilon_pos: F::of(t.epsilon_pos), neg_epsilon_neg: F::of(-t.epsilon_neg) }
    }

    /// `R = eps |P| / rho^2` of one particle from its `P` and `P / rho^2`.
    #[inline(always)]
    pub fn stress(&self, p: F, p_rho2: F) -> F {
        p_rho2 * if p > F::of(0.0) { self.epsilon_pos } else { self.neg_epsilon_neg }
    }

    /// `(R_a + R_b) f_ab^4`, `f_ab = w(r/h) / w(Q_DP)`, for a pair at distance `dist` (zero
    /// from `2h` on).
    #[inline(always)]
    pub fn term(&self, dist: F, r_a: F, r_b: F) -> F {
        let f = cubic_shape(dist * self.inv_h) * self.inv_w_dp;
        let f2 = f * f;
        (r_a + r_b) * (f2 * f2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::{CubicSpline, Kernel};

    fn scene(extra: &str) -> Result<Scene> {
        Scene::from_json(&format!(
            r#"{{"dim": 2, "dp": 0.01, "tank": {{"min": [0, 0], "max": [1, 1]}}, "fluid": [{{"min": [0, 0], "max": [1, 0.5]}}] {extra}}}"#
        ))
    }

    /// The pair term against a hand computation: h = coefh sqrt(2) dp with coefh 1, a pair at
    /// r = 0.8 h (q = 0.8: w = 1 - 1.5 0.64 + 0.75 0.512 = 0.424) and one at r = 1.5 h
    /// (w = 0.5^3 / 4 = 0.03125); w(2/3) = 1 - 2/3 + 2/9 = 5/9, so f = 0.7632 and 0.05625.
    /// P_a = 2000 Pa at 1001 kg/m^3, P_b = -500 Pa at 999 kg/m^3:
    /// R_a = 0.01 2000/1001^2, R_b = 0.2 500/999^2.
    #[test]
    fn pair_term_matches_a_hand_computation() {
        let s = scene(r#", "kernel": "cubic_spline", "tensile_correction": {}"#).expect("scene");
        let t = TensileConstants::new(&s);
        assert!(t.on && t.epsilon_pos == 0.01 && t.epsilon_neg == 0.2);
        assert!((t.inv_w_dp - 1.8).abs() < 1e-15, "{}", t.inv_w_dp);
        let h = s.h();
        let pair = TensilePair::<Real>::new(&t);
        let r_a = pair.stress(2000.0, 2000.0 / (1001.0 * 1001.0));
        let r_b = pair.stress(-500.0, -500.0 / (999.0 * 999.0));
        let (ra_hand, rb_hand) = (0.01 * 2000.0 / 1001.0f64.powi(2), 0.2 * 500.0 / 999.0f64.powi(2));
        assert!((r_a - ra_hand).abs() < 1e-15 && (r_b - rb_hand).abs() < 1e-15, "{r_a} {r_b}");
        for (q, f_hand) in [(0.8, 0.424 * 1.8), (1.5, 0.03125 * 1.8), (2.0, 0.0), (2.5, 0.0f64)] {
            let term = pair.term(q * h, r_a, r_b);
            let hand = (ra_hand + rb_hand) * f_hand.powi(EXPONENT);
            assert!((term - hand).abs() <= 1e-12 * hand.max(1e-300), "q {q}: {term} against {hand}");
        }
        // f is W(r) / W(h/1.5) of the kernel itself, 2D and 3D
        for dim in [2, 3] {
            let k = CubicSpline::new(h, dim);
            for q in [0.1, 0.5, 0.9, 1.0, 1.3, 1.9] {
                let f = k.w(q * h) / k.w(Q_DP * h);
                let term = pair.term(q * h, 1.0, 0.0);
                assert!((term - f.powi(EXPONENT)).abs() < 1e-12, "dim {dim} q {q}");
            }
        }
        // in f32: the same to single precision
        let p32 = TensilePair::<f32>::new(&t);
        let t32 = p32.term((0.8 * h) as f32, r_a as f32, r_b as f32) as Real;
        let hand = (ra_hand + rb_hand) * (0.424f64 * 1.8).powi(EXPONENT);
        assert!((t32 - hand).abs() < 1e-6 * hand, "{t32} {hand}");
    }

    #[test]
    fn defaults_and_refusals() {
        let s = scene(r#", "kernel": "cubic_spline""#).expect("scene");
        assert!(s.tensile_correction.is_none() && !TensileConstants::new(&s).on, "off by default");
        let s = scene(r#", "kernel": "cubic_spline", "tensile_correction": {"model": "monaghan", "epsilon_neg": 0.3}"#).expect("scene");
        assert_eq!(s.tensile_correction, Some(TensileCorrection { model: TensileModel::Monaghan, epsilon_pos: 0.01, epsilon_neg: 0.3 }));
        let refused = |extra: &str, field: &str| match scene(extra) {
            Err(Error::InvalidScene { field: f, reason }) => assert!(f.starts_with(field), "{extra}: field {f}: {reason}"),
            other => panic!("{extra}: expected a refusal naming {field}, got {other:?}"),
        };
        // the Wendland kernel (the default one) is refused, naming the table
        match scene(r#", "tensile_correction": {}"#) {
            Err(Error::InvalidScene { field, reason }) => assert!(field == "tensile_correction" && reason.contains("cubic_spline"), "{field}: {reason}"),
            other => panic!("Wendland with the correction: {other:?}"),
        }
        refused(r#", "kernel": "wendland", "tensile_correction": {"model": "monaghan"}"#, "tensile_correction");
        refused(r#", "kernel": "cubic_spline", "tensile_correction": {"epsilon_neg": -0.2}"#, "tensile_correction.epsilon_neg");
        refused(r#", "kernel": "cubic_spline", "tensile_correction": {"epsilon_pos": 1e999}"#, "tensile_correction.epsilon_pos");
        refused(r#", "kernel": "cubic_spline", "tensile_correction": {"eps": 0.2}"#, "tensile_correction");
        refused(r#", "kernel": "cubic_spline", "tensile_correction": {"model": "gray"}"#, "tensile_correction.model");
    }
}
