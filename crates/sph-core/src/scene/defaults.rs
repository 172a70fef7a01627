//! The default of every optional scene parameter: one [`Defaults`] value, the project's only
//! defaults. Python reads it (`watersim._core.scene_defaults()`) instead of keeping its own.

use serde::Serialize;

use super::numerics::{Boundary, Diffusion, ForcePrecision, Integrator, ShiftingModel, Slip, Viscosity};
use crate::kernel::KernelKind;
use crate::probes::{RunupMethod, SurfaceMethod};
use crate::physics::riemann::RiemannModel;
use crate::physics::tensile::TensileModel;
use crate::math::Real;

/// Every default, laid out as the scene's keys: `viscosity.nu` is the default of the `nu` key
/// of the `viscosity` table. A table whose option is off by default (`shifting`, `damping`)
/// holds the defaults of its parameters for when it is on; a table with several models holds
/// the default model and the parameters of every model.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Defaults {
    /// Magnitude of gravity [m/s^2].
    pub gravity: Real,
    /// Reference density of water [kg/m^3].
    pub rho0: Real,
    /// Wendland C2, DualSPHysics' default; free of the cubic spline's pairing instability.
    pub kernel: KernelKind,
    /// `h = coefh sqrt(dim) dp`; DualSPHysics' cases use 0.75-2.
    pub coefh: Real,
    /// `c0 = coefsound sqrt(g h_swl)`: density varies by about 0.25 % in a hydrostatic column.
    pub coefsound: Real,
    /// Tait exponent of water (Monaghan 1994).
    pub gamma: Real,
    /// DualSPHysics' Courant number for the Monaghan & Kos (1999) time step.
    pub cfl: Real,
    pub viscosity: ViscosityDefaults,
    pub diffusion: DiffusionDefaults,
    pub integrator: IntegratorDefaults,
    pub boundary: BoundaryDefaults,
    pub force_precision: ForcePrecision,
    pub shifting: ShiftingDefaults,
    pub tensile_correction: TensileDefaults,
    pub riemann: RiemannDefaults,
    pub kernel_correction: KernelCorrectionDefaults,
    pub damping: DampingDefaults,
    pub gauges: GaugeDefaults,
    /// Stability monitors (docs/stability.md): loose enough that a healthy run never trips
    /// them, tight enough to stop a diverging one within a few steps.
    pub density_band: Real,
    pub lost_fraction_limit: Real,
    pub energy_growth_limit: Real,
}

/// The default viscosity model and the parameters of each model.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ViscosityDefaults {
    /// A `model` tag of [`Viscosity`].
    pub model: &'static str,
    /// Monaghan (1992) artificial viscosity, in the 0.01-0.1 range for free-surface flows.
    pub alpha: Real,
    /// Kinematic viscosity of water at 20 C [m^2/s].
    pub nu: Real,
    /// Smagorinsky constant (Dalrymple & Rogers 2006).
    pub cs: Real,
    /// Blin constant (Dalrymple & Rogers 2006).
    pub ci: Real,
    /// Factor on the viscous term of fluid-wall pairs: walls as viscous as fluid
    /// (DualSPHysics' `ViscoBoundFactor` default).
    pub wall_factor: Real,
}

/// The default density diffusion term and its coefficient.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DiffusionDefaults {
    /// A `model` tag of [`Diffusion`].
    pub model: &'static str,
    /// The standard value (Molteni & Colagrossi 2009; Antuono et al. 2010).
    pub delta: Real,
}

/// The default time integrator and the Verlet scheme's parameter.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct IntegratorDefaults {
    /// A `scheme` tag of [`Integrator`].
    pub scheme: &'static str,
    /// Verlet: one Euler step every this many steps (DualSPHysics' VerletSteps).
    pub euler_every: u32,
}

/// The default wall model and the parameters of each model.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BoundaryDefaults {
    /// A `model` tag of [`Boundary`]: DBC, the dynamic boundary condition (Crespo et al. 2007).
    pub model: &'static str,
    /// Modified DBC's wall velocity: the wall's own (DualSPHysics' default `SlipMode`).
    pub slip: Slip,
}

/// Particle shifting's parameters (shifting is off by default).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ShiftingDefaults {
    /// The law (`lind` or `delta_plus`).
    pub model: ShiftingModel,
    /// `A` of `D = A h |u| dt`, DualSPHysics' value (Skillen et al. 2013 propose 1-6).
    pub coefficient: Real,
}

/// Monaghan's (2000) tensile correction's parameters (off by default).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TensileDefaults {
    /// The law (`monaghan`).
    pub model: TensileModel,
    /// `eps` at positive pressure: DualSPHysics' 0.01 (`GetKernelCubic_Tensil`).
    pub epsilon_pos: Real,
    /// `eps` at negative pressure: Monaghan's (2000) 0.2, DualSPHysics' too.
    pub epsilon_neg: Real,
}

/// The Riemann solver's parameters (off by default: the classic formulation).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RiemannDefaults {
    /// The solver (`acoustic`).
    pub model: RiemannModel,
    /// `eta` of the low-dissipation limiter: Zhang, Hu & Adams' (2017) 3.
    pub limiter: Real,
}

/// The kernel gradient correction's parameter (off by default).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct KernelCorrectionDefaults {
    /// Smallest eigenvalue of the correction matrix from which a particle is corrected: the
    /// free-surface band of Marrone et al. (2010), as the delta-plus shifting's.
    pub min_eigenvalue: Real,
}

/// How free-surface and run-up gauges find the water when the scene does not say.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GaugeDefaults {
    /// Elevation gauges: the kernel volume sum (no gap between particles to fall through).
    pub elevation_method: SurfaceMethod,
    /// Run-up gauges: the kernel volume sum along the segment.
    pub runup_method: RunupMethod,
}

/// The damping zone's parameters (no damping zone by default).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DampingDefaults {
    /// Largest reduction rate [1/s].
    pub strength: Real,
}

impl Default for Defaults {
    fn default() -> Self {
        Defaults {
            gravity: 9.81,
            rho0: 1000.0,
            kernel: KernelKind::Wendland,
            coefh: 1.0,
            coefsound: 20.0,
            gamma: 7.0,
            cfl: 0.2,
            viscosity: ViscosityDefaults { model: "artificial", alpha: 0.01, nu: 1.0e-6, cs: 0.12, ci: 0.0066, wall_factor: 1.0 },
            diffusion: DiffusionDefaults { model: "fourtakas", delta: 0.1 },
            integrator: IntegratorDefaults { scheme: "symplectic", euler_every: 40 },
            boundary: BoundaryDefaults { model: "dbc", slip: Slip::WallVelocity },
            force_precision: ForcePrecision::F64,
            shifting: ShiftingDefaults { model: ShiftingModel::Lind, coefficient: 2.0 },
            tensile_correction: TensileDefaults { model: TensileModel::Monaghan, epsilon_pos: 0.01, epsilon_neg: 0.2 },
            riemann: RiemannDefaults { model: RiemannModel::Acoustic, limiter: 3.0 },
            kernel_correction: KernelCorrectionDefaults { min_eigenvalue: 0.75 },
            damping: DampingDefaults { strength: 10.0 },
            gauges: GaugeDefaults { elevation_method: SurfaceMethod::Kernel, runup_method: RunupMethod::Kernel },
            density_band: 0.5,
            lost_fraction_limit: 0.01,
            energy_growth_limit: 0.05,
        }
    }
}

impl Defaults {
    /// The defaults as JSON (nested as the scene's tables).
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_else(|e| unreachable!("the defaults always serialise: {e}"))
    }
}

/// serde's `default = "path"` takes a function: one per defaulted key, each reading
/// [`Defaults::default`], so the values live there only. A tagged option's default is its
/// default model parsed from its tag alone, so that model's parameters take their defaults too.
pub(crate) mod serde_default {
    use super::*;

    macro_rules! from_defaults {
        ($($name:ident: $ty:ty = $($field:ident).+;)*) => {
            $(pub(crate) fn $name() -> $ty {
                Defaults::default().$($field).+
            })*
        };
    }

    from_defaults! {
        gravity: Real = gravity;
        rho0: Real = rho0;
        kernel: KernelKind = kernel;
        coefh: Real = coefh;
        coefsound: Real = coefsound;
        gamma: Real = gamma;
        cfl: Real = cfl;
        alpha: Real = viscosity.alpha;
        nu: Real = viscosity.nu;
        cs: Real = viscosity.cs;
        ci: Real = viscosity.ci;
        visc_wall_factor: Real = viscosity.wall_factor;
        delta: Real = diffusion.delta;
        euler_every: u32 = integrator.euler_every;
        mdbc_slip: Slip = boundary.slip;
        force_precision: ForcePrecision = force_precision;
        shifting_model: ShiftingModel = shifting.model;
        shifting_coefficient: Real = shifting.coefficient;
        tensile_model: TensileModel = tensile_correction.model;
        tensile_epsilon_pos: Real = tensile_correction.epsilon_pos;
        tensile_epsilon_neg: Real = tensile_correction.epsilon_neg;
        riemann_model: RiemannModel = riemann.model;
        riemann_limiter: Real = riemann.limiter;
        kgc_min_eigenvalue: Real = kernel_correction.min_eigenvalue;
        damping_strength: Real = damping.strength;
        elevation_method: SurfaceMethod = gauges.elevation_method;
        runup_method: RunupMethod = gauges.runup_method;
        density_band: Real = density_band;
        lost_fraction_limit: Real = lost_fraction_limit;
        energy_growth_limit: Real = energy_growth_limit;
    }

    /// A tagged option from its tag alone: its parameters take their serde defaults.
    fn tagged<T: serde::de::DeserializeOwned>(key: &str, tag: &str) -> T {
        serde_json::from_value(serde_json::json!({ key: tag }))
            .unwrap_or_else(|e| unreachable!("the default tag {tag:?} names a model with defaulted parameters: {e}"))
    }

    pub(crate) fn viscosity() -> Viscosity {
        tagged("model", Defaults::default().viscosity.model)
    }

    pub(crate) fn diffusion() -> Diffusion {
        tagged("model", Defaults::default().diffusion.model)
    }

    pub(crate) fn integrator() -> Integrator {
        tagged("scheme", Defaults::default().integrator.scheme)
    }

    pub(crate) fn boundary() -> Boundary {
        tagged("model", Defaults::default().boundary.model)
    }
}

#[cfg(test)]
mod tests {
    use super::serde_default::*;
    use super::*;

    #[test]
    fn tagged_defaults_are_the_default_models_with_default_parameters() {
        assert_eq!(viscosity(), Viscosity::Artificial { alpha: 0.01, wall_factor: 1.0 });
        assert_eq!(diffusion(), Diffusion::Fourtakas { delta: 0.1 });
        assert_eq!(integrator(), Integrator::Symplectic);
        assert_eq!(boundary(), Boundary::Dbc);
        let mdbc: Boundary = serde_json::from_str(r#"{"model": "mdbc"}"#).expect("mdbc");
        assert_eq!(mdbc, Boundary::Mdbc { slip: Slip::WallVelocity });
    }

    #[test]
    fn defaults_serialise_as_the_scene_tables() {
        let v: serde_json::Value = serde_json::from_str(&Defaults::default().to_json()).expect("json");
        assert_eq!(v["viscosity"]["model"], "artificial");
        assert_eq!(v["boundary"]["model"], "dbc");
        assert_eq!(v["kernel"], "wendland");
        assert_eq!(v["force_precision"], "f64");
        assert_eq!(v["integrator"]["euler_every"], 40);
    }
}
