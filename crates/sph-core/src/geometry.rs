//! Geometry -> particles: the tank, obstacles and fluid boxes of a [`Scene`] sampled on a `dp`
//! lattice.
//!
//! The lattice sits at `(i + 1/2) dp` from the tank's inner corner, so a wall face lies halfway
//! between the last fluid and first wall particles (the DBC gap is `dp`), and a fluid box
//! `[0, W]` holds exactly `W / dp` particles across. Wall particles fill `layers` lattice layers
//! behind every face (the tank box in the max-norm, so corners are full; obstacles by parry's
//! signed distance), enough to cover the kernel support.

use crate::error::{Error, Result};
use crate::math::{Dim, Real, SurfacePoint, Vector};
use crate::probes::NO_BODY;
use crate::scene::{Obstacle, Scene};

/// Particles sampled from a scene.
#[derive(Debug, Clone)]
pub struct Sampled<D: Dim> {
    pub walls: Vec<D::V>,
    /// Water level above each wall particle (for hydrostatic initialisation), or `None` when
    /// no fluid lies above it.
    pub wall_surface: Vec<Option<Real>>,
    pub fluid: Vec<D::V>,
    /// Top of the fluid box each fluid particle came from.
    pub fluid_surface: Vec<Real>,
    /// Paddle particles at rest (moved by the motion law), with their water level.
    pub moving: Vec<D::V>,
    pub moving_surface: Vec<Option<Real>>,
}

enum Solid<D: Dim> {
    Box { min: D::V, max: D::V },
    Plane { point: D::V, normal: D::V },
    /// Bed polyline in the x-z plane (vertices in order of increasing x).
    Profile { x: Vec<Real>, z: Vec<Real>, line: parry2d_f64::shape::Polyline },
    Mesh(Box<D::Mesh>),
    /// Sphere, cylinder, capsule or convex polygon: a placed parry shape.
    Shape(D::Shape),
}

impl<D: Dim> Solid<D> {
    /// The nearest point of the solid's surface, by parry's projection, and whether `p` is
    /// inside. Every query on a solid (sampling, body ids, modified DBC's wall normals) comes
    /// from it.
    fn project(&self, p: D::V) -> SurfacePoint<D::V> {
        match self {
            Solid::Box { min, max } => D::box_projection(*min, *max, p),
            Solid::Plane { point, normal } => D::plane_projection(*point, *normal, p),
            Solid::Profile { x, z, line } => profile_projection::<D>(x, z, line, p),
            Solid::Mesh(mesh) => D::mesh_projection(mesh, p),
            Solid::Shape(shape) => D::shape_projection(shape, p),
        }
    }

    /// Signed distance to the solid's surface, negative inside.
    fn signed_distance(&self, p: D::V) -> Real {
        self.project(p).signed_distance()
    }
}

/// The nearest point of the bed polyline to `p` (in its x-z plane), by parry's 2D polyline
/// projection; `p` is inside below the bed. Outside `[x[0], x[n-1]]` there is no solid.
fn profile_projection<D: Dim>(x: &[Real], z: &[Real], line: &parry2d_f64::shape::Polyline, p: D::V) -> SurfacePoint<D::V> {
    use parry2d_f64::query::PointQuery;
    let (px, pz) = (p.get(0), p.vertical());
    let q = glam::DVec2::new(px, pz);
    let proj = line.project_local_point(q, false).point - q;
    let mut offset = D::V::ZERO;
    offset.set(0, proj.x);
    offset.set(D::DIM - 1, proj.y);
    let n = x.len();
    let inside = px >= x[0] && px <= x[n - 1] && {
        let i = x.partition_point(|&v| v <= px).clamp(1, n - 1);
        pz < z[i - 1] + (z[i] - z[i - 1]) * (px - x[i - 1]) / (x[i] - x[i - 1])
    };
    SurfacePoint { offset, inside }
}

/// The scene's obstacles as solids with a signed distance, in the scene's order.
fn solids<D: Dim>(scene: &Scene) -> Result<Vec<Solid<D>>> {
    scene
        .obstacles
        .iter()
        .enumerate()
        .map(|(i, o)| -> Result<Solid<D>> {
            Ok(match o {
                Obstacle::Box { min, max } => Solid::Box { min: D::V::from_slice(min), max: D::V::from_slice(max) },
                Obstacle::Profile { x, z } => {
                    let vertices = x.iter().zip(z).map(|(&a, &b)| glam::DVec2::new(a, b)).collect();
                    Solid::Profile { x: x.clone(), z: z.clone(), line: parry2d_f64::shape::Polyline::new(vertices, None) }
                }
                Obstacle::Mesh { vertices, triangles } => {
                    Solid::Mesh(Box::new(D::mesh(vertices, triangles).map_err(|e| Error::invalid(format!("obstacles[{i}]"), e))?))
                }
                Obstacle::Plane { point, normal } => {
                    let n = D::V::from_slice(normal);
                    Solid::Plane { point: D::V::from_slice(point), normal: n * (1.0 / n.length()) }
                }
                Obstacle::Sphere { centre, radius } => Solid::Shape(D::ball(D::V::from_slice(centre), *radius)),
                Obstacle::Capsule { a, b, radius } => {
                    Solid::Shape(D::capsule(D::V::from_slice(a), D::V::from_slice(b), *radius))
                }
                Obstacle::Cylinder { a, b, radius } => Solid::Shape(
                    D::cylinder(D::V::from_slice(a), D::V::from_slice(b), *radius)
                        .map_err(|e| Error::invalid(format!("obstacles[{i}]"), e))?,
                ),
                Obstacle::Polygon { vertices } => {
                    let points: Vec<D::V> = vertices.iter().map(|v| D::V::from_slice(v)).collect();
                    Solid::Shape(D::convex_polygon(&points).map_err(|e| Error::invalid(format!("obstacles[{i}].vertices"), e))?)
                }
            })
        })
        .collect()
}

/// Which obstacle each of the fixed wall particles at `walls` belongs to: the index of the
/// first obstacle whose shell (`layers` thick inside its surface) holds it, or [`NO_BODY`].
/// In the tank that is the obstacle [`sample`] sampled it from. Behind a side wall that is a
/// plane of symmetry ([`Scene::symmetry_y_min`]) it is a particle of that wall inside a body
/// crossing it: the fluid's pull on it is the pull on the body's mirror half, which the
/// body's force in the mirrored tank holds.
pub fn wall_bodies<D: Dim>(scene: &Scene, walls: &[D::V]) -> Result<Vec<u16>> {
    let solids = solids::<D>(scene)?;
    let thickness = scene.layers() as Real * scene.dp;
    let (tank_min, tank_max) = (D::V::from_slice(&scene.tank.min), D::V::from_slice(&scene.tank.max));
    Ok(walls
        .iter()
        .map(|&p| {
            // inside the tank, or behind its plane of symmetry y = min (and inside along the rest)
            let owned = (0..D::DIM).all(|k| {
                let behind_symmetry = k == 1 && scene.symmetry_y_min && p.get(1) < tank_min.get(1);
                behind_symmetry || (p.get(k) >= tank_min.get(k) && p.get(k) <= tank_max.get(k))
            });
            let shell = |s: &Solid<D>| {
                let d = s.signed_distance(p);
                d < 0.0 && d >= -thickness
            };
            match solids.iter().position(shell) {
                Some(i) if owned && i < NO_BODY as usize => i as u16,
                _ => NO_BODY,
            }
        })
        .collect())
}

/// Modified DBC's ghost nodes (English et al. 2022, section 2.2): for each wall particle at
/// `walls`, the offset `r_g - r_w = 2 (q - r_w)` to its mirror image through the nearest
/// fluid-facing wall surface, `q` being the particle's projection on that surface (so the
/// normal and the distance come from one projection); zero for a particle with no surface
/// within the wall's thickness. The surfaces: the tank's inner box for a particle outside it
/// (a corner particle projects on the corner and mirrors diagonally), each obstacle for a
/// particle inside it (by [`Solid::project`], whatever the shape), and the paddle's face at
/// rest, `x = paddle.x`, for the paddle's particles (`paddle`: `walls` are its particles at
/// rest, whose only surface this is) and a flap's fixed part below the hinge. A surface is
/// fluid-facing when the ghost lies in the tank, outside every obstacle and in front of the
/// paddle; a particle none of whose surfaces is (under an obstacle standing on the floor, say)
/// mirrors through the nearest.
pub fn ghost_offsets<D: Dim>(scene: &Scene, walls: &[D::V], paddle: bool) -> Result<Vec<D::V>> {
    let solids = solids::<D>(scene)?;
    let thickness = scene.layers() as Real * scene.dp;
    let (lo, hi) = (D::V::from_slice(&scene.tank.min), D::V::from_slice(&scene.tank.max));
    let face = scene.paddle.as_ref().map(|p| p.x);
    let in_tank = |p: D::V| (0..D::DIM).all(|k| p.get(k) >= lo.get(k) && p.get(k) <= hi.get(k));
    let in_fluid =
        |g: D::V| in_tank(g) && face.is_none_or(|x| g.get(0) >= x) && solids.iter().all(|s| s.signed_distance(g) >= 0.0);
    Ok(walls
        .iter()
        .map(|&p| {
            // offsets from p to its surface points, each within the wall's thickness
            let mut surfaces: Vec<D::V> = Vec::with_capacity(2);
            let behind_face = face.filter(|&x| paddle || (p.get(0) < x && p.get(0) >= x - thickness && in_tank(p)));
            if let Some(x) = behind_face {
                let mut q = D::V::ZERO;
                q.set(0, x - p.get(0));
                surfaces.push(q);
            }
            if !paddle {
                if !in_tank(p) {
                    surfaces.push(p.max(lo).min(hi) - p);
                }
                for s in &solids {
                    let proj = s.project(p);
                    if proj.inside && proj.signed_distance() >= -thickness {
                        surfaces.push(proj.offset);
                    }
                }
            }
            let nearest = |facing: bool| {
                surfaces
                    .iter()
                    .filter(|&&q| !facing || in_fluid(p + q * 2.0))
                    .min_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
                    .copied()
            };
            nearest(true).or_else(|| nearest(false)).map_or(D::V::ZERO, |q| q * 2.0)
        })
        .collect())
}

/// Samples the scene's walls and fluid. Errors when the geometry leaves no fluid.
pub fn sample<D: Dim>(scene: &Scene) -> Result<Sampled<D>> {
    let dim = D::DIM;
    let dp = scene.dp;
    let layers = scene.layers() as i64;
    let tank_min = D::V::from_slice(&scene.tank.min);
    let tank_max = D::V::from_slice(&scene.tank.max);
    let solids = solids::<D>(scene)?;
    let fluid_boxes: Vec<(D::V, D::V)> =
        scene.fluid.iter().map(|b| (D::V::from_slice(&b.min), D::V::from_slice(&b.max))).collect();

    // Lattice index ranges along each axis: `layers` beyond the tank on every side but the top.
    let mut lo = [0i64; 3];
    let mut hi = [1i64; 3];
    for k in 0..dim {
        let n = ((tank_max.get(k) - tank_min.get(k)) / dp - 1e-9).ceil() as i64;
        lo[k] = -layers;
        hi[k] = if k == dim - 1 { n } else { n + layers };
    }
    let estimated: i64 = (0..dim).map(|k| hi[k] - lo[k]).product();
    const LATTICE_LIMIT: i64 = 2_000_000_000;
    if estimated > LATTICE_LIMIT {
        // the tank alone fits: the wall layers (given, or from the kernel's support) make it too large
        let tank_only: i64 = (0..dim).map(|k| (hi[k] - if k == dim - 1 { 0 } else { layers }).max(1)).product();
        let field = match (tank_only <= LATTICE_LIMIT, scene.boundary_layers.is_some()) {
            (false, _) => "dp",
            (true, true) => "boundary_layers",
            (true, false) => "coefh",
        };
        return Err(Error::invalid(
            field,
            format!("dp = {dp:e} m and {layers} wall layers would need a lattice of {estimated:e} points around the tank; refusing"),
        ));
    }

    let thickness = layers as Real * dp;
    let half = 0.5 * dp;
    let tol = 1e-9 * dp;
    let mut out = Sampled {
        walls: Vec::new(),
        wall_surface: Vec::new(),
        fluid: Vec::new(),
        fluid_surface: Vec::new(),
        moving: Vec::new(),
        moving_surface: Vec::new(),
    };
    let paddle_face = scene.paddle.as_ref().map(|p| p.x);
    // bodies can close a pocket of fluid off from the open top: flood the lattice to find it
    let mut enclosure = (!solids.is_empty()).then(|| Enclosure::new(&lo, &hi, dim));
    let vertical = dim - 1;
    let mut idx = [0i64; 3];
    for iz in lo[2]..hi[2] {
        idx[2] = iz;
        for iy in lo[1]..hi[1] {
            idx[1] = iy;
            for ix in lo[0]..hi[0] {
                idx[0] = ix;
                let mut p = D::V::ZERO;
                for k in 0..dim {
                    p.set(k, tank_min.get(k) + (idx[k] as Real + 0.5) * dp);
                }
                // Max-norm distance outside the tank's inner box (0 inside).
                let mut outside = 0.0f64;
                for k in 0..dim {
                    outside = outside.max(tank_min.get(k) - p.get(k)).max(p.get(k) - tank_max.get(k));
                }
                let in_tank = outside <= 0.0;
                // (in the wall shell of a solid, inside a solid); the shell is inside
                let (is_wall, inside) = if !in_tank {
                    (outside <= thickness && p.get(vertical) <= tank_max.get(vertical), false)
                } else {
                    solids.iter().fold((false, false), |(wall, inside), s| {
                        if wall {
                            return (true, true);
                        }
                        let d = s.signed_distance(p);
                        (d < 0.0 && d >= -thickness, inside || d < 0.0)
                    })
                };
                let site = enclosure.as_mut().and_then(|e| e.site(&idx));
                if let (Some(e), Some(k), false) = (enclosure.as_mut(), site, is_wall || inside) {
                    e.open[k / 64] |= 1 << (k % 64);
                }
                if is_wall {
                    out.walls.push(p);
                    out.wall_surface.push(surface_above::<D>(&fluid_boxes, p, thickness));
                    continue;
                }
                if !in_tank {
                    continue;
                }
                let mut top: Option<Real> = None;
                for (bmin, bmax) in &fluid_boxes {
                    let inside = (0..dim).all(|k| p.get(k) > bmin.get(k) && p.get(k) < bmax.get(k));
                    if inside {
                        top = Some(top.map_or(bmax.vertical(), |t: Real| t.max(bmax.vertical())));
                    }
                }
                let Some(top) = top else { continue };
                // Fluid fills every lattice site outside the solids that is not a wall site: the
                // water then has the geometry's volume, and fluid and wall particles sit a
                // lattice spacing apart as at the tank's faces. (Keeping fluid dp/2 off a
                // sloping bed instead leaves an empty strip dp/2 thick along it,
                // which walls that do not hold the water off, Adami's, let the water fill: the
                // level over a beach then falls by a fraction of dp at the start.)
                if inside {
                    continue;
                }
                if paddle_face.is_some_and(|x| p.get(0) < x + half - tol) {
                    continue;
                }
                if let (Some(e), Some(k)) = (enclosure.as_mut(), site) {
                    e.fluid_sites.push(k);
                }
                out.fluid.push(p);
                out.fluid_surface.push(top);
            }
        }
    }
    if let Some(paddle) = &scene.paddle {
        sample_paddle::<D>(scene, paddle, &fluid_boxes, &mut out);
    }
    if let Some(e) = enclosure {
        if let Some((n, first)) = e.trapped() {
            let p = out.fluid[first];
            let nearest = (0..solids.len())
                .min_by(|&a, &b| solids[a].signed_distance(p).abs().total_cmp(&solids[b].signed_distance(p).abs()))
                .unwrap_or(0);
            return Err(Error::invalid(
                format!("obstacles[{nearest}]"),
                format!(
                    "{n} fluid particles (the first at {:?}) are enclosed by this body, the other bodies and the tank with no path to the open top; remove the fluid there or open the pocket",
                    p.as_slice()
                ),
            ));
        }
    }
    if out.fluid.is_empty() {
        return Err(Error::invalid(
            "fluid",
            "the geometry leaves no fluid particle (fluid boxes are empty, outside the tank or inside obstacles)",
        ));
    }
    Ok(out)
}

/// The lattice sites inside the tank's index box that neither a wall nor a solid holds (a bit
/// each), and the site of each fluid particle, for finding fluid that bodies close off from the
/// open top.
struct Enclosure {
    n: [usize; 3],
    open: Vec<u64>,
    fluid_sites: Vec<usize>,
}

impl Enclosure {
    /// The tank's index box: lattice indices `0..hi[k]` (`hi` without the wall layers).
    fn new(lo: &[i64; 3], hi: &[i64; 3], dim: usize) -> Self {
        let mut n = [1usize; 3];
        for k in 0..dim {
            n[k] = (hi[k] - if k == dim - 1 { 0 } else { -lo[k] }).max(1) as usize;
        }
        let sites = n[0] * n[1] * n[2];
        Enclosure { n, open: vec![0; sites.div_ceil(64)], fluid_sites: Vec::new() }
    }

    /// The site of lattice index `idx`, if inside the index box.
    fn site(&self, idx: &[i64; 3]) -> Option<usize> {
        let mut k = 0usize;
        for a in (0..3).rev() {
            let i = usize::try_from(idx[a]).ok().filter(|&i| i < self.n[a])?;
            k = k * self.n[a] + i;
        }
        Some(k)
    }

    fn is_open(&self, k: usize) -> bool {
        self.open[k / 64] >> (k % 64) & 1 == 1
    }

    /// Floods the open sites from the top layer of the index box (the tank's open top) through
    /// face neighbours; returns how many fluid particles it did not reach and the first of them.
    fn trapped(&self) -> Option<(usize, usize)> {
        let [nx, ny, nz] = self.n;
        let up = if nz > 1 { 2 } else { 1 };
        let (layer, count) = if up == 2 { (nx * ny, nz) } else { (nx, ny) };
        let mut seen = vec![0u64; self.open.len()];
        let mut queue = std::collections::VecDeque::new();
        for k in (count - 1) * layer..count * layer {
            if self.is_open(k) {
                seen[k / 64] |= 1 << (k % 64);
                queue.push_back(k);
            }
        }
        let strides = [1usize, nx, nx * ny];
        while let Some(k) = queue.pop_front() {
            let coord = [k % nx, (k / nx) % ny, k / (nx * ny)];
            for a in 0..3 {
                let len = self.n[a];
                for (step, ok) in [(-1i64, coord[a] > 0), (1, coord[a] + 1 < len)] {
                    if !ok {
                        continue;
                    }
                    let j = if step < 0 { k - strides[a] } else { k + strides[a] };
                    if self.is_open(j) && seen[j / 64] >> (j % 64) & 1 == 0 {
                        seen[j / 64] |= 1 << (j % 64);
                        queue.push_back(j);
                    }
                }
            }
        }
        let unreached: Vec<usize> =
            (0..self.fluid_sites.len()).filter(|&i| seen[self.fluid_sites[i] / 64] >> (self.fluid_sites[i] % 64) & 1 == 0).collect();
        unreached.first().map(|&first| (unreached.len(), first))
    }
}

/// The sampled points of a pressure gauge `on_wall` (`field`, its points flattened): each point
/// moved from the nearest wall surface (the tank's floor and sides, an obstacle's surface)
/// along its normal to dp/2 inside the fluid. A point farther than dp from every wall surface
/// is refused, naming it.
pub fn wall_sensor_points<D: Dim>(scene: &Scene, field: &str, points: &[Real]) -> Result<Vec<Real>> {
    let dim = D::DIM;
    let dp = scene.dp;
    let solids = solids::<D>(scene)?;
    let (tank_min, tank_max) = (D::V::from_slice(&scene.tank.min), D::V::from_slice(&scene.tank.max));
    let mut out = Vec::with_capacity(points.len());
    let in_fluid = |q: D::V| {
        (0..dim).all(|k| q.get(k) >= tank_min.get(k) && q.get(k) <= tank_max.get(k))
            && solids.iter().all(|s| s.signed_distance(q) >= 0.0)
    };
    for (j, pt) in points.chunks(dim).enumerate() {
        let p = D::V::from_slice(pt);
        // each surface near p: (distance to it, signed distance on the fluid's side, unit normal
        // into the fluid)
        let mut near: Vec<(Real, Real, D::V)> = Vec::new();
        for k in 0..dim {
            // the faces at min (all axes) and max (horizontal axes: the top is open), where the
            // point lies over the face
            let over = (0..dim).filter(|&a| a != k).all(|a| p.get(a) >= tank_min.get(a) - dp && p.get(a) <= tank_max.get(a) + dp);
            if !over {
                continue;
            }
            let mut n = D::V::ZERO;
            n.set(k, 1.0);
            near.push(((p.get(k) - tank_min.get(k)).abs(), p.get(k) - tank_min.get(k), n));
            if k < dim - 1 {
                near.push(((tank_max.get(k) - p.get(k)).abs(), tank_max.get(k) - p.get(k), n * -1.0));
            }
        }
        for s in &solids {
            let d = s.signed_distance(p);
            // the outward normal: the signed distance's gradient, by central differences
            let eps = 1e-4 * dp;
            let mut g = D::V::ZERO;
            for a in 0..dim {
                let mut e = D::V::ZERO;
                e.set(a, eps);
                g.set(a, (s.signed_distance(p + e) - s.signed_distance(p - e)) / (2.0 * eps));
            }
            let len = g.length();
            if len > 0.0 && len.is_finite() {
                near.push((d.abs(), d, g * (1.0 / len)));
            }
        }
        near.sort_by(|a, b| a.0.total_cmp(&b.0));
        let closest = near.first().map(|c| c.0);
        // the nearest surface within dp whose side the point moves to is fluid (not the floor
        // under a body standing on it, say)
        let sampled = near
            .iter()
            .filter(|(d, _, _)| *d <= dp * (1.0 + 1e-9))
            .map(|&(_, s, n)| p + n * (0.5 * dp - s))
            .find(|&q| in_fluid(q));
        match sampled {
            Some(q) => out.extend_from_slice(q.as_slice()),
            None => {
                let how = match closest {
                    Some(d) if d <= dp * (1.0 + 1e-9) => "on no wall surface facing the fluid (inside a body or a wall)".to_string(),
                    Some(d) => format!("{d:.4} m from the nearest wall or body surface, farther than dp = {dp}"),
                    None => format!("farther than dp = {dp} from every wall surface"),
                };
                return Err(Error::invalid(
                    format!("{field}.points[{j}]"),
                    format!("{:?} is {how}: a sensor on a wall sits on the tank's floor or sides or on a body, on the water's side", pt),
                ));
            }
        }
    }
    Ok(out)
}

/// The paddle: `layers` lattice layers behind its face `x`, from the tank floor to the tank top
/// and across the tank's inner width. A flap's part below its hinge is a fixed wall.
fn sample_paddle<D: Dim>(scene: &Scene, paddle: &crate::motion::Paddle, boxes: &[(D::V, D::V)], out: &mut Sampled<D>) {
    let dim = D::DIM;
    let dp = scene.dp;
    let up = dim - 1;
    let layers = scene.layers();
    let floor = scene.tank.min[up];
    let hinge = paddle.hinge_z.unwrap_or(floor);
    let thickness = layers as Real * dp;
    let nz = ((scene.tank.max[up] - floor) / dp - 1e-9).ceil() as usize;
    let ny = if dim == 3 { ((scene.tank.max[1] - scene.tank.min[1]) / dp - 1e-9).ceil() as usize } else { 1 };
    for iz in 0..nz {
        for iy in 0..ny {
            for j in 0..layers {
                let mut p = D::V::ZERO;
                p.set(0, paddle.x - (j as Real + 0.5) * dp);
                if dim == 3 {
                    p.set(1, scene.tank.min[1] + (iy as Real + 0.5) * dp);
                }
                p.set(up, floor + (iz as Real + 0.5) * dp);
                let surface = surface_above::<D>(boxes, p, thickness);
                if p.get(up) < hinge {
                    out.walls.push(p);
                    out.wall_surface.push(surface);
                } else {
                    out.moving.push(p);
                    out.moving_surface.push(surface);
                }
            }
        }
    }
}

/// Highest fluid-box top over the horizontal position of `p` (within `margin`), if it is above `p`.
fn surface_above<D: Dim>(boxes: &[(D::V, D::V)], p: D::V, margin: Real) -> Option<Real> {
    let v = D::DIM - 1;
    boxes
        .iter()
        .filter(|(bmin, bmax)| (0..v).all(|k| p.get(k) > bmin.get(k) - margin && p.get(k) < bmax.get(k) + margin))
        .map(|(_, bmax)| bmax.vertical())
        .filter(|&top| top > p.vertical())
        .fold(None, |acc: Option<Real>, t| Some(acc.map_or(t, |a| a.max(t))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Dim2, Dim3};

    fn scene(json: &str) -> Scene {
        Scene::from_json(json).expect("valid scene")
    }

    #[test]
    fn dambreak_2d_counts() {
        let s = scene(
            r#"{"dim": 2, "dp": 0.1, "tank": {"min": [0, 0], "max": [4, 3]},
                "fluid": [{"min": [0, 0], "max": [1, 2]}], "boundary_layers": 3}"#,
        );
        let g = sample::<Dim2>(&s).expect("sampled");
        assert_eq!(g.fluid.len(), 10 * 20);
        // floor: (40 + 6) x 3, two side walls: 3 x 30 each
        assert_eq!(g.walls.len(), 46 * 3 + 2 * 3 * 30);
        let xmax = g.fluid.iter().map(|p| p.x).fold(0.0, f64::max);
        assert!((xmax - 0.95).abs() < 1e-12);
    }

    #[test]
    fn beach_plane_removes_fluid_and_adds_walls() {
        let flat = scene(
            r#"{"dim": 2, "dp": 0.05, "tank": {"min": [0, 0], "max": [4, 1]},
                "fluid": [{"min": [0, 0], "max": [4, 0.5]}]}"#,
        );
        let beach = scene(
            r#"{"dim": 2, "dp": 0.05, "tank": {"min": [0, 0], "max": [4, 1]},
                "obstacles": [{"shape": "plane", "point": [2, 0], "normal": [-0.5, 1]}],
                "fluid": [{"min": [0, 0], "max": [4, 0.5]}]}"#,
        );
        let f = sample::<Dim2>(&flat).expect("flat");
        let b = sample::<Dim2>(&beach).expect("beach");
        // slope 1/2 from x = 2 reaches z = 0.5 at x = 3: a triangle of 0.25 m^2 and the dry
        // 0.5 m^2 beyond x = 3 are removed, and no more: the water keeps its volume.
        let removed = (f.fluid.len() - b.fluid.len()) as f64 * 0.05 * 0.05;
        assert!((removed - 0.75).abs() < 0.01, "removed {removed}");
        assert!(b.walls.len() > f.walls.len());
        for p in &b.fluid {
            let d = Dim2::plane_signed_distance(glam::DVec2::new(2.0, 0.0), glam::DVec2::new(-0.5, 1.0).normalize(), *p);
            assert!(d >= 0.0);
        }
    }

    #[test]
    fn profile_bar_matches_its_area() {
        // a trapezoidal bar 0.3 m high: 1:20 up over 6 m, 2 m crest, 1:10 down over 3 m
        let s = scene(
            r#"{"dim": 2, "dp": 0.02, "tank": {"min": [0, 0], "max": [20, 0.6]},
                "obstacles": [{"shape": "profile", "x": [6, 12, 14, 17], "z": [0, 0.3, 0.3, 0]}],
                "fluid": [{"min": [0, 0], "max": [20, 0.4]}]}"#,
        );
        let g = sample::<Dim2>(&s).expect("sampled");
        let area = 20.0 * 0.4 - g.fluid.len() as f64 * 0.02 * 0.02;
        let bar = 0.5 * 6.0 * 0.3 + 2.0 * 0.3 + 0.5 * 3.0 * 0.3;
        // the bar's own area, no strip along the bed
        assert!((area - bar).abs() < 0.01, "removed {area}, bar {bar}");
        assert!(Scene::from_json(
            r#"{"dim": 2, "dp": 0.02, "tank": {"min": [0, 0], "max": [20, 0.6]},
                "obstacles": [{"shape": "profile", "x": [6, 6], "z": [0, 0.3]}],
                "fluid": [{"min": [0, 0], "max": [20, 0.4]}]}"#
        )
        .is_err());
    }

    #[test]
    fn mesh_obstacle_removes_its_volume() {
        // a closed, outward-oriented box 0.4 x 0.5 x 0.2 m standing on the floor, as triangles
        let (x0, x1, y0, y1, z0, z1) = (0.3, 0.7, 0.0, 0.5, 0.0, 0.2);
        let v = [
            [x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
            [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1],
        ];
        let t: [[u32; 3]; 12] = [
            [0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
            [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7],
        ];
        let json = format!(
            r#"{{"dim": 3, "dp": 0.05, "tank": {{"min": [0, 0, 0], "max": [1, 0.5, 0.6]}},
                "obstacles": [{{"shape": "mesh", "vertices": {v:?}, "triangles": {t:?}}}],
                "fluid": [{{"min": [0, 0, 0], "max": [1, 0.5, 0.4]}}]}}"#
        );
        let with = sample::<Dim3>(&scene(&json)).expect("sampled");
        let without = sample::<Dim3>(&scene(
            r#"{"dim": 3, "dp": 0.05, "tank": {"min": [0, 0, 0], "max": [1, 0.5, 0.6]},
                "fluid": [{"min": [0, 0, 0], "max": [1, 0.5, 0.4]}]}"#,
        ))
        .expect("sampled");
        let removed = (without.fluid.len() - with.fluid.len()) as f64 * 0.05f64.powi(3);
        // faces on lattice mid-planes: exactly the box's 0.04 m^3 goes, the nearest fluid sits dp/2 off
        assert!((removed - 0.04).abs() < 1e-9, "removed {removed}");
        assert!(with.walls.len() > without.walls.len());
        let flat = json.replace(r#""dim": 3"#, r#""dim": 2"#);
        assert!(Scene::from_json(&flat).is_err());
    }

    fn tank_with(dim: usize, bodies: &str, extra: &str) -> String {
        let (tank, fluid) = if dim == 2 {
            (r#"{"min": [0, 0], "max": [1, 0.8]}"#, r#"{"min": [0, 0], "max": [1, 0.6]}"#)
        } else {
            (r#"{"min": [0, 0, 0], "max": [1, 0.8, 0.8]}"#, r#"{"min": [0, 0, 0], "max": [1, 0.8, 0.6]}"#)
        };
        format!(r#"{{"dim": {dim}, "dp": 0.02, "tank": {tank}, "fluid": [{fluid}], "obstacles": [{bodies}] {extra}}}"#)
    }

    /// Fluid volume a body removes from the tank of [`tank_with`].
    fn removed<D: Dim>(bodies: &str) -> f64 {
        let full = sample::<D>(&scene(&tank_with(D::DIM, "", ""))).expect("sampled").fluid.len();
        let with = sample::<D>(&scene(&tank_with(D::DIM, bodies, ""))).expect("sampled").fluid.len();
        (full - with) as f64 * 0.02f64.powi(D::DIM as i32)
    }

    #[test]
    fn parry_bodies_remove_their_volume() {
        use std::f64::consts::PI;
        let cases2 = [
            (r#"{"shape": "sphere", "centre": [0.5, 0.3], "radius": 0.15}"#, PI * 0.15 * 0.15),
            (r#"{"shape": "capsule", "a": [0.3, 0.3], "b": [0.7, 0.3], "radius": 0.1}"#, PI * 0.01 + 0.4 * 0.2),
            (r#"{"shape": "polygon", "vertices": [[0.2, 0], [0.8, 0], [0.5, 0.4]]}"#, 0.5 * 0.6 * 0.4),
        ];
        for (body, volume) in cases2 {
            let r = removed::<Dim2>(body);
            assert!((r - volume).abs() < 0.03 * volume, "{body}: removed {r}, volume {volume}");
        }
        let cases3 = [
            (r#"{"shape": "sphere", "centre": [0.5, 0.4, 0.3], "radius": 0.2}"#, 4.0 / 3.0 * PI * 0.008),
            (r#"{"shape": "cylinder", "a": [0.5, 0.4, 0], "b": [0.5, 0.4, 0.5], "radius": 0.15}"#, PI * 0.0225 * 0.5),
            (r#"{"shape": "cylinder", "a": [0.2, 0.4, 0.3], "b": [0.8, 0.4, 0.3], "radius": 0.1}"#, PI * 0.01 * 0.6),
            (r#"{"shape": "capsule", "a": [0.3, 0.4, 0.3], "b": [0.7, 0.4, 0.3], "radius": 0.1}"#, PI * 0.01 * 0.4 + 4.0 / 3.0 * PI * 0.001),
        ];
        for (body, volume) in cases3 {
            let r = removed::<Dim3>(body);
            assert!((r - volume).abs() < 0.04 * volume, "{body}: removed {r}, volume {volume}");
        }
    }

    fn refusal(json: &str, build: bool) -> String {
        let err = match Scene::from_json(json) {
            Err(e) => e,
            Ok(s) if build => match if s.dim == 2 { sample::<Dim2>(&s).map(|_| ()) } else { sample::<Dim3>(&s).map(|_| ()) } {
                Err(e) => e,
                Ok(()) => panic!("accepted: {json}"),
            },
            Ok(_) => panic!("accepted: {json}"),
        };
        match err {
            Error::InvalidScene { field, .. } => field,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn bad_bodies_are_refused_naming_the_field() {
        let outside = tank_with(2, r#"{"shape": "sphere", "centre": [0.95, 0.3], "radius": 0.1}"#, "");
        assert_eq!(refusal(&outside, false), "obstacles[0]");
        // the top is open: a column may rise above the walls
        assert!(Scene::from_json(&tank_with(2, r#"{"shape": "box", "min": [0.4, 0], "max": [0.5, 0.9]}"#, "")).is_ok());
        let tilted = tank_with(3, r#"{"shape": "cylinder", "a": [0.1, 0.4, 0.1], "b": [0.9, 0.4, 0.1], "radius": 0.2}"#, "");
        assert_eq!(refusal(&tilted, false), "obstacles[0]");
        // only the wall y = 0 that is a plane of symmetry may be crossed, and only in 3D
        let on_y0 = r#"{"shape": "box", "min": [0.4, -0.1, 0], "max": [0.5, 0.1, 0.9]}"#;
        assert_eq!(refusal(&tank_with(3, on_y0, ""), false), "obstacles[0]");
        assert!(Scene::from_json(&tank_with(3, on_y0, r#", "symmetry_y_min": true"#)).is_ok());
        let beyond_y0 = r#"{"shape": "box", "min": [0.4, -0.3, 0], "max": [0.5, -0.1, 0.9]}"#;
        assert_eq!(refusal(&tank_with(3, beyond_y0, r#", "symmetry_y_min": true"#), false), "obstacles[0]");
        let on_far_wall = r#"{"shape": "box", "min": [0.4, 0.7, 0], "max": [0.5, 0.9, 0.9]}"#;
        assert_eq!(refusal(&tank_with(3, on_far_wall, r#", "symmetry_y_min": true"#), false), "obstacles[0]");
        assert_eq!(refusal(&tank_with(2, "", r#", "symmetry_y_min": true"#), false), "symmetry_y_min");
        let concave = tank_with(2, r#"{"shape": "polygon", "vertices": [[0.2, 0], [0.8, 0], [0.5, 0.1], [0.5, 0.4]]}"#, "");
        assert_eq!(refusal(&concave, false), "obstacles[0].vertices");
        let flat_cylinder = tank_with(2, r#"{"shape": "cylinder", "a": [0.5, 0.1], "b": [0.5, 0.3], "radius": 0.1}"#, "");
        assert_eq!(refusal(&flat_cylinder, false), "obstacles[0]");
        // a box with one face missing: an open mesh
        let v = "[[0.3,0.3,0.1],[0.7,0.3,0.1],[0.7,0.6,0.1],[0.3,0.6,0.1],[0.3,0.3,0.4],[0.7,0.3,0.4],[0.7,0.6,0.4],[0.3,0.6,0.4]]";
        let closed = "[[0,2,1],[0,3,2],[4,5,6],[4,6,7],[0,1,5],[0,5,4],[1,2,6],[1,6,5],[2,3,7],[2,7,6],[3,0,4],[3,4,7]]";
        let open = "[[0,2,1],[0,3,2],[4,5,6],[4,6,7],[0,1,5],[0,5,4],[1,2,6],[1,6,5],[2,3,7],[2,7,6]]";
        let flipped = "[[0,1,2],[0,3,2],[4,5,6],[4,6,7],[0,1,5],[0,5,4],[1,2,6],[1,6,5],[2,3,7],[2,7,6],[3,0,4],[3,4,7]]";
        let mesh = |t: &str| tank_with(3, &format!(r#"{{"shape": "mesh", "vertices": {v}, "triangles": {t}}}"#), "");
        assert!(Scene::from_json(&mesh(closed)).is_ok());
        assert_eq!(refusal(&mesh(open), false), "obstacles[0].triangles");
        assert_eq!(refusal(&mesh(flipped), false), "obstacles[0].triangles");
    }

    #[test]
    fn a_body_crossing_a_plane_of_symmetry_owns_the_wall_particles_inside_it() {
        // a pile whose axis lies on the side wall y = 0: that wall's particles inside its shell
        // are its own, and none of the floor's under it
        let pile = r#"{"shape": "cylinder", "a": [0.5, 0, 0], "b": [0.5, 0, 0.8], "radius": 0.1}"#;
        let s = scene(&tank_with(3, pile, r#", "symmetry_y_min": true"#));
        let walls = sample::<Dim3>(&s).expect("sampled").walls;
        let owner = wall_bodies::<Dim3>(&s, &walls).expect("bodies");
        let thickness = s.layers() as Real * s.dp;
        for (p, &b) in walls.iter().zip(&owner) {
            let r = ((p.x - 0.5).powi(2) + p.y * p.y).sqrt();
            let depth = (0.1 - r).min(p.z).min(0.8 - p.z);
            let expected = depth > 0.0 && depth <= thickness;
            assert_eq!(b == 0, expected, "wall particle at {p:?}");
        }
        assert!(walls.iter().zip(&owner).any(|(p, &b)| b == 0 && p.y < 0.0));
    }

    #[test]
    fn fluid_enclosed_by_bodies_is_refused() {
        // a cup: a floor-standing U of three boxes with water in and around it is fine...
        let cup = r#"{"shape": "box", "min": [0.2, 0], "max": [0.3, 0.5]}, {"shape": "box", "min": [0.6, 0], "max": [0.7, 0.5]},
                     {"shape": "box", "min": [0.3, 0], "max": [0.6, 0.1]}"#;
        assert!(sample::<Dim2>(&scene(&tank_with(2, cup, ""))).is_ok());
        // ...but a lid over it (water to 0.6 m fills the pocket below it) traps the water inside
        let lidded = format!(r#"{cup}, {{"shape": "box", "min": [0.2, 0.5], "max": [0.7, 0.6]}}"#);
        let field = refusal(&tank_with(2, &lidded, ""), true);
        assert!(field.starts_with("obstacles["), "{field}");
        // a closed ring around a pocket, away from the walls
        let ring = r#"{"shape": "box", "min": [0.3, 0.1], "max": [0.7, 0.16]}, {"shape": "box", "min": [0.3, 0.44], "max": [0.7, 0.5]},
                      {"shape": "box", "min": [0.3, 0.1], "max": [0.36, 0.5]}, {"shape": "box", "min": [0.64, 0.1], "max": [0.7, 0.5]}"#;
        assert!(refusal(&tank_with(2, ring, ""), true).starts_with("obstacles["));
    }

    #[test]
    fn wall_sensors_sit_on_walls_and_sample_half_a_dp_inside() {
        let body = r#"{"shape": "box", "min": [0.4, 0], "max": [0.6, 0.3]}"#;
        let s = scene(&tank_with(2, body, ""));
        // on the box's face x = 0.4, on the floor, just inside the left wall
        let pts = [0.4, 0.1, 0.2, 0.0, 0.005, 0.3];
        let q = wall_sensor_points::<Dim2>(&s, "gauges[0]", &pts).expect("on walls");
        let want = [0.39, 0.1, 0.2, 0.01, 0.01, 0.3];
        for (a, b) in q.iter().zip(want) {
            assert!((a - b).abs() < 1e-6, "{q:?}");
        }
        let err = wall_sensor_points::<Dim2>(&s, "gauges[0]", &[0.4, 0.1, 0.2, 0.2]);
        assert!(matches!(err, Err(Error::InvalidScene { field, .. }) if field == "gauges[0].points[1]"));
        // on the floor under the box: near walls, but none faces the water
        let under = wall_sensor_points::<Dim2>(&s, "gauges[0]", &[0.5, 0.0]);
        assert!(matches!(under, Err(Error::InvalidScene { field, reason }) if field == "gauges[0].points[0]" && reason.contains("facing")));
        let gauge = r#", "gauges": [{"type": "pressure", "name": "p", "points": [[0.2, 0.3]], "interval": 0.1, "on_wall": true}]"#;
        assert!(Scene::from_json(&tank_with(2, body, gauge)).is_ok());
    }

    #[test]
    fn tank_3d_and_no_fluid_error() {
        let s = scene(
            r#"{"dim": 3, "dp": 0.1, "tank": {"min": [0, 0, 0], "max": [1, 0.5, 1]},
                "fluid": [{"min": [0, 0, 0], "max": [1, 0.5, 0.5]}]}"#,
        );
        let g = sample::<Dim3>(&s).expect("sampled");
        assert_eq!(g.fluid.len(), 10 * 5 * 5);
        let hidden = scene(
            r#"{"dim": 2, "dp": 0.1, "tank": {"min": [0, 0], "max": [1, 1]},
                "obstacles": [{"shape": "box", "min": [0, 0], "max": [1, 0.6]}],
                "fluid": [{"min": [0, 0], "max": [1, 0.5]}]}"#,
        );
        assert!(matches!(sample::<Dim2>(&hidden), Err(Error::InvalidScene { .. })));
    }
}
