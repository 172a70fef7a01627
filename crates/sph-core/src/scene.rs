//! The scene: geometry, physics options and numerical parameters, as plain serde data.
//!
//! Python builds a scene, the core checks every field ([`Scene::validate`]) before anything is
//! allocated, and [`crate::build`] turns it into a monomorphised solver. Unknown keys are refused.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::kernel::KernelKind;
use crate::math::Real;
use crate::motion::{Paddle, PaddleKind};
use crate::probes::GaugeSpec;

/// Viscosity model (DESIGN.md section 2). One per scene.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub enum Viscosity {
    /// Monaghan (1992) artificial viscosity with coefficient `alpha`.
    Artificial { alpha: Real },
    /// Lo & Shao (2002) laminar viscosity, kinematic viscosity `nu` [m^2/s].
    Laminar { nu: Real },
    /// Laminar viscosity plus the SPS Smagorinsky closure (Dalrymple & Rogers 2006).
    LaminarSps {
        nu: Real,
        #[serde(default = "default_cs")]
        cs: Real,
        #[serde(default = "default_ci")]
        ci: Real,
    },
}

fn default_cs() -> Real {
    0.12
}
fn default_ci() -> Real {
    0.0066
}

/// Density diffusion term in the continuity equation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub enum Diffusion {
    None,
    /// Molteni & Colagrossi (2009).
    Molteni { delta: Real },
    /// Fourtakas et al. (2019): the hydrostatic part of the density difference is removed,
    /// taken in pressure (`physics::forces::hydrostatic_free_difference`).
    Fourtakas { delta: Real },
}

/// Time integrator (DESIGN.md section 2).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "scheme", rename_all = "snake_case", deny_unknown_fields)]
pub enum Integrator {
    Symplectic,
    Verlet {
        #[serde(default = "default_euler_every")]
        euler_every: u32,
    },
}

fn default_euler_every() -> u32 {
    40
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
}

/// Floating-point type of the fluid force loop's pair arithmetic. The state (positions,
/// velocities, densities) and the sums over neighbours stay in f64 either way.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ForcePrecision {
    /// Every pair term in f64.
    #[default]
    F64,
    /// Pair terms in f32, eight to an AVX2 register instead of four, as DualSPHysics forms
    /// its forces. Neighbour offsets are taken in f64 before rounding, and pressures and
    /// density differences from `rho/rho0 - 1` formed in f64, so no term loses more than f32's
    /// relative precision (about 6e-8); docs/benchmarks.md measures the effect.
    F32,
}

/// Fickian particle shifting (Lind et al. 2012, J. Comput. Phys. 231, Eqs. 22-23): after each
/// step a fluid particle moves by `dr = -a_fs D grad C`, with the concentration gradient
/// `grad C = sum_b V_b grad W_ab` over fluid and wall neighbours and Skillen et al. (2013)'s
/// coefficient `D = A h |u| dt` (their Eq. 26), so still water is never shifted. Free-surface
/// particles lack half their neighbours and `grad C` would push them out of the water: the
/// particle divergence `div r = -sum_b V_b r_ab . grad W_ab` (Lee et al. 2008; `dim` in the
/// bulk) detects them, and `a_fs` ramps from 0 at `div r = surface_threshold` to 1 at
/// `div r = dim` (DualSPHysics' free-surface correction, Mokos 2013, with its thresholds 1.5
/// in 2D and 2.75 in 3D). The shift only moves particles; it does not correct the velocity or
/// density (as DualSPHysics' Lind shifting).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shifting {
    /// `A` of `D = A h |u| dt`; Skillen et al. (2013) propose 1-6, DualSPHysics uses 2.
    #[serde(default = "default_shifting_coefficient")]
    pub coefficient: Real,
    /// Particle divergence at and below which a particle is on the free surface and not
    /// shifted; default 1.5 in 2D, 2.75 in 3D. Must lie between 0 and `dim`.
    #[serde(default)]
    pub surface_threshold: Option<Real>,
}

fn default_shifting_coefficient() -> Real {
    2.0
}

impl Shifting {
    /// The free-surface threshold for `dim` (the default when none is given).
    pub fn threshold(&self, dim: usize) -> Real {
        self.surface_threshold.unwrap_or(if dim == 2 { 1.5 } else { 2.75 })
    }
}

/// An axis-aligned box `[min, max]`; vectors have `dim` entries, the last vertical.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSpec {
    pub min: Vec<Real>,
    pub max: Vec<Real>,
}

/// A solid obstacle inside the tank, sampled into wall particles.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum Obstacle {
    Box { min: Vec<Real>, max: Vec<Real> },
    /// Solid on the side opposite `normal` (a beach: normal pointing up and offshore), clipped to
    /// the tank.
    Plane { point: Vec<Real>, normal: Vec<Real> },
    /// Piecewise-linear bed: solid below the polyline through `(x[i], z[i])` (extruded across
    /// the width in 3D), between `x[0]` and the last `x`. Bars, beaches, measured bathymetry.
    Profile { x: Vec<Real>, z: Vec<Real> },
    /// A closed triangle mesh with outward-facing triangles (3D only): bathymetry or structures
    /// from an STL file (read in Python). Vertices are `[x, y, z]`; triangles index them.
    Mesh { vertices: Vec<Vec<Real>>, triangles: Vec<[u32; 3]> },
}

/// Velocity damping zone at the far end of a flume (DualSPHysics' damping zone form):
/// after each step, fluid velocities are scaled by `1 - dt * strength * s^2`, where
/// `s = (x - x_start) / (x_end - x_start)` clamped to `[0, 1]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Damping {
    pub x_start: Real,
    pub x_end: Real,
    /// Largest reduction rate [1/s].
    #[serde(default = "default_damping_strength")]
    pub strength: Real,
}

fn default_damping_strength() -> Real {
    10.0
}

/// A complete scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    pub dim: usize,
    /// Initial particle spacing [m].
    pub dp: Real,
    /// Magnitude of gravity [m/s^2], acting along -z.
    #[serde(default = "default_gravity")]
    pub gravity: Real,
    /// Reference density [kg/m^3].
    #[serde(default = "default_rho0")]
    pub rho0: Real,
    #[serde(default = "default_kernel")]
    pub kernel: KernelKind,
    /// `h = coefh * sqrt(dim) * dp`.
    #[serde(default = "default_coefh")]
    pub coefh: Real,
    /// `c0 = coefsound * sqrt(g * h_swl)`.
    #[serde(default = "default_coefsound")]
    pub coefsound: Real,
    /// Tait exponent.
    #[serde(default = "default_gamma")]
    pub gamma: Real,
    /// Depth used for the sound speed [m]; default: highest fluid top above the tank floor.
    #[serde(default)]
    pub h_swl: Option<Real>,
    /// Courant number of the variable time step.
    #[serde(default = "default_cfl")]
    pub cfl: Real,
    #[serde(default = "default_viscosity")]
    pub viscosity: Viscosity,
    #[serde(default = "default_diffusion")]
    pub diffusion: Diffusion,
    #[serde(default = "default_integrator")]
    pub integrator: Integrator,
    /// Wall boundary model; DBC by default.
    #[serde(default = "default_boundary")]
    pub boundary: Boundary,
    /// Arithmetic of the force loop's pair terms (the SPS closure always uses f64).
    #[serde(default)]
    pub force_precision: ForcePrecision,
    /// Particle shifting; none by default.
    #[serde(default)]
    pub shifting: Option<Shifting>,
    /// Inner faces of the tank (floor and side walls; the top is open).
    pub tank: BoxSpec,
    #[serde(default)]
    pub obstacles: Vec<Obstacle>,
    /// Fluid boxes, initialised hydrostatically from each box's top.
    pub fluid: Vec<BoxSpec>,
    /// Wall thickness in particle layers; default `ceil(2h/dp)` covers the kernel support.
    #[serde(default)]
    pub boundary_layers: Option<usize>,
    /// Density band of the stability monitor: a density outside `rho0 (1 -+ x)` stops the run.
    #[serde(default = "default_density_band")]
    pub density_band: Real,
    /// Fluid particles leaving the domain (the tank and its walls, and one tank height above it)
    /// are frozen and excluded; the run stops when more than this fraction of the fluid is out.
    #[serde(default = "default_lost_fraction_limit")]
    pub lost_fraction_limit: Real,
    /// Without a paddle, the run stops when the fluid's mechanical energy exceeds its initial
    /// value by more than this fraction of the initial potential energy above the tank floor.
    #[serde(default = "default_energy_growth_limit")]
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

fn default_gravity() -> Real {
    9.81
}
fn default_rho0() -> Real {
    1000.0
}
fn default_kernel() -> KernelKind {
    KernelKind::Wendland
}
fn default_coefh() -> Real {
    1.0
}
fn default_coefsound() -> Real {
    20.0
}
fn default_gamma() -> Real {
    7.0
}
fn default_cfl() -> Real {
    0.2
}
fn default_viscosity() -> Viscosity {
    Viscosity::Artificial { alpha: 0.01 }
}
fn default_diffusion() -> Diffusion {
    Diffusion::Fourtakas { delta: 0.1 }
}
fn default_boundary() -> Boundary {
    Boundary::Dbc
}
fn default_integrator() -> Integrator {
    Integrator::Symplectic
}
fn default_density_band() -> Real {
    0.5
}
fn default_lost_fraction_limit() -> Real {
    0.01
}
fn default_energy_growth_limit() -> Real {
    0.05
}

fn check_positive(field: &str, v: Real) -> Result<()> {
    if !v.is_finite() {
        return Err(Error::invalid(field, format!("must be a finite number, got {v}")));
    }
    if v <= 0.0 {
        return Err(Error::invalid(field, format!("must be > 0, got {v}")));
    }
    Ok(())
}

fn check_non_negative(field: &str, v: Real) -> Result<()> {
    if !v.is_finite() || v < 0.0 {
        return Err(Error::invalid(field, format!("must be a finite number >= 0, got {v}")));
    }
    Ok(())
}

fn check_vector(field: &str, v: &[Real], dim: usize) -> Result<()> {
    if v.len() != dim {
        return Err(Error::invalid(field, format!("must have {dim} components (dim = {dim}), got {}", v.len())));
    }
    if let Some(x) = v.iter().find(|x| !x.is_finite()) {
        return Err(Error::invalid(field, format!("components must be finite, got {x}")));
    }
    Ok(())
}

fn check_box(field: &str, b: &BoxSpec, dim: usize) -> Result<()> {
    check_vector(&format!("{field}.min"), &b.min, dim)?;
    check_vector(&format!("{field}.max"), &b.max, dim)?;
    for i in 0..dim {
        if b.max[i] <= b.min[i] {
            return Err(Error::invalid(
                field,
                format!("max[{i}] = {} must be greater than min[{i}] = {}", b.max[i], b.min[i]),
            ));
        }
    }
    Ok(())
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
        self.boundary_layers.unwrap_or_else(|| (2.0 * self.h() / self.dp - 1e-9).ceil() as usize)
    }

    /// Still-water depth used for the sound speed.
    pub fn h_swl(&self) -> Real {
        self.h_swl.unwrap_or_else(|| {
            let floor = self.tank.min[self.dim - 1];
            self.fluid.iter().map(|b| b.max[self.dim - 1] - floor).fold(0.0, Real::max)
        })
    }

    /// Checks every field; the error names the field and the reason.
    pub fn validate(&self) -> Result<()> {
        if self.dim != 2 && self.dim != 3 {
            return Err(Error::invalid("dim", format!("must be 2 or 3, got {}", self.dim)));
        }
        let dim = self.dim;
        check_positive("dp", self.dp)?;
        check_non_negative("gravity", self.gravity)?;
        check_positive("rho0", self.rho0)?;
        check_positive("coefh", self.coefh)?;
        check_positive("coefsound", self.coefsound)?;
        check_positive("gamma", self.gamma)?;
        check_positive("cfl", self.cfl)?;
        if self.cfl > 1.0 {
            return Err(Error::invalid("cfl", format!("must be <= 1, got {}", self.cfl)));
        }
        check_positive("density_band", self.density_band)?;
        check_non_negative("lost_fraction_limit", self.lost_fraction_limit)?;
        if self.lost_fraction_limit > 1.0 {
            return Err(Error::invalid("lost_fraction_limit", format!("must be <= 1, got {}", self.lost_fraction_limit)));
        }
        check_positive("energy_growth_limit", self.energy_growth_limit)?;
        if let Some(d) = self.h_swl {
            check_positive("h_swl", d)?;
        }
        match self.viscosity {
            Viscosity::Artificial { alpha } => check_non_negative("viscosity.alpha", alpha)?,
            Viscosity::Laminar { nu } => check_non_negative("viscosity.nu", nu)?,
            Viscosity::LaminarSps { nu, cs, ci } => {
                check_non_negative("viscosity.nu", nu)?;
                check_non_negative("viscosity.cs", cs)?;
                check_non_negative("viscosity.ci", ci)?;
                if self.force_precision == ForcePrecision::F32 {
                    return Err(Error::invalid(
                        "force_precision",
                        "f32 pair terms exist in the batched force loop only; the SPS closure runs the f64 loop, so use f64",
                    ));
                }
            }
        }
        match self.diffusion {
            Diffusion::None => {}
            Diffusion::Molteni { delta } | Diffusion::Fourtakas { delta } => {
                check_non_negative("diffusion.delta", delta)?
            }
        }
        if let Integrator::Verlet { euler_every } = self.integrator {
            if euler_every == 0 {
                return Err(Error::invalid("integrator.euler_every", "must be >= 1"));
            }
        }
        if let Some(sh) = self.shifting {
            check_positive("shifting.coefficient", sh.coefficient)?;
            let t = sh.threshold(dim);
            if !t.is_finite() || t <= 0.0 || t >= dim as Real {
                return Err(Error::invalid(
                    "shifting.surface_threshold",
                    format!("must lie strictly between 0 and dim = {dim} (the bulk's particle divergence), got {t}"),
                ));
            }
        }
        if let Some(0) = self.boundary_layers {
            return Err(Error::invalid("boundary_layers", "must be >= 1"));
        }
        check_box("tank", &self.tank, dim)?;
        for (i, o) in self.obstacles.iter().enumerate() {
            let f = format!("obstacles[{i}]");
            match o {
                Obstacle::Box { min, max } => {
                    check_box(&f, &BoxSpec { min: min.clone(), max: max.clone() }, dim)?
                }
                Obstacle::Mesh { vertices, triangles } => {
                    if dim != 3 {
                        return Err(Error::invalid(f, "a triangle mesh needs dim = 3"));
                    }
                    if triangles.is_empty() {
                        return Err(Error::invalid(format!("{f}.triangles"), "needs at least one triangle"));
                    }
                    for (j, v) in vertices.iter().enumerate() {
                        check_vector(&format!("{f}.vertices[{j}]"), v, 3)?;
                    }
                    if let Some((j, t)) = triangles.iter().enumerate().find(|(_, t)| t.iter().any(|&i| i as usize >= vertices.len())) {
                        return Err(Error::invalid(
                            format!("{f}.triangles[{j}]"),
                            format!("{t:?} indexes past the {} vertices", vertices.len()),
                        ));
                    }
                }
                Obstacle::Profile { x, z } => {
                    if x.len() != z.len() || x.len() < 2 {
                        return Err(Error::invalid(
                            format!("{f}.z"),
                            format!("needs as many values as x, at least 2 (x: {}, z: {})", x.len(), z.len()),
                        ));
                    }
                    if let Some(v) = x.iter().chain(z).find(|v| !v.is_finite()) {
                        return Err(Error::invalid(f, format!("values must be finite, got {v}")));
                    }
                    if let Some(i) = x.windows(2).position(|w| w[1] <= w[0]) {
                        return Err(Error::invalid(format!("{f}.x"), format!("must increase strictly (x[{i}] >= x[{}])", i + 1)));
                    }
                }
                Obstacle::Plane { point, normal } => {
                    check_vector(&format!("{f}.point"), point, dim)?;
                    check_vector(&format!("{f}.normal"), normal, dim)?;
                    let n2: Real = normal.iter().map(|x| x * x).sum();
                    if n2 < 1e-24 {
                        return Err(Error::invalid(format!("{f}.normal"), "must not be the zero vector"));
                    }
                }
            }
        }
        if self.fluid.is_empty() {
            return Err(Error::invalid("fluid", "at least one fluid box is needed"));
        }
        let tol = 1e-9 * self.dp;
        for (i, b) in self.fluid.iter().enumerate() {
            let f = format!("fluid[{i}]");
            check_box(&f, b, dim)?;
            for k in 0..dim {
                let upper_ok = k == dim - 1 || b.max[k] <= self.tank.max[k] + tol;
                if b.min[k] < self.tank.min[k] - tol || !upper_ok || b.max[k] > self.tank.max[k] + tol {
                    return Err(Error::invalid(
                        f,
                        format!(
                            "fluid box [{:?}, {:?}] does not fit in the tank [{:?}, {:?}] (axis {k})",
                            b.min, b.max, self.tank.min, self.tank.max
                        ),
                    ));
                }
            }
            for k in 0..dim {
                if b.max[k] - b.min[k] < self.dp {
                    return Err(Error::invalid(
                        f,
                        format!("extent {} along axis {k} is smaller than dp = {}", b.max[k] - b.min[k], self.dp),
                    ));
                }
            }
        }
        self.validate_flume()?;
        self.validate_memory()?;
        for k in 0..dim {
            let extent = self.tank.max[k] - self.tank.min[k];
            if extent < 2.0 * self.dp {
                return Err(Error::invalid(
                    "tank",
                    format!("extent {extent} along axis {k} is smaller than 2 dp = {}", 2.0 * self.dp),
                ));
            }
        }
        Ok(())
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
        let dim = self.dim;
        let cell = self.dp.powi(dim as i32);
        let fluid: f64 = self.fluid.iter().map(|b| (0..dim).map(|k| b.max[k] - b.min[k]).product::<f64>()).sum();
        let t = self.layers() as f64 * self.dp;
        let outer: f64 = (0..dim)
            .map(|k| self.tank.max[k] - self.tank.min[k] + if k == dim - 1 { t } else { 2.0 * t })
            .product();
        let inner: f64 = (0..dim).map(|k| self.tank.max[k] - self.tank.min[k]).product();
        (fluid + (outer - inner)) / cell
    }

    /// Cells of the neighbour grid: the tank with its walls and as much again above it, in
    /// cells of side `h` (half the support, see `simulation.rs`).
    pub fn estimated_cells(&self) -> f64 {
        let dim = self.dim;
        let t = self.layers() as f64 * self.dp;
        let cell = self.h();
        (0..dim)
            .map(|k| {
                let extent = self.tank.max[k] - self.tank.min[k];
                let extent = if k == dim - 1 { 2.0 * extent + 2.0 * t } else { extent + 2.0 * t };
                (extent / cell).floor().max(1.0)
            })
            .product()
    }

    /// Refuses a resolution whose arrays would not fit in memory (an estimate: about
    /// `48 dim + 100` bytes per particle, see docs/physics-options.md).
    fn validate_memory(&self) -> Result<()> {
        let limit = self.memory_limit_bytes.or_else(available_memory_bytes).map_or(f64::INFINITY, |b| b as f64);
        let particles = self.estimated_particles();
        // cell starts of three groups plus the sort cursor, 16 bytes per cell of the grid
        let cells = self.estimated_cells();
        let particle_bytes = particles * (48.0 * self.dim as f64 + 100.0);
        let bytes = particle_bytes + 16.0 * cells;
        if !(bytes <= limit) {
            // a grid larger than the particles means h is tiny for the tank: blame coefh
            let (field, fix) = if 16.0 * cells > particle_bytes { ("coefh", "increase coefh") } else { ("dp", "use a larger dp") };
            return Err(Error::invalid(
                field,
                format!(
                    "dp = {} and h = {:e} m need about {:.3e} particles and {:.3e} grid cells, {:.2} GiB, more than the {:.2} GiB allowed; {fix}",
                    self.dp,
                    self.h(),
                    particles,
                    cells,
                    bytes / 1024f64.powi(3),
                    limit / 1024f64.powi(3)
                ),
            ));
        }
        if !(cells < u32::MAX as f64) {
            return Err(Error::invalid(
                "coefh",
                format!("h = {:e} m makes a neighbour grid of {cells:.3e} cells (the limit is {:e}); increase coefh or dp", self.h(), u32::MAX as f64),
            ));
        }
        Ok(())
    }

    /// Paddle, damping zone and gauges.
    fn validate_flume(&self) -> Result<()> {
        let dim = self.dim;
        let up = dim - 1;
        let tol = 1e-9 * self.dp;
        if let Some(p) = &self.paddle {
            if !p.x.is_finite() {
                return Err(Error::invalid("paddle.x", format!("must be finite, got {}", p.x)));
            }
            p.law.validate("paddle.law")?;
            let back = p.x - self.layers() as Real * self.dp - p.law.max_backward_excursion();
            if back < self.tank.min[0] - tol || p.x >= self.tank.max[0] {
                return Err(Error::invalid(
                    "paddle.x",
                    format!(
                        "the paddle at x = {} ({} layers of dp thick, moving back by up to {:.4} m) must lie inside the tank [{}, {}]",
                        p.x,
                        self.layers(),
                        p.law.max_backward_excursion(),
                        self.tank.min[0],
                        self.tank.max[0]
                    ),
                ));
            }
            for (i, b) in self.fluid.iter().enumerate() {
                if b.min[0] < p.x - tol {
                    return Err(Error::invalid(
                        format!("fluid[{i}]"),
                        format!("starts at x = {} behind the paddle face x = {}", b.min[0], p.x),
                    ));
                }
            }
            if let Some(z) = p.hinge_z {
                if !z.is_finite() || z < self.tank.min[up] || z >= self.tank.max[up] {
                    return Err(Error::invalid("paddle.hinge_z", format!("must lie within the tank height, got {z}")));
                }
            }
            if let Some(z) = p.swl_z {
                if !z.is_finite() || z <= p.hinge_z.unwrap_or(self.tank.min[up]) {
                    return Err(Error::invalid("paddle.swl_z", format!("must be above the hinge, got {z}")));
                }
            }
            if p.kind == PaddleKind::Piston && p.hinge_z.is_some() {
                return Err(Error::invalid("paddle.hinge_z", "only a flap has a hinge"));
            }
        }
        if let Some(d) = &self.damping {
            if !d.x_start.is_finite() || !d.x_end.is_finite() || d.x_end <= d.x_start {
                return Err(Error::invalid(
                    "damping",
                    format!("x_end ({}) must be finite and greater than x_start ({})", d.x_end, d.x_start),
                ));
            }
            check_non_negative("damping.strength", d.strength)?;
        }
        let mut names = std::collections::HashSet::new();
        for (i, g) in self.gauges.iter().enumerate() {
            let f = format!("gauges[{i}]");
            g.validate(&f, dim, &self.tank.min, &self.tank.max)?;
            if !names.insert(g.name().to_string()) {
                return Err(Error::invalid(format!("{f}.name"), format!("duplicate gauge name {:?}", g.name())));
            }
        }
        Ok(())
    }
}

/// 80 % of `MemAvailable` from /proc/meminfo, if readable.
fn available_memory_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024 / 10 * 8)
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
    fn errors_name_the_field() {
        let cases = [
            (dambreak_json(r#", "cfl": -1"#), "cfl"),
            (dambreak_json(r#", "kernel": "gauss""#), "kernel"),
            (dambreak_json(r#", "viscosity": {"model": "artificial", "alpha": -0.1}"#), "viscosity.alpha"),
            (dambreak_json(r#", "viscosity": {"model": "magic"}"#), "viscosity"),
            (dambreak_json(r#", "bogus": 1"#), "bogus"),
            (dambreak_json(r#", "shifting": {"coefficient": 0}"#), "shifting.coefficient"),
            (dambreak_json(r#", "shifting": {"surface_threshold": 2.0}"#), "shifting.surface_threshold"),
            (dambreak_json(r#", "shifting": {"coeff": 2}"#), "shifting"),
            (dambreak_json(r#", "boundary": {"model": "mirror"}"#), "boundary"),
            (dambreak_json(r#", "memory_limit_bytes": 1000"#), "dp"),
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
