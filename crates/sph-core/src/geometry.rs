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
            })
        })
        .collect()
}

/// Which obstacle each of the fixed wall particles at `walls` was sampled from: the index of the
/// first obstacle whose shell (`layers` thick inside its surface) holds it, as [`sample`]
/// decides, or [`NO_BODY`] for the tank's walls (outside the tank's inner box) and the rest.
pub fn wall_bodies<D: Dim>(scene: &Scene, walls: &[D::V]) -> Result<Vec<u16>> {
    let solids = solids::<D>(scene)?;
    let thickness = scene.layers() as Real * scene.dp;
    let (tank_min, tank_max) = (D::V::from_slice(&scene.tank.min), D::V::from_slice(&scene.tank.max));
    Ok(walls
        .iter()
        .map(|&p| {
            let in_tank = (0..D::DIM).all(|k| p.get(k) >= tank_min.get(k) && p.get(k) <= tank_max.get(k));
            let shell = |s: &Solid<D>| {
                let d = s.signed_distance(p);
                d < 0.0 && d >= -thickness
            };
            match solids.iter().position(shell) {
                Some(i) if in_tank && i < NO_BODY as usize => i as u16,
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
                let is_wall = if !in_tank {
                    outside <= thickness && p.get(vertical) <= tank_max.get(vertical)
                } else {
                    solids.iter().any(|s| {
                        let d = s.signed_distance(p);
                        d < 0.0 && d >= -thickness
                    })
                };
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
                if solids.iter().any(|s| s.signed_distance(p) < 0.0) {
                    continue;
                }
                if paddle_face.is_some_and(|x| p.get(0) < x + half - tol) {
                    continue;
                }
                out.fluid.push(p);
                out.fluid_surface.push(top);
            }
        }
    }
    if let Some(paddle) = &scene.paddle {
        sample_paddle::<D>(scene, paddle, &fluid_boxes, &mut out);
    }
    if out.fluid.is_empty() {
        return Err(Error::invalid(
            "fluid",
            "the geometry leaves no fluid particle (fluid boxes are empty, outside the tank or inside obstacles)",
        ));
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
