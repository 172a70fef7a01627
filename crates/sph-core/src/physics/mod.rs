//! Physics of the WCSPH step: equation of state, continuity with density diffusion, momentum with
//! one viscosity model (DESIGN.md section 2). Options are compile-time constants of the force
//! loop, so a term that is off costs nothing in the hot loop.

pub mod batched;
pub mod delta_plus;
pub mod eos;
#[cfg(feature = "flop-count")]
pub mod flop_count;
pub mod forces;
pub mod kgc;
pub mod riemann;
pub mod split_positions;
pub mod tensile;

use crate::math::Real;
use crate::scene::{Diffusion, ForcePrecision, Scene, Viscosity};

/// Most particles in one rayon task of a per-particle neighbour loop. Rayon splits an indexed
/// loop adaptively into about four pieces per thread and splits a piece again only when
/// another thread steals it: the thread that finishes first then waits while the other ends
/// a piece of up to a quarter of the loop, as it can steal nothing smaller. With tasks this
/// small the tail is one task (measured on the 2D dam break on two threads in d355c0a).
pub const NEIGHBOUR_TASK: usize = 64;

/// Viscosity model as a const generic of the force loop.
pub const VISC_ARTIFICIAL: u8 = 0;
pub const VISC_LAMINAR: u8 = 1;
pub const VISC_LAMINAR_SPS: u8 = 2;

/// Density diffusion as a const generic of the force loop.
pub const DIFF_NONE: u8 = 0;
pub const DIFF_MOLTENI: u8 = 1;
pub const DIFF_FOURTAKAS: u8 = 2;
/// The Riemann solver's formulation (`riemann.rs`) in the batched loop: its continuity carries
/// the density dissipation and its `P*` replaces the pressure term (no diffusion term besides).
pub const DIFF_RIEMANN: u8 = 3;

/// Constants of a run, derived once from the scene.
#[derive(Clone, Copy, Debug)]
pub struct Constants {
    pub dim: usize,
    pub dp: Real,
    pub h: Real,
    pub support: Real,
    /// Particle mass `rho0 dp^dim` [kg] (all particles, fluid and wall, have the same mass).
    pub mass: Real,
    pub rho0: Real,
    pub gamma: Real,
    /// Tait stiffness `B = c0^2 rho0 / gamma` [Pa].
    pub b_tait: Real,
    /// Reference sound speed `c0 = coefsound sqrt(g h_swl)` [m/s].
    pub c0: Real,
    pub gravity: Real,
    /// `eta^2 = 0.01 h^2`, keeps `1/r^2` terms finite.
    pub eta2: Real,
    /// Artificial viscosity coefficient (0 when another model is used).
    pub alpha: Real,
    /// Laminar kinematic viscosity [m^2/s].
    pub nu: Real,
    /// Factor on the viscous term of fluid-wall pairs ([`Viscosity::wall_factor`]).
    pub visc_wall_factor: Real,
    /// SPS: `(Cs dp)^2` and `2/3 C_I dp^2` (Dalrymple & Rogers 2006).
    pub sps_smag: Real,
    pub sps_blin: Real,
    /// Density diffusion: `delta h c0`.
    pub delta_h_c0: Real,
    /// `rho0 g` and `1 / c0^2`: the pressure form of the hydrostatic correction.
    pub rho0_g: Real,
    pub inv_c0_2: Real,
    /// `1 / rho0`.
    pub inv_rho0: Real,
    pub cfl: Real,
    /// Relative half-width of the densities the monitor accepts ([`Constants::density_limits`]).
    pub density_band: Real,
    /// The batched force loop forms its pair terms in f32 (`ForcePrecision::F32`).
    pub pair_f32: bool,
    /// Monaghan's (2000) tensile correction (`on` false without it).
    pub tensile: tensile::TensileConstants,
    /// `eta` of the Riemann solver's low-dissipation limiter (`riemann.rs`; 0 without the solver).
    pub riemann_limiter: Real,
}

impl Constants {
    /// `(alpha, nu)` of the viscous terms of a pair: as given between fluid particles, times
    /// the wall factor ([`Viscosity::wall_factor`]) against a wall particle.
    #[inline(always)]
    pub fn viscous_coefficients(&self, wall: bool) -> (Real, Real) {
        if wall {
            (self.alpha * self.visc_wall_factor, self.nu * self.visc_wall_factor)
        } else {
            (self.alpha, self.nu)
        }
    }

    /// The densities the monitor accepts: `rho0 (1 -+ density_band)`.
    pub fn density_limits(&self) -> (Real, Real) {
        (self.rho0 * (1.0 - self.density_band), self.rho0 * (1.0 + self.density_band))
    }

    pub fn new(scene: &Scene) -> Self {
        let dim = scene.dim;
        let h = scene.h();
        let c0 = scene.coefsound * (scene.gravity * scene.h_swl()).sqrt();
        // A tank without gravity has no hydrostatic scale: fall back to coefsound * sqrt(g0 h_swl)
        // with standard gravity so that c0 stays positive.
        let c0 = if c0 > 0.0 { c0 } else { scene.coefsound * (9.81 * scene.h_swl()).sqrt() };
        let b_tait = eos::stiffness(c0, scene.rho0, scene.gamma);
        let (alpha, nu, cs, ci) = match scene.viscosity {
            Viscosity::Artificial { alpha, .. } => (alpha, 0.0, 0.0, 0.0),
            Viscosity::Laminar { nu, .. } => (0.0, nu, 0.0, 0.0),
            Viscosity::LaminarSps { nu, cs, ci, .. } => (0.0, nu, cs, ci),
        };
        let delta = match scene.diffusion {
            Diffusion::None => 0.0,
            Diffusion::Molteni { delta } | Diffusion::Fourtakas { delta } => delta,
        };
        Self {
            dim,
            dp: scene.dp,
            h,
            support: 2.0 * h,
            mass: scene.rho0 * scene.dp.powi(dim as i32),
            rho0: scene.rho0,
            gamma: scene.gamma,
            b_tait,
            c0,
            gravity: scene.gravity,
            eta2: 0.01 * h * h,
            alpha,
            nu,
            visc_wall_factor: scene.viscosity.wall_factor(),
            sps_smag: (cs * scene.dp).powi(2),
            sps_blin: 2.0 / 3.0 * ci * scene.dp * scene.dp,
            delta_h_c0: delta * h * c0,
            rho0_g: scene.rho0 * scene.gravity,
            inv_c0_2: 1.0 / (c0 * c0),
            inv_rho0: 1.0 / scene.rho0,
            cfl: scene.cfl,
            density_band: scene.density_band,
            pair_f32: scene.force_precision == ForcePrecision::F32,
            tensile: tensile::TensileConstants::new(scene),
            riemann_limiter: scene.riemann.map_or(0.0, |r| r.limiter),
        }
    }
}

