//! Riemann-solver SPH with the low-dissipation limiter (C. Zhang, X. Y. Hu, N. A. Adams, "A weakly
//! compressible SPH method based on a low-dissipation Riemann solver", J. Comput. Phys. 335
//! (2017) 605-620). Between each pair a one-dimensional Riemann problem is solved along
//! `e_ab = r_ab / |r_ab|`, left state `a`, right state `b`, with `U = -e_ab . v` (the velocity
//! from `a` towards `b`), by their linearised (acoustic) solver, with the
//! acoustic impedances `Z = rho c`:
//!
//! `U* = (Z_a U_a + Z_b U_b + P_a - P_b) / (Z_a + Z_b)`,
//! `P* = (Z_a P_b + Z_b P_a + Z_a Z_b beta (U_a - U_b)) / (Z_a + Z_b)`,
//!
//! and their limiter keeps the dissipation to compression and makes it quadratic
//! in the approach speed: `beta = min(eta max(U_a - U_b, 0) / cbar, 1)`, `cbar = (Z_a + Z_b) /
//! (rho_a + rho_b)`, `eta` = [`RiemannSolver::limiter`] (their 3); the limiter acts in momentum only.
//! The equations:
//!
//! `drho_a/dt = 2 rho_a sum_b (m / rho_b) (U* - U_a) dW_ab/dr`,
//! `dv_a/dt = -2 sum_b m P* / (rho_a rho_b) grad_a W_ab + g` (+ viscosity).
//!
//! Without dissipation (`U* - U_a = (U_b - U_a) / 2`, `P* = (P_a + P_b) / 2`) these are the
//! classic continuity and a symmetric pressure gradient. The Riemann solver's dissipation
//! replaces the artificial viscosity (in momentum, by the limiter) and the density diffusion (in
//! continuity, by `P_a - P_b` in `U*`, a diffusion of density with `delta` near `r/2h`), so a
//! scene with this solver is refused either (`RiemannSolver::validate`); water's own viscosity
//! (laminar, with or without SPS) is added as in the classic loop.
//!
//! Verlet's leapfrog amplifies that continuity dissipation (`RiemannSolver::validate` refuses it):
//! the solver runs with the symplectic integrator.
//!
//! One change from the paper, for water under gravity: the pressure jump in `U*` is taken
//! without its hydrostatic part, `P_a - P_b + rho0 g z_ab`, as Fourtakas et al. (2019) do for
//! the density diffusion: otherwise the jump diffuses the hydrostatic density gradient, and
//! the kernel's truncation at the free surface makes still water gain mass there
//! (`forces::hydrostatic_free_difference` gives the reasons).
//!
//! Walls (every model: DBC, Adami, mDBC) enter as neighbours with their own density, pressure
//! and velocity: the same `P*` in momentum (the limiter's dissipation keeps approaching fluid
//! off the wall), and in continuity the velocity part of `U*` only (the wall's density is a
//! boundary device, not fluid to diffuse into, as the density diffusion is fluid-only).

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::math::{PairFloat, Real};
use crate::scene::serde_default as default;
use crate::scene::{Diffusion, ForcePrecision, Integrator, Scene, Viscosity};

/// The scene's `riemann` table (absent: the classic formulation). Defaults in
/// `scene/defaults.rs`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RiemannSolver {
    /// The solver: `acoustic` (the linearised solver of Zhang et al. 2017, the only one).
    #[serde(default = "default::riemann_model")]
    pub model: RiemannModel,
    /// `eta` of the low-dissipation limiter `beta = min(eta max(U_a - U_b, 0) / cbar, 1)`;
    /// 0 drops the momentum's dissipation, a large value gives the full acoustic solver.
    #[serde(default = "default::riemann_limiter")]
    pub limiter: Real,
}

/// The solver of [`RiemannSolver`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RiemannModel {
    /// Linearised acoustic Riemann solver (Zhang, Hu & Adams 2017; SPHinXsys'
    /// `AcousticRiemannSolver`).
    Acoustic,
}

impl RiemannModel {
    pub fn name(self) -> &'static str {
        match self {
            RiemannModel::Acoustic => "acoustic",
        }
    }
}

impl RiemannSolver {
    /// Checks the table and the options it replaces or cannot run with; errors name the key.
    pub fn validate(&self, scene: &Scene) -> Result<()> {
        if !self.limiter.is_finite() || self.limiter < 0.0 {
            return Err(Error::invalid("riemann.limiter", format!("must be finite and >= 0, got {}", self.limiter)));
        }
        if let Viscosity::Artificial { .. } = scene.viscosity {
            return Err(Error::invalid(
                "viscosity",
                "the Riemann solver's limiter replaces the artificial viscosity (Zhang et al. 2017); \
                 with riemann use viscosity model laminar or laminar_sps",
            ));
        }
        if scene.diffusion != Diffusion::None {
            return Err(Error::invalid(
                "diffusion",
                "the Riemann solver's continuity diffuses density itself (the pressure jump in U*); \
                 with riemann use diffusion model none",
            ));
        }
        if let Integrator::Verlet { .. } = scene.integrator {
            // Verlet's leapfrog `rho^{n+1} = rho^{n-1} + 2 dt D^n` amplifies every diffusive
            // mode; the solver's continuity diffuses as a density diffusion with delta near
            // r/2h, which grows by e^4 between two Euler steps (40 steps) where delta = 0.1
            // grows by e^0.8.
            return Err(Error::invalid(
                "integrator",
                "the Verlet scheme's leapfrog amplifies the Riemann solver's density dissipation; \
                 with riemann use the symplectic integrator",
            ));
        }
        if scene.force_precision == ForcePrecision::F32 {
            return Err(Error::invalid("force_precision", "the Riemann solver's force loop is f64 only; use f64"));
        }
        if scene.tensile_correction.is_some() {
            return Err(Error::invalid(
                "tensile_correction",
                "is a correction of the classic pressure term; the Riemann solver's force loop has none",
            ));
        }
        Ok(())
    }
}

/// The particle's own state in a pair computation: density, pressure and acoustic impedance
/// `Z = rho c`.
#[derive(Clone, Copy)]
pub(crate) struct OwnState<F: PairFloat> {
    pub rho: F,
    pub p: F,
    pub z: F,
}

/// What one pair adds (module docs): `p_term` multiplies `-grad_a W_ab` in momentum (then `m`),
/// `drho_over_f` multiplies `F = (dW/dr)/r` in continuity (then `m`); `inv_r2e = 1/(r^2 + eta^2)`
/// and `inv_sum_rho = 1/(rho_a + rho_b)` serve the viscous terms, `inv_dist = 1/|r|` the kernels
/// that need it.
#[derive(Clone, Copy)]
pub(crate) struct PairTerms<F: PairFloat> {
    pub p_term: F,
    pub drho_over_f: F,
    pub inv_r2e: F,
    pub inv_sum_rho: F,
    pub inv_dist: F,
}

/// The Riemann solver's terms of one pair in the pair float type `F`: the one home of the
/// formulas, for both force loops (`forces.rs` and `batched.rs`, with `DIFF = DIFF_RIEMANN`).
/// `vr = v_ab . r_ab`, `z_ab` the vertical component of `r_ab`, `fluid` whether `b` is fluid
/// (the continuity's pressure jump acts between fluid particles only).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn pair_terms<F: PairFloat>(
    eta: F,
    rho0_g: F,
    a: OwnState<F>,
    rho_b: F,
    p_b: F,
    c_b: F,
    vr: F,
    dist: F,
    r2e: F,
    z_ab: F,
    fluid: bool,
) -> PairTerms<F> {
    let (zero, one, two) = (F::of(0.0), F::of(1.0), F::of(2.0));
    let z_b = rho_b * c_b;
    let sum_z = a.z + z_b;
    let sum_rho = a.rho + rho_b;
    // one division gives the pair's six reciprocals: 1/|r|, 1/(Z_a + Z_b), 1/rho_a, 1/rho_b,
    // 1/(r^2 + eta^2) and 1/(rho_a + rho_b) (divisions share one slow unit)
    let (q1, q2, q3) = (dist * sum_z, rho_b * r2e, a.rho * sum_rho);
    let inv_all = one / (q1 * q2 * q3);
    let inv_dist = sum_z * q2 * q3 * inv_all;
    let inv_sum_z = dist * q2 * q3 * inv_all;
    let inv_rhoa_rhob = q1 * r2e * sum_rho * inv_all;
    let inv_r2e = q1 * rho_b * q3 * inv_all;
    let inv_sum_rho = q1 * q2 * a.rho * inv_all;

    // U_a - U_b = -e_ab . v_ab; the limiter's cbar = (Z_a + Z_b) / (rho_a + rho_b)
    let du = -vr * inv_dist;
    let approaching = if du > zero { du } else { zero };
    let beta = eta * approaching * sum_rho * inv_sum_z;
    let beta = if beta < one { beta } else { one };
    let p_star = (a.z * p_b + z_b * a.p + a.z * z_b * beta * du) * inv_sum_z;

    // U* - U_a = (Z_b (U_b - U_a) + P_a - P_b) / (Z_a + Z_b), times dW/dr = |r| F, with
    // U_b - U_a = v_ab . r_ab / |r|: the velocity part is Z_b v_ab . r_ab F / (Z_a + Z_b), the
    // pressure part (without its hydrostatic part) (P_a - P_b + rho0 g z_ab) |r| F / (Z_a + Z_b)
    let mut flux = z_b * vr;
    if fluid {
        flux += (a.p - p_b + rho0_g * z_ab) * dist;
    }
    // 2 rho_a / rho_b = 2 rho_a^2 / (rho_a rho_b)
    PairTerms {
        p_term: two * p_star * inv_rhoa_rhob,
        drho_over_f: two * a.rho * a.rho * inv_rhoa_rhob * flux * inv_sum_z,
        inv_r2e,
        inv_sum_rho,
        inv_dist,
    }
}
