//! Every check of a scene, run before anything is allocated: each refusal names the offending
//! key's dotted path (`viscosity.alpha`, `fluid[0]`) and the reason.

use super::geometry::BoxSpec;
use super::numerics::{Diffusion, ForcePrecision, Integrator, ShiftingModel, Viscosity};
use super::{Obstacle, Scene};
use crate::error::{Error, Result};
use crate::math::Real;
use crate::motion::PaddleKind;

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

/// Smallest `coefh`: a smaller h reaches no more than the nearest neighbours, and the neighbour
/// grid (cells of side h) outgrows memory. DualSPHysics' cases use 0.75-2.
pub const MIN_COEFH: Real = 0.5;

/// Largest `density_band`: the band `rho0 (1 -+ density_band)` then reaches zero density, and a
/// wider one bounds nothing below.
pub const MAX_DENSITY_BAND: Real = 1.0;

/// Largest `energy_growth_limit`: an unforced fluid whose mechanical energy grew by its whole
/// initial potential energy is no solution any more, so a looser monitor would never stop a run
/// that needs stopping.
pub const MAX_ENERGY_GROWTH_LIMIT: Real = 1.0;

fn check_obstacle(f: &str, o: &Obstacle, dim: usize) -> Result<()> {
    match o {
        Obstacle::Box { min, max } => {
            check_box(f, &BoxSpec { min: min.clone(), max: max.clone() }, dim)?
        }
        Obstacle::Sphere { centre, radius } => {
            check_vector(&format!("{f}.centre"), centre, dim)?;
            check_positive(&format!("{f}.radius"), *radius)?;
        }
        Obstacle::Cylinder { a, b, radius } | Obstacle::Capsule { a, b, radius } => {
            if dim != 3 && matches!(o, Obstacle::Cylinder { .. }) {
                return Err(Error::invalid(f, "a cylinder needs dim = 3 (in 2D a sphere is the section of one across the width)"));
            }
            check_vector(&format!("{f}.a"), a, dim)?;
            check_vector(&format!("{f}.b"), b, dim)?;
            check_positive(&format!("{f}.radius"), *radius)?;
            if a == b && matches!(o, Obstacle::Cylinder { .. }) {
                return Err(Error::invalid(format!("{f}.b"), "the axis' ends a and b must differ"));
            }
        }
        Obstacle::Polygon { vertices } => {
            if dim != 2 {
                return Err(Error::invalid(f, "a polygon needs dim = 2 (in 3D, a closed mesh)"));
            }
            if vertices.len() < 3 {
                return Err(Error::invalid(format!("{f}.vertices"), format!("needs at least 3 vertices, got {}", vertices.len())));
            }
            for (j, v) in vertices.iter().enumerate() {
                check_vector(&format!("{f}.vertices[{j}]"), v, 2)?;
            }
            let points: Vec<glam::DVec2> = vertices.iter().map(|v| glam::DVec2::new(v[0], v[1])).collect();
            <crate::math::Dim2 as crate::math::Dim>::convex_polygon(&points)
                .map_err(|e| Error::invalid(format!("{f}.vertices"), e))?;
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
            check_closed(&format!("{f}.triangles"), vertices, triangles)?;
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
    Ok(())
}

/// A closed, consistently oriented surface: every edge (between vertices merged by position)
/// is shared by exactly two triangles that run along it in opposite directions. Without that
/// the mesh has no inside, and parry's inside test (pseudo-normals) answers at random.
fn check_closed(f: &str, vertices: &[Vec<Real>], triangles: &[[u32; 3]]) -> Result<()> {
    use std::collections::HashMap;
    let mut merged: HashMap<[u64; 3], usize> = HashMap::new();
    let id: Vec<usize> = vertices
        .iter()
        .map(|v| {
            let key = [v[0].to_bits(), v[1].to_bits(), v[2].to_bits()];
            let n = merged.len();
            *merged.entry(key).or_insert(n)
        })
        .collect();
    // directed edge -> how many triangles run along it
    let mut edges: HashMap<(usize, usize), u32> = HashMap::new();
    for (j, t) in triangles.iter().enumerate() {
        let v = t.map(|i| id[i as usize]);
        if v[0] == v[1] || v[1] == v[2] || v[0] == v[2] {
            return Err(Error::invalid(format!("{f}[{j}]"), format!("triangle {t:?} has two vertices at the same point")));
        }
        for k in 0..3 {
            *edges.entry((v[k], v[(k + 1) % 3])).or_insert(0) += 1;
        }
    }
    let mut open = 0usize;
    let mut twisted = 0usize;
    for (&(a, b), &n) in &edges {
        match (n, edges.get(&(b, a)).copied().unwrap_or(0)) {
            (1, 1) => {}
            (_, 0) => open += 1,
            _ => twisted += 1,
        }
    }
    if open > 0 || twisted > 0 {
        return Err(Error::invalid(
            f,
            format!(
                "the mesh is not a closed, consistently oriented surface: {open} edges belong to one triangle only (holes), {twisted} to triangles running the same way or to more than two"
            ),
        ));
    }
    Ok(())
}

fn check_at_most(field: &str, v: Real, max: Real, reason: &str) -> Result<()> {
    if v > max {
        return Err(Error::invalid(field, format!("must be <= {max} ({reason}), got {v}")));
    }
    Ok(())
}

impl Scene {
    /// Checks every field; the error names the field and the reason.
    pub fn validate(&self) -> Result<()> {
        if self.dim != 2 && self.dim != 3 {
            return Err(Error::invalid("dim", format!("must be 2 or 3, got {}", self.dim)));
        }
        self.validate_parameters()?;
        self.validate_numerics()?;
        self.validate_geometry()?;
        self.validate_flume()?;
        self.validate_memory()?;
        for k in 0..self.dim {
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

    /// The scalar parameters and the stability monitors' thresholds.
    fn validate_parameters(&self) -> Result<()> {
        check_positive("dp", self.dp)?;
        check_non_negative("gravity", self.gravity)?;
        check_positive("rho0", self.rho0)?;
        check_positive("coefh", self.coefh)?;
        if self.coefh < MIN_COEFH {
            return Err(Error::invalid(
                "coefh",
                format!(
                    "must be >= {MIN_COEFH} (h = coefh sqrt(dim) dp; a smaller h reaches no more than the nearest neighbours), got {}",
                    self.coefh
                ),
            ));
        }
        check_positive("coefsound", self.coefsound)?;
        check_positive("gamma", self.gamma)?;
        check_positive("cfl", self.cfl)?;
        check_at_most("cfl", self.cfl, 1.0, "the Courant number")?;
        check_positive("density_band", self.density_band)?;
        check_at_most("density_band", self.density_band, MAX_DENSITY_BAND, "the band rho0 (1 -+ density_band) then reaches zero density")?;
        check_non_negative("lost_fraction_limit", self.lost_fraction_limit)?;
        check_at_most("lost_fraction_limit", self.lost_fraction_limit, 1.0, "a fraction of the fluid")?;
        check_positive("energy_growth_limit", self.energy_growth_limit)?;
        check_at_most("energy_growth_limit", self.energy_growth_limit, MAX_ENERGY_GROWTH_LIMIT, "a growth by the whole initial potential energy")?;
        if let Some(d) = self.h_swl {
            check_positive("h_swl", d)?;
        }
        Ok(())
    }

    /// Viscosity, diffusion, integrator, shifting, tensile correction and wall thickness.
    fn validate_numerics(&self) -> Result<()> {
        let dim = self.dim;
        check_non_negative("viscosity.wall_factor", self.viscosity.wall_factor())?;
        match self.viscosity {
            Viscosity::Artificial { alpha, .. } => check_non_negative("viscosity.alpha", alpha)?,
            Viscosity::Laminar { nu, .. } => check_non_negative("viscosity.nu", nu)?,
            Viscosity::LaminarSps { nu, cs, ci, .. } => {
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
            if sh.model == ShiftingModel::DeltaPlus && sh.surface_threshold.is_some() {
                return Err(Error::invalid(
                    "shifting.surface_threshold",
                    "belongs to model lind; delta_plus finds the free surface from the renormalisation matrix's smallest eigenvalue",
                ));
            }
            let t = sh.threshold(dim);
            if !t.is_finite() || t <= 0.0 || t >= dim as Real {
                return Err(Error::invalid(
                    "shifting.surface_threshold",
                    format!("must lie strictly between 0 and dim = {dim} (the bulk's particle divergence), got {t}"),
                ));
            }
        }
        if let Some(t) = &self.tensile_correction {
            t.validate(self.kernel)?;
        }
        if let Some(r) = &self.riemann {
            r.validate(self)?;
        }
        if let Some(k) = &self.kernel_correction {
            k.validate(self)?;
        }
        if let Some(0) = self.boundary_layers {
            return Err(Error::invalid("boundary_layers", "must be >= 1"));
        }
        Ok(())
    }

    /// The tank, the obstacles and the fluid boxes.
    fn validate_geometry(&self) -> Result<()> {
        let dim = self.dim;
        check_box("tank", &self.tank, dim)?;
        if self.symmetry_y_min && dim != 3 {
            return Err(Error::invalid("symmetry_y_min", "a side wall y = tank.min[1] exists in 3D scenes only"));
        }
        // a thousandth of dp: no lattice site tells it apart, and a mesh read from f32 (binary
        // STL) rounds its vertices by more than 1e-9 dp
        let tol = 1e-3 * self.dp;
        for (i, o) in self.obstacles.iter().enumerate() {
            let f = format!("obstacles[{i}]");
            check_obstacle(&f, o, dim)?;
            if let Some((lo, hi)) = o.bounds(dim) {
                // the top is open: a body may rise above the walls (DualSPHysics' CaseDambreak
                // column does)
                // it may cross the side wall y = tank.min[1] that is a plane of symmetry
                let crosses_symmetry = |k: usize| k == 1 && self.symmetry_y_min && hi[k] > self.tank.min[k] + tol;
                let out = |k: usize| {
                    (lo[k] < self.tank.min[k] - tol && !crosses_symmetry(k)) || (k + 1 < dim && hi[k] > self.tank.max[k] + tol)
                };
                if let Some(k) = (0..dim).find(|&k| out(k)) {
                    let hint = if k == 1 && dim == 3 && lo[k] < self.tank.min[k] - tol && !self.symmetry_y_min {
                        " (it may cross the wall y = tank.min[1] when that is a plane of symmetry, symmetry_y_min)"
                    } else {
                        ""
                    };
                    return Err(Error::invalid(
                        f,
                        format!(
                            "the body spans [{}, {}] along axis {k}, outside the tank [{}, {}]{hint}",
                            lo[k], hi[k], self.tank.min[k], self.tank.max[k]
                        ),
                    ));
                }
            }
        }
        if self.fluid.is_empty() {
            return Err(Error::invalid("fluid", "at least one fluid box is needed"));
        }
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
        Ok(())
    }

    /// Refuses a resolution whose arrays would not fit in memory (an estimate: about
    /// `48 dim + 100` bytes per particle, see docs/physics-options.md).
    fn validate_memory(&self) -> Result<()> {
        let limit = self.memory_limit_bytes.or_else(available_memory_bytes).map_or(f64::INFINITY, |b| b as f64);
        // cell starts of three groups plus the sort cursor, 16 bytes per cell of the grid
        let bytes_with = |layers: usize| {
            let particle_bytes = self.estimated_particles_with(layers) * (48.0 * self.dim as f64 + 100.0);
            (particle_bytes, 16.0 * self.estimated_cells_with(layers))
        };
        let layers = self.layers();
        let (particle_bytes, grid_bytes) = bytes_with(layers);
        let bytes = particle_bytes + grid_bytes;
        if !(bytes <= limit) {
            let fits = |layers: usize| {
                let (p, g) = bytes_with(layers);
                p + g <= limit
            };
            let coefh_layers = self.layers_for_coefh(self.coefh);
            let default_layers = self.layers_for_coefh(super::default::coefh());
            // The field whose usual value would make the run fit: a grid larger than the
            // particles means h is tiny for the tank; a wall shell that fits with the layers
            // the support needs means boundary_layers, and one that fits with the default
            // coefh's layers means a huge coefh (its walls follow the support); else dp.
            let (field, fix) = if grid_bytes > particle_bytes {
                ("coefh", "increase coefh".to_string())
            } else if self.boundary_layers.is_some() && layers > coefh_layers && fits(coefh_layers) {
                ("boundary_layers", format!("{layers} layers of dp; the support needs {coefh_layers}"))
            } else if self.boundary_layers.is_none() && layers > default_layers && fits(default_layers) {
                ("coefh", format!("coefh = {} asks for walls of {layers} layers of dp; use a smaller coefh", self.coefh))
            } else {
                ("dp", "use a larger dp".to_string())
            };
            return Err(Error::invalid(
                field,
                format!(
                    "dp = {} m, h = {:e} m and {layers} wall layers need about {:.3e} particles and {:.3e} grid cells, {:.3e} GiB, more than the {:.2} GiB allowed; {fix}",
                    self.dp,
                    self.h(),
                    self.estimated_particles(),
                    self.estimated_cells(),
                    bytes / 1024f64.powi(3),
                    limit / 1024f64.powi(3)
                ),
            ));
        }
        let cells = self.estimated_cells();
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
            g.validate(&f, dim, &self.tank.min, &self.tank.max, self.obstacles.len())?;
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
