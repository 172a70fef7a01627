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
    #[serde(default = "default::damping_strength")]
    pub strength: Real,
}
