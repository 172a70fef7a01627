//! Dimension aliases: one source for 2D and 3D.
//!
//! Everything dimension-specific lives here (vectors, integer cell coordinates, the symmetric
//! tensor used by the SPS closure, and the parry shape queries used to sample geometry). The rest
//! of the core is written once against [`Dim`] and monomorphised for [`Dim2`] and [`Dim3`].
//! The last vector component is always vertical (z), gravity acts along it.

use std::fmt::Debug;
use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

use glam::{DVec2, DVec3};

/// Floating-point type of the solver state.
pub type Real = f64;

/// Vector operations the solver needs, implemented for glam's `DVec2` and `DVec3`.
pub trait Vector:
    Copy
    + Send
    + Sync
    + Default
    + Debug
    + PartialEq
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Real, Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + bytemuck::Pod
    + 'static
{
    const ZERO: Self;
    fn dot(self, other: Self) -> Real;
    fn length_squared(self) -> Real;
    fn length(self) -> Real {
        self.length_squared().sqrt()
    }
    /// Component `i` (0 = x, last = vertical).
    fn get(self, i: usize) -> Real;
    fn set(&mut self, i: usize, value: Real);
    /// Vertical component (y in 2D, z in 3D).
    fn vertical(self) -> Real;
    fn is_finite(self) -> bool;
    fn min(self, other: Self) -> Self;
    fn max(self, other: Self) -> Self;
    fn splat(v: Real) -> Self;
    /// Builds a vector from exactly `DIM` values.
    fn from_slice(values: &[Real]) -> Self;
    fn as_slice(&self) -> &[Real] {
        bytemuck::cast_slice(std::slice::from_ref(self))
    }
}

macro_rules! impl_vector {
    ($t:ty, $dim:expr) => {
        impl Vector for $t {
            const ZERO: Self = <$t>::ZERO;
            #[inline(always)]
            fn dot(self, other: Self) -> Real {
                <$t>::dot(self, other)
            }
            #[inline(always)]
            fn length_squared(self) -> Real {
                <$t>::length_squared(self)
            }
            #[inline(always)]
            fn get(self, i: usize) -> Real {
                self[i]
            }
            #[inline(always)]
            fn set(&mut self, i: usize, value: Real) {
                self[i] = value;
            }
            #[inline(always)]
            fn vertical(self) -> Real {
                self[$dim - 1]
            }
            #[inline(always)]
            fn is_finite(self) -> bool {
                <$t>::is_finite(self)
            }
            #[inline(always)]
            fn min(self, other: Self) -> Self {
                <$t>::min(self, other)
            }
            #[inline(always)]
            fn max(self, other: Self) -> Self {
                <$t>::max(self, other)
            }
            #[inline(always)]
            fn splat(v: Real) -> Self {
                <$t>::splat(v)
            }
            fn from_slice(values: &[Real]) -> Self {
                <$t>::from_slice(values)
            }
        }
    };
}
impl_vector!(DVec2, 2);
impl_vector!(DVec3, 3);

/// Floating-point type of the fluid force loop's pair arithmetic: `f64` (the state's precision)
/// or `f32` (twice the SIMD width; DualSPHysics' choice for velocities, densities and forces).
/// Positions and the state stay `f64`; only the per-pair terms are formed in this type.
pub trait PairFloat:
    Copy
    + Default
    + Debug
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + std::ops::Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + Send
    + Sync
    + 'static
{
    /// Partial sums per particle: one AVX2 register of this type.
    const LANES: usize;
    /// Whether this is the single-precision type (the pair terms then take density differences
    /// from `rho/rho0 - 1`, formed in f64, instead of subtracting two densities near `rho0`).
    const SINGLE: bool;
    fn of(x: Real) -> Self;
    /// From f32, exactly (the single-precision scan's offsets).
    fn of_f32(x: f32) -> Self;
    fn to_real(self) -> Real;
    fn sqrt(self) -> Self;
    fn abs(self) -> Self;
}

macro_rules! impl_pair_float {
    ($t:ty, $lanes:expr, $single:expr) => {
        impl PairFloat for $t {
            const LANES: usize = $lanes;
            const SINGLE: bool = $single;
            #[inline(always)]
            fn of(x: Real) -> Self {
                x as $t
            }
            #[inline(always)]
            fn of_f32(x: f32) -> Self {
                x as $t
            }
            #[inline(always)]
            fn to_real(self) -> Real {
                self as Real
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                <$t>::sqrt(self)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
        }
    };
}
impl_pair_float!(f64, 4, false);
impl_pair_float!(f32, 8, true);

/// Symmetric tensor storage for the SPS stress (3 components in 2D, 6 in 3D).
pub trait SymTensor: Copy + Send + Sync + Default + Debug + 'static {}
impl SymTensor for [Real; 3] {}
impl SymTensor for [Real; 6] {}

/// A spatial dimension: its vector type, cell coordinates, symmetric tensors and shape queries.
pub trait Dim: Copy + Send + Sync + Debug + Default + 'static {
    const DIM: usize;
    /// Number of cells in the neighbour stencil (3^DIM).
    const STENCIL: usize;
    type V: Vector;
    type Sym: SymTensor;

    /// Symmetric part of the outer product `a (x) b`, scaled by `w`, added to `s`.
    fn sym_add_outer(s: &mut Self::Sym, a: Self::V, b: Self::V, w: Real);
    /// `s . v`
    fn sym_dot(s: &Self::Sym, v: Self::V) -> Self::V;
    /// Trace and squared Frobenius norm `S_ij S_ij`.
    fn sym_trace_and_norm2(s: &Self::Sym) -> (Real, Real);
    /// `s` scaled by `a`, plus `b` on the diagonal.
    fn sym_scale_add_diag(s: &Self::Sym, a: Real, b: Real) -> Self::Sym;
    /// Smallest eigenvalue of `s`.
    fn sym_min_eigenvalue(s: &Self::Sym) -> Real;
    /// `adj(s) . v`: `det(s) s^-1 . v` without the division (the direction of `s^-1 . v`
    /// when `s` is positive definite).
    fn sym_adjugate_dot(s: &Self::Sym, v: Self::V) -> Self::V;
    /// `s^-1` (None where `det(s)` is 0 or not finite).
    fn sym_inverse(s: &Self::Sym) -> Option<Self::Sym>;
    /// The identity tensor.
    fn sym_identity() -> Self::Sym;

    /// The nearest point of the surface of the axis-aligned box `[min, max]` to `p`, by parry's
    /// point projection.
    fn box_projection(min: Self::V, max: Self::V, p: Self::V) -> SurfacePoint<Self::V>;
    /// Signed distance from `p` to the surface of the axis-aligned box `[min, max]`
    /// (negative inside).
    fn box_signed_distance(min: Self::V, max: Self::V, p: Self::V) -> Real {
        Self::box_projection(min, max, p).signed_distance()
    }
    /// A closed, outward-oriented triangle mesh (3D only).
    type Mesh: Send + Sync;
    /// Builds a mesh from vertices (`DIM` values each) and triangles; the error says why not.
    fn mesh(vertices: &[Vec<Real>], triangles: &[[u32; 3]]) -> std::result::Result<Self::Mesh, String>;
    /// The nearest point of the mesh surface to `p` (parry's pseudo-normal test for inside).
    fn mesh_projection(mesh: &Self::Mesh, p: Self::V) -> SurfacePoint<Self::V>;
    /// Signed distance from `p` to the mesh surface, negative inside.
    fn mesh_signed_distance(mesh: &Self::Mesh, p: Self::V) -> Real {
        Self::mesh_projection(mesh, p).signed_distance()
    }

    /// The nearest point to `p` of the plane through `point` with unit `normal` (the solid on
    /// the side opposite the normal), by parry's half-space projection.
    fn plane_projection(point: Self::V, normal: Self::V, p: Self::V) -> SurfacePoint<Self::V>;
    /// Signed distance from `p` to that plane (positive on the normal's side).
    fn plane_signed_distance(point: Self::V, normal: Self::V, p: Self::V) -> Real {
        Self::plane_projection(point, normal, p).signed_distance()
    }

    /// A parry shape placed in the scene (its local frame's origin and, in 3D, rotation).
    type Shape: Send + Sync;
    /// A ball (a disc in 2D, the section of a horizontal cylinder across the width).
    fn ball(centre: Self::V, radius: Real) -> Self::Shape;
    /// A capsule: the points within `radius` of the segment `a b`.
    fn capsule(a: Self::V, b: Self::V, radius: Real) -> Self::Shape;
    /// A cylinder of `radius` whose axis runs from the centre of one end, `a`, to the other's,
    /// `b` (3D only: the error says why not).
    fn cylinder(a: Self::V, b: Self::V, radius: Real) -> std::result::Result<Self::Shape, String>;
    /// The convex polygon through `vertices` (2D only; the error says why not).
    fn convex_polygon(vertices: &[Self::V]) -> std::result::Result<Self::Shape, String>;
    /// The nearest point of the placed shape's surface to `p`, by parry's point projection.
    fn shape_projection(shape: &Self::Shape, p: Self::V) -> SurfacePoint<Self::V>;
}

/// The nearest point of a solid's surface to a query point `p`, as the offset from `p` to it,
/// and whether `p` is inside the solid: the signed distance and, for a point inside, the
/// direction out of the solid (modified DBC's wall normals, `boundary/mdbc.rs`) come from one
/// projection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint<V> {
    /// Surface point minus query point.
    pub offset: V,
    pub inside: bool,
}

impl<V: Vector> SurfacePoint<V> {
    /// Distance from the query point to the surface, negative inside.
    pub fn signed_distance(&self) -> Real {
        let d = self.offset.length();
        if self.inside {
            -d
        } else {
            d
        }
    }
}

/// A parry shape in its local frame, placed in the scene: local point `q` is at
/// `origin + rotation q`.
pub struct Placed<S: ?Sized, V, R> {
    pub shape: Box<S>,
    pub origin: V,
    pub rotation: R,
}

#[derive(Clone, Copy, Debug, Default)]
pub struct Dim2;
#[derive(Clone, Copy, Debug, Default)]
pub struct Dim3;

macro_rules! shape_queries {
    ($parry:ident) => {
        fn box_projection(min: Self::V, max: Self::V, p: Self::V) -> SurfacePoint<Self::V> {
            use $parry::query::PointQuery;
            let half = (max - min) * 0.5;
            let centre = (max + min) * 0.5;
            let proj = $parry::shape::Cuboid::new(half).project_local_point(p - centre, false);
            SurfacePoint { offset: proj.point - (p - centre), inside: proj.is_inside }
        }
        fn plane_projection(point: Self::V, normal: Self::V, p: Self::V) -> SurfacePoint<Self::V> {
            use $parry::query::PointQuery;
            let proj = $parry::shape::HalfSpace::new(normal).project_local_point(p - point, false);
            SurfacePoint { offset: proj.point - (p - point), inside: proj.is_inside }
        }
        fn ball(centre: Self::V, radius: Real) -> Self::Shape {
            Placed { shape: Box::new($parry::shape::Ball::new(radius)), origin: centre, rotation: Default::default() }
        }
        fn capsule(a: Self::V, b: Self::V, radius: Real) -> Self::Shape {
            let shape = $parry::shape::Capsule::new(a - a, b - a, radius);
            Placed { shape: Box::new(shape), origin: a, rotation: Default::default() }
        }
    };
}

impl Dim for Dim2 {
    const DIM: usize = 2;
    const STENCIL: usize = 9;
    type V = DVec2;
    /// xx, yy, xy
    type Sym = [Real; 3];
    type Mesh = ();

    fn mesh(_: &[Vec<Real>], _: &[[u32; 3]]) -> std::result::Result<(), String> {
        Err("a triangle mesh needs dim = 3".to_string())
    }
    fn mesh_projection(_: &(), _: DVec2) -> SurfacePoint<DVec2> {
        SurfacePoint { offset: DVec2::splat(Real::INFINITY), inside: false }
    }

    type Shape = Placed<dyn parry2d_f64::shape::Shape, DVec2, ()>;
    fn cylinder(_: DVec2, _: DVec2, _: Real) -> std::result::Result<Self::Shape, String> {
        Err("a cylinder needs dim = 3 (in 2D, a sphere is the section of a cylinder across the width)".to_string())
    }
    fn convex_polygon(vertices: &[DVec2]) -> std::result::Result<Self::Shape, String> {
        let polygon = parry2d_f64::shape::ConvexPolygon::from_convex_hull(vertices)
            .ok_or_else(|| "the vertices enclose no area".to_string())?;
        if polygon.points().len() != vertices.len() {
            return Err(format!(
                "the polygon is not convex or repeats a vertex: its convex hull has {} of its {} vertices",
                polygon.points().len(),
                vertices.len()
            ));
        }
        Ok(Placed { shape: Box::new(polygon), origin: DVec2::ZERO, rotation: () })
    }
    fn shape_projection(shape: &Self::Shape, p: DVec2) -> SurfacePoint<DVec2> {
        let q = p - shape.origin;
        let proj = shape.shape.project_local_point(q, false);
        SurfacePoint { offset: proj.point - q, inside: proj.is_inside }
    }

    #[inline(always)]
    fn sym_add_outer(s: &mut Self::Sym, a: DVec2, b: DVec2, w: Real) {
        s[0] += w * a.x * b.x;
        s[1] += w * a.y * b.y;
        s[2] += w * 0.5 * (a.x * b.y + a.y * b.x);
    }
    #[inline(always)]
    fn sym_dot(s: &Self::Sym, v: DVec2) -> DVec2 {
        DVec2::new(s[0] * v.x + s[2] * v.y, s[2] * v.x + s[1] * v.y)
    }
    #[inline(always)]
    fn sym_trace_and_norm2(s: &Self::Sym) -> (Real, Real) {
        (s[0] + s[1], s[0] * s[0] + s[1] * s[1] + 2.0 * s[2] * s[2])
    }
    #[inline(always)]
    fn sym_scale_add_diag(s: &Self::Sym, a: Real, b: Real) -> Self::Sym {
        [a * s[0] + b, a * s[1] + b, a * s[2]]
    }
    #[inline(always)]
    fn sym_min_eigenvalue(s: &Self::Sym) -> Real {
        let half = 0.5 * (s[0] - s[1]);
        0.5 * (s[0] + s[1]) - (half * half + s[2] * s[2]).sqrt()
    }
    #[inline(always)]
    fn sym_adjugate_dot(s: &Self::Sym, v: DVec2) -> DVec2 {
        DVec2::new(s[1] * v.x - s[2] * v.y, s[0] * v.y - s[2] * v.x)
    }
    fn sym_inverse(s: &Self::Sym) -> Option<Self::Sym> {
        let det = s[0] * s[1] - s[2] * s[2];
        (det != 0.0 && det.is_finite()).then(|| [s[1] / det, s[0] / det, -s[2] / det])
    }
    fn sym_identity() -> Self::Sym {
        [1.0, 1.0, 0.0]
    }
    shape_queries!(parry2d_f64);
}

impl Dim for Dim3 {
    const DIM: usize = 3;
    const STENCIL: usize = 27;
    type V = DVec3;
    /// xx, yy, zz, xy, xz, yz
    type Sym = [Real; 6];
    type Mesh = parry3d_f64::shape::TriMesh;

    fn mesh(vertices: &[Vec<Real>], triangles: &[[u32; 3]]) -> std::result::Result<Self::Mesh, String> {
        use parry3d_f64::shape::{TriMesh, TriMeshFlags};
        let v: Vec<DVec3> = vertices.iter().map(|p| DVec3::from_slice(p)).collect();
        let flags = TriMeshFlags::ORIENTED | TriMeshFlags::MERGE_DUPLICATE_VERTICES;
        TriMesh::with_flags(v, triangles.to_vec(), flags).map_err(|e| format!("not a usable triangle mesh: {e:?}"))
    }
    type Shape = Placed<dyn parry3d_f64::shape::Shape, DVec3, glam::DQuat>;
    fn cylinder(a: DVec3, b: DVec3, radius: Real) -> std::result::Result<Self::Shape, String> {
        let axis = b - a;
        let length = axis.length();
        if !(length > 0.0) {
            return Err("the axis' ends a and b must differ".to_string());
        }
        // parry's cylinder runs along its local y axis, centred on the origin
        let rotation = glam::DQuat::from_rotation_arc(DVec3::Y, axis / length);
        let shape = parry3d_f64::shape::Cylinder::new(0.5 * length, radius);
        Ok(Placed { shape: Box::new(shape), origin: (a + b) * 0.5, rotation })
    }
    fn convex_polygon(_: &[DVec3]) -> std::result::Result<Self::Shape, String> {
        Err("a polygon needs dim = 2 (in 3D, a closed mesh)".to_string())
    }
    fn shape_projection(shape: &Self::Shape, p: DVec3) -> SurfacePoint<DVec3> {
        let q = shape.rotation.inverse() * (p - shape.origin);
        let proj = shape.shape.project_local_point(q, false);
        SurfacePoint { offset: shape.rotation * (proj.point - q), inside: proj.is_inside }
    }
    fn mesh_projection(mesh: &Self::Mesh, p: DVec3) -> SurfacePoint<DVec3> {
        use parry3d_f64::query::PointQuery;
        // the pseudo-normal projection gives the nearest surface point and a reliable inside flag
        let (proj, _) = mesh.project_local_point_and_get_feature(p);
        SurfacePoint { offset: proj.point - p, inside: proj.is_inside }
    }

    #[inline(always)]
    fn sym_add_outer(s: &mut Self::Sym, a: DVec3, b: DVec3, w: Real) {
        s[0] += w * a.x * b.x;
        s[1] += w * a.y * b.y;
        s[2] += w * a.z * b.z;
        s[3] += w * 0.5 * (a.x * b.y + a.y * b.x);
        s[4] += w * 0.5 * (a.x * b.z + a.z * b.x);
        s[5] += w * 0.5 * (a.y * b.z + a.z * b.y);
    }
    #[inline(always)]
    fn sym_dot(s: &Self::Sym, v: DVec3) -> DVec3 {
        DVec3::new(
            s[0] * v.x + s[3] * v.y + s[4] * v.z,
            s[3] * v.x + s[1] * v.y + s[5] * v.z,
            s[4] * v.x + s[5] * v.y + s[2] * v.z,
        )
    }
    #[inline(always)]
    fn sym_trace_and_norm2(s: &Self::Sym) -> (Real, Real) {
        (
            s[0] + s[1] + s[2],
            s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]),
        )
    }
    #[inline(always)]
    fn sym_scale_add_diag(s: &Self::Sym, a: Real, b: Real) -> Self::Sym {
        [a * s[0] + b, a * s[1] + b, a * s[2] + b, a * s[3], a * s[4], a * s[5]]
    }
    /// The trigonometric solution of the characteristic cubic (Smith 1961, Commun. ACM 4(4)).
    fn sym_min_eigenvalue(s: &Self::Sym) -> Real {
        let [xx, yy, zz, xy, xz, yz] = *s;
        let off = xy * xy + xz * xz + yz * yz;
        let q = (xx + yy + zz) / 3.0;
        let (a, b, c) = (xx - q, yy - q, zz - q);
        let p = ((a * a + b * b + c * c + 2.0 * off) / 6.0).sqrt();
        if p == 0.0 {
            return q;
        }
        // det((s - q I) / p) / 2, clamped to [-1, 1] against rounding
        let det = a * (b * c - yz * yz) - xy * (xy * c - yz * xz) + xz * (xy * yz - b * xz);
        let r = (det / (2.0 * p * p * p)).clamp(-1.0, 1.0);
        let phi = r.acos() / 3.0;
        q + 2.0 * p * (phi + 2.0 * std::f64::consts::FRAC_PI_3).cos()
    }
    fn sym_adjugate_dot(s: &Self::Sym, v: DVec3) -> DVec3 {
        let [xx, yy, zz, xy, xz, yz] = *s;
        let (a00, a11, a22) = (yy * zz - yz * yz, xx * zz - xz * xz, xx * yy - xy * xy);
        let (a01, a02, a12) = (xz * yz - xy * zz, xy * yz - xz * yy, xy * xz - xx * yz);
        DVec3::new(a00 * v.x + a01 * v.y + a02 * v.z, a01 * v.x + a11 * v.y + a12 * v.z, a02 * v.x + a12 * v.y + a22 * v.z)
    }
    fn sym_inverse(s: &Self::Sym) -> Option<Self::Sym> {
        let [xx, yy, zz, xy, xz, yz] = *s;
        let (a00, a11, a22) = (yy * zz - yz * yz, xx * zz - xz * xz, xx * yy - xy * xy);
        let (a01, a02, a12) = (xz * yz - xy * zz, xy * yz - xz * yy, xy * xz - xx * yz);
        let det = xx * a00 + xy * a01 + xz * a02;
        (det != 0.0 && det.is_finite()).then(|| [a00 / det, a11 / det, a22 / det, a01 / det, a02 / det, a12 / det])
    }
    fn sym_identity() -> Self::Sym {
        [1.0, 1.0, 1.0, 0.0, 0.0, 0.0]
    }
    shape_queries!(parry3d_f64);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smallest_eigenvalue_and_adjugate() {
        // 2D: [[3, 1], [1, 2]] has eigenvalues (5 -+ sqrt 5) / 2
        let s2 = [3.0, 2.0, 1.0];
        assert!((Dim2::sym_min_eigenvalue(&s2) - (5.0 - 5f64.sqrt()) / 2.0).abs() < 1e-14);
        let v2 = DVec2::new(0.3, -1.2);
        let back = Dim2::sym_dot(&s2, Dim2::sym_adjugate_dot(&s2, v2)) / 5.0;
        assert!((back - v2).length() < 1e-14, "{back}");
        // 3D: diag(2, 3, 4) rotated about z by 30 degrees keeps its eigenvalues 2, 3, 4
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let s3 = [2.0 * c * c + 3.0 * s * s, 2.0 * s * s + 3.0 * c * c, 4.0, (2.0 - 3.0) * c * s, 0.0, 0.0];
        assert!((Dim3::sym_min_eigenvalue(&s3) - 2.0).abs() < 1e-12);
        assert!((Dim3::sym_min_eigenvalue(&[1.5, 1.5, 1.5, 0.0, 0.0, 0.0]) - 1.5).abs() < 1e-15);
        let v3 = DVec3::new(0.3, -1.2, 0.7);
        let back = Dim3::sym_dot(&s3, Dim3::sym_adjugate_dot(&s3, v3)) / 24.0;
        assert!((back - v3).length() < 1e-12, "{back}");
        // inverses: s (s^-1 v) = v; a singular tensor has none
        let inv2 = Dim2::sym_inverse(&s2).expect("regular");
        assert!((Dim2::sym_dot(&s2, Dim2::sym_dot(&inv2, v2)) - v2).length() < 1e-14);
        let s3b = [2.0, 3.0, 4.0, 0.5, -0.3, 0.2];
        let inv3 = Dim3::sym_inverse(&s3b).expect("regular");
        assert!((Dim3::sym_dot(&s3b, Dim3::sym_dot(&inv3, v3)) - v3).length() < 1e-14);
        assert!(Dim2::sym_inverse(&[1.0, 1.0, 1.0]).is_none() && Dim3::sym_inverse(&[0.0; 6]).is_none());
        assert_eq!(Dim2::sym_dot(&Dim2::sym_identity(), v2), v2);
        assert_eq!(Dim3::sym_dot(&Dim3::sym_identity(), v3), v3);
    }

    #[test]
    fn box_distance_signs() {
        let min = DVec2::new(0.0, 0.0);
        let max = DVec2::new(2.0, 1.0);
        assert!((Dim2::box_signed_distance(min, max, DVec2::new(1.0, 0.5)) + 0.5).abs() < 1e-12);
        assert!((Dim2::box_signed_distance(min, max, DVec2::new(-0.25, 0.5)) - 0.25).abs() < 1e-12);
        let d3 = Dim3::box_signed_distance(DVec3::ZERO, DVec3::ONE, DVec3::new(0.5, 0.5, 1.5));
        assert!((d3 - 0.5).abs() < 1e-12);
    }

    #[test]
    fn plane_distance_signs() {
        let n = DVec2::new(-1.0, 1.0).normalize();
        let d = Dim2::plane_signed_distance(DVec2::ZERO, n, DVec2::new(0.0, 1.0));
        assert!((d - 1.0 / 2f64.sqrt()).abs() < 1e-12);
        let d = Dim2::plane_signed_distance(DVec2::ZERO, n, DVec2::new(1.0, 0.0));
        assert!((d + 1.0 / 2f64.sqrt()).abs() < 1e-12);
    }
}
