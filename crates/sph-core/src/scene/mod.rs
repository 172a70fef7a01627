//! The scene: geometry, physics options and numerical parameters, as plain serde data.
//!
//! Python builds a scene, the core checks every field ([`Scene::validate`], in `validate.rs`)
//! before anything is allocated, and [`crate::build`] turns it into a monomorphised solver.
//! Unknown keys are refused. Every optional key's default is in [`Defaults`].

mod defaults;
mod geometry;
mod numerics;
mod validate;

use serde::{Deserialize, Serialize};

use self::defaults::serde_default as default;
pub(crate) use self::defaults::serde_default;
pub use self::defaults::{
    BoundaryDefaults, DampingDefaults, Defaults, DiffusionDefaults, GaugeDefaults, IntegratorDefaults, ShiftingDefaults, TensileDefaults,
    ViscosityDefaults,
};
pub use self::geometry::{BoxSpec, Damping, Obstacle};
pub use self::numerics::{Boundary, Diffusion, ForcePrecision, Integrator, Shifting, ShiftingModel, Slip, Viscosity};
use crate::error::{Error, Result};
use crate::kernel::KernelKind;
use crate::math::Real;
use crate::motion::Paddle;
pub use crate::physics::kgc::KernelCorrection;
pub use crate::physics::riemann::{RiemannModel, RiemannSolver};
pub use crate::physics::tensile::{TensileCorrection, TensileModel};
use crate::probes::GaugeSpec;

/// A complete scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    pub dim: usize,
    /// Initial particle spacing [m].
    pub dp: Real,
    /// Magnitude of gravity [m/s^2], acting along -z.
    #[serde(default = "default::gravity")]
    pub gravity: Real,
    /// Reference density [kg/m^3].
    #[serde(default = "default::rho0")]
    pub rho0: Real,
    #[serde(default = "default::kernel")]
    pub kernel: KernelKind,
    /// `h = coefh * sqrt(dim) * dp`.
    #[serde(default = "default::coefh")]
    pub coefh: Real,
    /// `c0 = coefsound * sqrt(g * h_swl)`.
    #[serde(default = "default::coefsound")]
    pub coefsound: Real,
    /// Tait exponent.
    #[serde(default = "default::gamma")]
    pub gamma: Real,
    /// Depth used for the sound speed [m]; default: highest fluid top above the tank floor.
    #[serde(default)]
    pub h_swl: Option<Real>,
    /// Courant number of the variable time step.
    #[serde(default = "default::cfl")]
    pub cfl: Real,
    #[serde(default = "default::viscosity")]
    pub viscosity: Viscosity,
    #[serde(default = "default::diffusion")]
    pub diffusion: Diffusion,
    #[serde(default = "default::integrator")]
    pub integrator: Integrator,
    /// Wall boundary model.
    #[serde(default = "default::boundary")]
    pub boundary: Boundary,
    /// Arithmetic of the force loop's pair terms (the SPS closure always uses f64).
    #[serde(default = "default::force_precision")]
    pub force_precision: ForcePrecision,
    /// Particle shifting; none by default.
    #[serde(default)]
    pub shifting: Option<Shifting>,
    /// Monaghan's (2000) tensile correction (`physics/tensile.rs`; cubic spline only); none by
    /// default. Left out of the scene's JSON when none, so scenes written before it existed
    /// resolve to the same JSON.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tensile_correction: Option<TensileCorrection>,
    /// Riemann-solver SPH with the low-dissipation limiter (`physics/riemann.rs`); the classic
    /// formulation without it. Left out of the scene's JSON when absent, as `tensile_correction`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub riemann: Option<RiemannSolver>,
    /// Kernel gradient correction of the pressure term (`physics/kgc.rs`); none by default, and
    /// left out of the scene's JSON then.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kernel_correction: Option<KernelCorrection>,
    /// Inner faces of the tank (floor and side walls; the top is open).
    pub tank: BoxSpec,
    /// The side wall `y = tank.min[1]` is a plane of symmetry (3D): the tank is half of one
    /// mirrored through it. A body may then cross that wall (a pile whose axis lies on it);
    /// the wall's particles inside the body's shell are the body's, standing for its mirror
    /// half, so that its force is the pull of the fluid in the tank on the whole body, half the
    /// mirrored tank's force (`geometry::wall_bodies`). The wall stays a wall of the scene's
    /// wall model: give it free slip (inviscid walls) for a plane of symmetry. Left out of the
    /// scene's JSON when false.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub symmetry_y_min: bool,
    #[serde(default)]
    pub obstacles: Vec<Obstacle>,
    /// Fluid boxes, initialised hydrostatically from each box's top.
    pub fluid: Vec<BoxSpec>,
    /// Wall thickness in particle layers; default `ceil(2h/dp)` covers the kernel support.
    #[serde(default)]
    pub boundary_layers: Option<usize>,
    /// Density band of the stability monitor: a density outside `rho0 (1 -+ x)` stops the run.
    #[serde(default = "default::density_band")]
    pub density_band: Real,
    /// Fluid particles leaving the domain (the tank and its walls, and one tank height above it)
    /// are frozen and excluded; the run stops when more than this fraction of the fluid is out.
    #[serde(default = "default::lost_fraction_limit")]
    pub lost_fraction_limit: Real,
    /// Without a paddle, the run stops when the fluid's mechanical energy exceeds its initial
    /// value by more than this fraction of the initial potential energy above the tank floor.
    #[serde(default = "default::energy_growth_limit")]
    pub energy_growth_limit: Real,
    /// Memory the run may use [bytes]; default: 80 % of the machine's available memory
    /// (`MemAvailable` of /proc/meminfo; no check where that is unknown). A scene whose
    /// estimated particle arrays exceed it is refused before anything is allocated.
    #[serde(default)]
    pub memory_limit_bytes: Option<u64>,
    /// Wave-maker paddle; none for tanks and dam breaks.
    #[serde(default)]
    pub paddle: Option<Paddle>,
    #[serde(default)]
    pub damping: Option<Damping>,
    #[serde(default)]
    pub gauges: Vec<GaugeSpec>,
}

impl Scene {
    /// Parses a scene from JSON; errors name the offending field's path.
    pub fn from_json(text: &str) -> Result<Self> {
        let de = &mut serde_json::Deserializer::from_str(text);
        let scene: Scene = serde_path_to_error::deserialize(de).map_err(|e| {
            let path = e.path().to_string();
            let field = if path.is_empty() || path == "." { "scene".to_string() } else { path };
            Error::invalid(field, e.into_inner().to_string())
        })?;
        scene.validate()?;
        Ok(scene)
    }

    /// The scene as the core runs it, every default filled in, as JSON (what Python compares
    /// its builders against: the core's defaults are the only ones).
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_else(|e| unreachable!("a Scene always serialises: {e}"))
    }

    /// Smoothing length `h = coefh * sqrt(dim) * dp`.
    pub fn h(&self) -> Real {
        self.coefh * (self.dim as Real).sqrt() * self.dp
    }

    /// Wall thickness in layers: enough to cover the kernel support `2h`.
    pub fn layers(&self) -> usize {
        self.boundary_layers.unwrap_or_else(|| self.layers_for_coefh(self.coefh))
    }

    /// The layers that cover the support `2h` of a smoothing length of `coefh`.
    pub(crate) fn layers_for_coefh(&self, coefh: Real) -> usize {
        (2.0 * coefh * (self.dim as Real).sqrt() - 1e-9).ceil() as usize
    }

    /// Still-water depth used for the sound speed.
    pub fn h_swl(&self) -> Real {
        self.h_swl.unwrap_or_else(|| {
            let floor = self.tank.min[self.dim - 1];
            self.fluid.iter().map(|b| b.max[self.dim - 1] - floor).fold(0.0, Real::max)
        })
    }
}

impl Scene {
    /// Still-water level: the top of the highest fluid box.
    pub fn still_water_level(&self) -> Real {
        let up = self.dim - 1;
        self.fluid.iter().map(|b| b.max[up]).fold(Real::NEG_INFINITY, Real::max)
    }

    /// Estimated particle count: fluid boxes plus a wall shell `layers` thick around the tank.
    pub fn estimated_particles(&self) -> f64 {
        self.estimated_particles_with(self.layers())
    }

    /// [`Scene::estimated_particles`] with walls of `layers` layers.
    pub(crate) fn estimated_particles_with(&self, layers: usize) -> f64 {
        let dim = self.dim;
        let cell = self.dp.powi(dim as i32);
        let fluid: f64 = self.fluid.iter().map(|b| (0..dim).map(|k| b.max[k] - b.min[k]).product::<f64>()).sum();
        let t = layers as f64 * self.dp;
        let outer: f64 = (0..dim)
            .map(|k| self.tank.max[k] - self.tank.min[k] + if k == dim - 1 { t } else { 2.0 * t })
            .product();
        let inner: f64 = (0..dim).map(|k| self.tank.max[k] - self.tank.min[k]).product();
        (fluid + (outer - inner)) / cell
    }

    /// Cells of the neighbour grid: the tank with its walls and as much again above it, in
    /// cells of side `h` (half the support, see `simulation.rs`).
    pub fn estimated_cells(&self) -> f64 {
        self.estimated_cells_with(self.layers())
    }

    /// [`Scene::estimated_cells`] with walls of `layers` layers.
    pub(crate) fn estimated_cells_with(&self, layers: usize) -> f64 {
        let dim = self.dim;
        let t = layers as f64 * self.dp;
        let cell = self.h();
        (0..dim)
            .map(|k| {
                let extent = self.tank.max[k] - self.tank.min[k];
                let extent = if k == dim - 1 { 2.0 * extent + 2.0 * t } else { extent + 2.0 * t };
                (extent / cell).floor().max(1.0)
            })
            .product()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dambreak_json(extra: &str) -> String {
        format!(
            r#"{{"dim": 2, "dp": 0.05, "tank": {{"min": [0, 0], "max": [4, 3]}},
                "fluid": [{{"min": [0, 0], "max": [1, 2]}}] {extra}}}"#
        )
    }

    #[test]
    fn defaults_parse() {
        let s = Scene::from_json(&dambreak_json("")).expect("valid scene");
        assert_eq!(s.kernel, KernelKind::Wendland);
        assert_eq!(s.h_swl(), 2.0);
        assert_eq!(s.layers(), 3);
    }

    #[test]
    fn options_named_by_their_tag_alone_take_the_default_parameters() {
        let d = Defaults::default();
        let s = Scene::from_json(&dambreak_json(
            r#", "viscosity": {"model": "laminar_sps"}, "diffusion": {"model": "molteni"}, "integrator": {"scheme": "verlet"}, "shifting": {}"#,
        ))
        .expect("valid scene");
        assert_eq!(s.viscosity, Viscosity::LaminarSps { nu: d.viscosity.nu, cs: d.viscosity.cs, ci: d.viscosity.ci, wall_factor: d.viscosity.wall_factor });
        assert_eq!(s.diffusion, Diffusion::Molteni { delta: d.diffusion.delta });
        assert_eq!(s.integrator, Integrator::Verlet { euler_every: d.integrator.euler_every });
        assert_eq!(s.shifting.map(|sh| sh.coefficient), Some(d.shifting.coefficient));
        let plain = Scene::from_json(&dambreak_json("")).expect("valid scene");
        assert_eq!((plain.gravity, plain.coefh, plain.boundary), (d.gravity, d.coefh, super::defaults::serde_default::boundary()));
        assert_eq!((plain.density_band, plain.energy_growth_limit), (d.density_band, d.energy_growth_limit));
        // gauges without a method take the Defaults' methods
        let gauged = Scene::from_json(&dambreak_json(
            r#", "gauges": [{"type": "elevation", "name": "e", "position": [2, 0], "interval": 0.1},
                            {"type": "runup", "name": "r", "start": [2, 0], "end": [3, 1], "interval": 0.1}]"#,
        ))
        .expect("valid scene");
        match (&gauged.gauges[0], &gauged.gauges[1]) {
            (GaugeSpec::Elevation { method: e, .. }, GaugeSpec::Runup { method: r, .. }) => {
                assert_eq!((*e, *r), (d.gauges.elevation_method, d.gauges.runup_method));
            }
            other => panic!("gauges parsed as {other:?}"),
        }
    }

    #[test]
    fn errors_name_the_field() {
        let cases = [
            (dambreak_json(r#", "cfl": -1"#), "cfl"),
            (dambreak_json(r#", "coefh": 0.3"#), "coefh"),
            (dambreak_json(r#", "density_band": 1.5"#), "density_band"),
            (dambreak_json(r#", "energy_growth_limit": 2"#), "energy_growth_limit"),
            (dambreak_json(r#", "kernel": "gauss""#), "kernel"),
            (dambreak_json(r#", "viscosity": {"model": "artificial", "alpha": -0.1}"#), "viscosity.alpha"),
            (dambreak_json(r#", "viscosity": {"model": "magic"}"#), "viscosity"),
            (dambreak_json(r#", "viscosity": {"model": "laminar", "wall_factor": -1}"#), "viscosity.wall_factor"),
            (dambreak_json(r#", "bogus": 1"#), "bogus"),
            (dambreak_json(r#", "shifting": {"coefficient": 0}"#), "shifting.coefficient"),
            (dambreak_json(r#", "shifting": {"surface_threshold": 2.0}"#), "shifting.surface_threshold"),
            (dambreak_json(r#", "shifting": {"coeff": 2}"#), "shifting"),
            (dambreak_json(r#", "shifting": {"model": "delta_plus", "surface_threshold": 1.5}"#), "shifting.surface_threshold"),
            (dambreak_json(r#", "shifting": {"model": "fick"}"#), "shifting"),
            (dambreak_json(r#", "boundary": {"model": "mirror"}"#), "boundary"),
            // the Riemann solver replaces the artificial viscosity and the density diffusion
            (dambreak_json(r#", "riemann": {}"#), "viscosity"),
            (dambreak_json(r#", "riemann": {}, "viscosity": {"model": "laminar"}"#), "diffusion"),
            (dambreak_json(r#", "riemann": {"limiter": -1}, "viscosity": {"model": "laminar"}, "diffusion": {"model": "none"}"#), "riemann.limiter"),
            (dambreak_json(r#", "riemann": {"model": "hllc"}"#), "riemann"),
            (dambreak_json(r#", "riemann": {"eta": 3}"#), "riemann"),
            (dambreak_json(r#", "riemann": {}, "viscosity": {"model": "laminar"}, "diffusion": {"model": "none"}, "force_precision": "f32""#), "force_precision"),
            (dambreak_json(r#", "riemann": {}, "viscosity": {"model": "laminar"}, "diffusion": {"model": "none"}, "integrator": {"scheme": "verlet"}"#), "integrator"),
            (dambreak_json(r#", "kernel_correction": {"min_eigenvalue": 0}"#), "kernel_correction.min_eigenvalue"),
            (dambreak_json(r#", "kernel_correction": {"min_eigenvalue": 1.5}"#), "kernel_correction.min_eigenvalue"),
            (dambreak_json(r#", "kernel_correction": {"lambda": 0.5}"#), "kernel_correction"),
            (dambreak_json(r#", "kernel_correction": {}, "force_precision": "f32""#), "force_precision"),
            (dambreak_json(r#", "kernel_correction": {}, "kernel": "cubic_spline", "tensile_correction": {}"#), "tensile_correction"),
            (dambreak_json(r#", "memory_limit_bytes": 1000"#), "dp"),
            // the wall shell of a huge support or of too many layers: not dp's fault
            (dambreak_json(r#", "coefh": 1e6"#), "coefh"),
            (dambreak_json(r#", "boundary_layers": 100000000"#), "boundary_layers"),
            (dambreak_json(r#", "obstacles": [{"shape": "plane", "point": [0, 0], "normal": [0, 0]}]"#), "obstacles[0].normal"),
            (r#"{"dim": 2, "dp": 0.0, "tank": {"min": [0, 0], "max": [4, 3]}, "fluid": [{"min": [0, 0], "max": [1, 2]}]}"#.to_string(), "dp"),
            (r#"{"dim": 2, "dp": 0.1, "tank": {"min": [0, 0], "max": [4, 3]}, "fluid": [{"min": [0, 0], "max": [5, 2]}]}"#.to_string(), "fluid[0]"),
        ];
        for (json, field) in cases {
            match Scene::from_json(&json) {
                Err(Error::InvalidScene { field: f, reason }) => {
                    assert!(f.starts_with(field), "expected field {field}, got {f}: {reason}")
                }
                other => panic!("expected an error for {field}, got {other:?}"),
            }
        }
    }
}
