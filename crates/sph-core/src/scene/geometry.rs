//! The geometry of a scene: the tank and fluid boxes, solid obstacles and the damping zone.

use serde::{Deserialize, Serialize};

use super::defaults::serde_default as default;
use crate::math::Real;

/// An axis-aligned box `[min, max]`; vectors have `dim` entries, the last vertical.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSpec {
    pub min: Vec<Real>,
    pub max: Vec<Real>,
}

/// A solid body inside the tank, sampled into wall particles of the scene's wall model. Every
/// shape is a parry shape with a signed distance (`crate::geometry`), which decides its wall
/// shell and the fluid it removes; all but the plane and the profile must lie inside the tank.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum Obstacle {
    Box { min: Vec<Real>, max: Vec<Real> },
    /// A ball of `radius` about `centre`; in 2D a disc (a horizontal cylinder across the width).
    Sphere { centre: Vec<Real>, radius: Real },
    /// A cylinder of `radius` whose axis runs from the centre of one end, `a`, to the other's,
    /// `b` (3D only): a pile, a column.
    Cylinder { a: Vec<Real>, b: Vec<Real>, radius: Real },
    /// The points within `radius` of the segment `a b`.
    Capsule { a: Vec<Real>, b: Vec<Real>, radius: Real },
    /// A convex polygon through `vertices` `[x, z]`, in any order (2D only).
    Polygon { vertices: Vec<Vec<Real>> },
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

impl Obstacle {
    /// The corners `(min, max)` of the body's bounding box, or `None` for the plane and the
    /// profile, which the tank clips.
    pub fn bounds(&self, dim: usize) -> Option<(Vec<Real>, Vec<Real>)> {
        let around = |points: &[&[Real]], r: Real| {
            let lo = (0..dim).map(|k| points.iter().map(|p| p[k]).fold(Real::INFINITY, Real::min) - r).collect();
            let hi = (0..dim).map(|k| points.iter().map(|p| p[k]).fold(Real::NEG_INFINITY, Real::max) + r).collect();
            (lo, hi)
        };
        match self {
            Obstacle::Box { min, max } => Some((min.clone(), max.clone())),
            Obstacle::Sphere { centre, radius } => Some(around(&[centre], *radius)),
            Obstacle::Capsule { a, b, radius } => Some(around(&[a, b], *radius)),
            Obstacle::Cylinder { a, b, radius } => {
                // each end is a disc of `radius` normal to the axis: along axis k it reaches
                // radius * sqrt(1 - n_k^2) past the end's centre
                let axis: Vec<Real> = (0..dim).map(|k| b[k] - a[k]).collect();
                let len = axis.iter().map(|x| x * x).sum::<Real>().sqrt();
                let reach: Vec<Real> = axis.iter().map(|x| radius * (1.0 - (x / len).powi(2)).max(0.0).sqrt()).collect();
                let lo = (0..dim).map(|k| a[k].min(b[k]) - reach[k]).collect();
                let hi = (0..dim).map(|k| a[k].max(b[k]) + reach[k]).collect();
                Some((lo, hi))
            }
            Obstacle::Polygon { vertices } | Obstacle::Mesh { vertices, .. } => {
                let points: Vec<&[Real]> = vertices.iter().map(|v| v.as_slice()).collect();
                Some(around(&points, 0.0))
            }
            Obstacle::Plane { .. } | Obstacle::Profile { .. } => None,
        }
    }
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
    #[serde(default = "default::damping_strength")]
    pub strength: Real,
}
