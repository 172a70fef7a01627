//! The numerical options of a scene: viscosity, density diffusion, time integrator, wall model,
//! force precision and particle shifting. Each option's defaults are in [`super::Defaults`].

use serde::{Deserialize, Serialize};

use super::defaults::serde_default as default;
use crate::math::Real;

/// Viscosity model (DESIGN.md section 2). One per scene.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub enum Viscosity {
    /// Monaghan (1992) artificial viscosity with coefficient `alpha`.
    Artificial {
        #[serde(default = "default::alpha")]
        alpha: Real,
        /// See [`Viscosity::wall_factor`].
        #[serde(default = "default::visc_wall_factor")]
        wall_factor: Real,
    },
    /// Lo & Shao (2002) laminar viscosity, kinematic viscosity `nu` [m^2/s].
    Laminar {
        #[serde(default = "default::nu")]
        nu: Real,
        /// See [`Viscosity::wall_factor`].
        #[serde(default = "default::visc_wall_factor")]
        wall_factor: Real,
    },
    /// Laminar viscosity plus the SPS Smagorinsky closure (Dalrymple & Rogers 2006).
    LaminarSps {
        #[serde(default = "default::nu")]
        nu: Real,
        #[serde(default = "default::cs")]
        cs: Real,
        #[serde(default = "default::ci")]
        ci: Real,
        /// See [`Viscosity::wall_factor`].
        #[serde(default = "default::visc_wall_factor")]
        wall_factor: Real,
    },
}

impl Viscosity {
    /// The factor on the viscous term of fluid-wall pairs (DualSPHysics' `ViscoBoundFactor`):
    /// 1 treats a wall particle as fluid, 0 drops the wall's viscous force, so the wall is free
    /// slip for the viscosity while its pressure still keeps the fluid out (Adami et al. 2012,
    /// section 2.3, treat free-slip walls this way). Applies to the artificial term and the
    /// laminar one; the SPS stress acts between fluid particles only.
    pub fn wall_factor(&self) -> Real {
        match *self {
            Viscosity::Artificial { wall_factor, .. }
            | Viscosity::Laminar { wall_factor, .. }
            | Viscosity::LaminarSps { wall_factor, .. } => wall_factor,
        }
    }
}

/// Density diffusion term in the continuity equation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub enum Diffusion {
    None,
    /// Molteni & Colagrossi (2009).
    Molteni {
        #[serde(default = "default::delta")]
        delta: Real,
    },
    /// Fourtakas et al. (2019): the hydrostatic part of the density difference is removed,
    /// taken in pressure (`physics::forces::hydrostatic_free_difference`).
    Fourtakas {
        #[serde(default = "default::delta")]
        delta: Real,
    },
}

/// Time integrator (DESIGN.md section 2).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "scheme", rename_all = "snake_case", deny_unknown_fields)]
pub enum Integrator {
    Symplectic,
    Verlet {
        #[serde(default = "default::euler_every")]
        euler_every: u32,
    },
}

/// How wall particles get the density (and so the pressure) that pushes on the fluid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub enum Boundary {
    /// Dynamic boundary condition (Crespo et al. 2007): wall particles integrate continuity
    /// from their fluid neighbours (clamped at rho0, as DualSPHysics). Their density remembers
    /// history: a wall particle that starts dry keeps fluid off by more than a wall that starts
    /// wet, and one at a moving waterline is pumped up by the clamp (docs/wave-flume.md).
    Dbc,
    /// Adami, Hu & Adams (2012, J. Comput. Phys. 231, Eq. 27): at every force evaluation each
    /// wall particle takes the pressure extrapolated from its fluid neighbours,
    /// `p_w = (sum_f p_f W_wf + (g - a_w) . sum_f rho_f r_wf W_wf) / sum_f W_wf`, floored at
    /// 0 (no suction), and the density of that pressure; no memory. `a_w` is the wall's own
    /// acceleration (the paddle's, from its motion law).
    Adami,
    /// Modified dynamic boundary condition (English et al. 2022, Comp. Part. Mech. 9, 1-15;
    /// `boundary/mdbc.rs`): each wall particle has a ghost node, its mirror image through the
    /// wall surface along the surface normal (from the solids' geometry); the density at the
    /// ghost and its gradient are interpolated from the fluid with the first-order (kernel
    /// gradient) corrected SPH interpolation, the Shepard average where that system is
    /// ill-conditioned, and the wall particle takes `rho_w = rho_g + (r_w - r_g) . grad rho_g`,
    /// at least rho0 (no suction, as DualSPHysics' walls), at every force evaluation; no memory.
    Mdbc {
        /// The velocity the wall shows the fluid (in the viscous and continuity terms).
        #[serde(default = "default::mdbc_slip")]
        slip: Slip,
    },
}

/// The velocity a modified-DBC wall particle shows the fluid (DualSPHysics' `SlipMode`), from
/// the wall's own velocity `v_m` and the Shepard average `v_g` of the fluid's at its ghost node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Slip {
    /// The wall's own velocity, `v_w = v_m` (zero for fixed walls; DualSPHysics' "DBC vel=0",
    /// English et al.'s scheme): the artificial viscosity then acts as for DBC walls.
    WallVelocity,
    /// `v_w = 2 v_m - v_g`: the velocity interpolated to the wall surface, halfway between
    /// particle and ghost, is the wall's (English et al. 2022, section 2.3).
    NoSlip,
    /// The fluid's tangential velocity and the mirror of its normal velocity about the wall's,
    /// `v_w = v_g + 2 ((v_m - v_g) . n) n`: no shear at the wall, no flow through it.
    FreeSlip,
}

/// Floating-point type of the fluid force loop's pair arithmetic. The state (positions,
/// velocities, densities) and the sums over neighbours stay in f64 either way.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ForcePrecision {
    /// Every pair term in f64.
    F64,
    /// Pair terms in f32, eight to an AVX2 register instead of four, as DualSPHysics forms
    /// its forces. Neighbour offsets are taken in f64 before rounding, and pressures and
    /// density differences from `rho/rho0 - 1` formed in f64, so no term loses more than f32's
    /// relative precision (about 6e-8); docs/benchmarks.md measures the effect.
    F32,
}

/// Particle shifting: after each step a fluid particle moves along minus a concentration
/// gradient, which evens out the particle distribution (one extra neighbour pass a step).
///
/// `model = "lind"` (the default): Fickian shifting (Lind et al. 2012, J. Comput. Phys. 231,
/// Eqs. 22-23), `dr = -a_fs D grad C`, with the concentration gradient `grad C = sum_b V_b
/// grad W_ab` over fluid and wall neighbours and Skillen et al. (2013)'s coefficient
/// `D = A h |u| dt` (their Eq. 26), so still water is never shifted. Free-surface particles lack
/// half their neighbours and `grad C` would push them out of the water: the particle divergence
/// `div r = -sum_b V_b r_ab . grad W_ab` (Lee et al. 2008; `dim` in the bulk) detects them, and
/// `a_fs` ramps from 0 at `div r = surface_threshold` to 1 at `div r = dim` (DualSPHysics'
/// free-surface correction, Mokos 2013, with its thresholds 1.5 in 2D and 2.75 in 3D).
///
/// `model = "delta_plus"`: the delta-plus-SPH shifting (Sun, Colagrossi, Marrone & Zhang 2017,
/// Comput. Methods Appl. Mech. Engrg. 315, section 2.3; `physics::delta_plus`):
/// `dr = -A h U_max dt sum_b [1 + R (W_ab / W(dp))^n] grad W_ab V_b` with R = 0.2, n = 4 (their
/// `CFL Ma (2h)^2` is `4 h U_max dt` for `dt = CFL h / c0`, `Ma = U_max / c0`: A = 4), `U_max`
/// the largest fluid speed of the step; the free surface is found from the smallest eigenvalue
/// `lambda` of `sum_b (r_b - r_a) (x) grad W_ab V_b` (Marrone et al. 2010; 1 in the bulk,
/// about 0.5 on a flat surface): not shifted up to 0.75 (on the surface), shifted along the
/// surface only (`(I - n n) dr`, `n` the surface's normal) within the kernel support of a
/// surface particle, in full elsewhere. `surface_threshold` belongs to `lind` and is refused
/// here.
///
/// Either shift only moves particles; it does not correct the velocity or density (as
/// DualSPHysics' Lind shifting and the 2017 delta-plus-SPH).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shifting {
    /// Which law: `lind` or `delta_plus`.
    #[serde(default = "default::shifting_model")]
    pub model: ShiftingModel,
    /// `A` of `D = A h |u| dt` (`lind`) or of `A h U_max dt` (`delta_plus`).
    #[serde(default = "default::shifting_coefficient")]
    pub coefficient: Real,
    /// `lind` only: particle divergence at and below which a particle is on the free surface
    /// and not shifted; default 1.5 in 2D, 2.75 in 3D. Must lie between 0 and `dim`.
    #[serde(default)]
    pub surface_threshold: Option<Real>,
}

/// The law of [`Shifting`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShiftingModel {
    Lind,
    DeltaPlus,
}

impl ShiftingModel {
    pub fn name(self) -> &'static str {
        match self {
            ShiftingModel::Lind => "lind",
            ShiftingModel::DeltaPlus => "delta_plus",
        }
    }
}

impl Shifting {
    /// The free-surface threshold for `dim` (the default when none is given).
    pub fn threshold(&self, dim: usize) -> Real {
        self.surface_threshold.unwrap_or(if dim == 2 { 1.5 } else { 2.75 })
    }
}
