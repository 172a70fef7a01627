//! Smoothing kernels with analytic gradients (seed 000; DESIGN.md section 2).
//!
//! All kernels have compact support `2h`. `grad_factor(r)` returns `(dW/dr) / r`, so that
//! `grad_a W_ab = r_ab * grad_factor(|r_ab|)` without a division by `r` in the hot loop.

use serde::{Deserialize, Serialize};

use crate::math::{PairFloat, Real};

/// Kernel choice of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum KernelKind {
    CubicSpline,
    Wendland,
    WendlandC4,
}

impl KernelKind {
    pub fn name(self) -> &'static str {
        match self {
            KernelKind::CubicSpline => "cubic_spline",
            KernelKind::Wendland => "wendland",
            KernelKind::WendlandC4 => "wendland_c4",
        }
    }
}

/// A radial kernel with support `2h`.
pub trait Kernel: Copy + Send + Sync + 'static {
    const KIND: KernelKind;
    fn new(h: Real, dim: usize) -> Self;
    fn h(&self) -> Real;
    /// Support radius `2h`.
    fn support(&self) -> Real {
        2.0 * self.h()
    }
    /// `W(r)`.
    fn w(&self, r: Real) -> Real;
    /// `(dW/dr) / r` for `0 < r`; finite at `r -> 0`. Zero for `r >= 2h`.
    #[inline(always)]
    fn grad_factor(&self, r: Real) -> Real {
        self.grad_factor_in::<Real>(r)
    }
    /// Whether [`Kernel::grad_factor_inv_r`] uses `1/r` (the pair loop then folds it into the
    /// pair's single division).
    const NEEDS_INV_R: bool = false;
    /// [`Kernel::grad_factor`] given `1/r` as well.
    #[inline(always)]
    fn grad_factor_inv_r(&self, r: Real, inv_r: Real) -> Real {
        self.grad_factor_inv_r_in::<Real>(r, inv_r)
    }
    /// [`Kernel::grad_factor`] in the pair loop's float type (`f64`: the same operations).
    fn grad_factor_in<F: PairFloat>(&self, r: F) -> F;
    /// [`Kernel::grad_factor_inv_r`] in the pair loop's float type.
    #[inline(always)]
    fn grad_factor_inv_r_in<F: PairFloat>(&self, r: F, _inv_r: F) -> F {
        self.grad_factor_in(r)
    }
}

/// Cubic spline M4 (Monaghan & Lattanzio 1985): `alpha_D = 10/(7 pi h^2)` in 2D, `1/(pi h^3)` in 3D.
#[derive(Clone, Copy, Debug)]
pub struct CubicSpline {
    h: Real,
    inv_h: Real,
    alpha_d: Real,
}

impl Kernel for CubicSpline {
    const KIND: KernelKind = KernelKind::CubicSpline;
    fn new(h: Real, dim: usize) -> Self {
        let pi = std::f64::consts::PI;
        let alpha_d = if dim == 2 { 10.0 / (7.0 * pi * h * h) } else { 1.0 / (pi * h * h * h) };
        Self { h, inv_h: 1.0 / h, alpha_d }
    }
    fn h(&self) -> Real {
        self.h
    }
    #[inline(always)]
    fn w(&self, r: Real) -> Real {
        let q = r * self.inv_h;
        if q < 1.0 {
            self.alpha_d * (1.0 - 1.5 * q * q + 0.75 * q * q * q)
        } else if q < 2.0 {
            let t = 2.0 - q;
            self.alpha_d * 0.25 * t * t * t
        } else {
            0.0
        }
    }
    #[inline(always)]
    fn grad_factor_in<F: PairFloat>(&self, r: F) -> F {
        self.grad_factor_inv_r_in(r, F::of(1.0) / r)
    }
    const NEEDS_INV_R: bool = true;
    #[inline(always)]
    fn grad_factor_inv_r_in<F: PairFloat>(&self, r: F, inv_r: F) -> F {
        let q = r * F::of(self.inv_h);
        let c = F::of(self.alpha_d * self.inv_h * self.inv_h);
        // d/dq (1 - 3/2 q^2 + 3/4 q^3) / q = -3 + 9/4 q inside q < 1, -3/4 (2 - q)^2 / q outside;
        // both are computed and one selected: the branch would be mispredicted in the pair loop.
        let inner = c * (F::of(-3.0) + F::of(2.25) * q);
        let t = F::of(2.0) - q;
        // `max(t, 0)` as a comparison (the same value for every input, no NaN blend)
        let t = if t > F::of(0.0) { t } else { F::of(0.0) };
        let outer = c * (F::of(-0.75) * t * t * F::of(self.h) * inv_r); // 1/q = h/r
        if q < F::of(1.0) {
            inner
        } else {
            outer
        }
    }
}

/// Wendland C2 (Wendland 1995): `alpha_D (1 - q/2)^4 (2q + 1)`, `alpha_D = 7/(4 pi h^2)` (2D),
/// `21/(16 pi h^3)` (3D).
#[derive(Clone, Copy, Debug)]
pub struct WendlandC2 {
    h: Real,
    inv_h: Real,
    alpha_d: Real,
    /// `-5 alpha_D / h^2`, the constant of [`Kernel::grad_factor`] (two multiplications per
    /// pair fewer than forming it there).
    grad_coef: Real,
}

impl Kernel for WendlandC2 {
    const KIND: KernelKind = KernelKind::Wendland;
    fn new(h: Real, dim: usize) -> Self {
        let pi = std::f64::consts::PI;
        let alpha_d = if dim == 2 { 7.0 / (4.0 * pi * h * h) } else { 21.0 / (16.0 * pi * h * h * h) };
        let inv_h = 1.0 / h;
        Self { h, inv_h, alpha_d, grad_coef: -5.0 * alpha_d * inv_h * inv_h }
    }
    fn h(&self) -> Real {
        self.h
    }
    #[inline(always)]
    fn w(&self, r: Real) -> Real {
        let q = r * self.inv_h;
        if q < 2.0 {
            let t = 1.0 - 0.5 * q;
            let t2 = t * t;
            self.alpha_d * t2 * t2 * (2.0 * q + 1.0)
        } else {
            0.0
        }
    }
    #[inline(always)]
    fn grad_factor_in<F: PairFloat>(&self, r: F) -> F {
        let q = r * F::of(self.inv_h);
        if q < F::of(2.0) {
            // dW/dq = -5 q alpha_D (1 - q/2)^3, so (dW/dr)/r = -5 alpha_D (1 - q/2)^3 / h^2.
            let t = F::of(1.0) - F::of(0.5) * q;
            F::of(self.grad_coef) * (t * t * t)
        } else {
            F::of(0.0)
        }
    }
}

/// Wendland C4 (Wendland 1995; with support `2h` as in Dehnen & Aly 2012, Table 1):
/// `alpha_D (1 - q/2)^6 (35/12 q^2 + 3 q + 1)`, `alpha_D = 9/(4 pi h^2)` (2D), `495/(256 pi h^3)`
/// (3D). Smoother than C2 (a continuous fourth derivative), with a smaller error in the kernel
/// sums on disordered particles at the same `h`; two more multiplications per pair.
#[derive(Clone, Copy, Debug)]
pub struct WendlandC4 {
    h: Real,
    inv_h: Real,
    alpha_d: Real,
    /// `-14/3 alpha_D / h^2`, the constant of [`Kernel::grad_factor`].
    grad_coef: Real,
}

impl Kernel for WendlandC4 {
    const KIND: KernelKind = KernelKind::WendlandC4;
    fn new(h: Real, dim: usize) -> Self {
        let pi = std::f64::consts::PI;
        let alpha_d = if dim == 2 { 9.0 / (4.0 * pi * h * h) } else { 495.0 / (256.0 * pi * h * h * h) };
        let inv_h = 1.0 / h;
        Self { h, inv_h, alpha_d, grad_coef: -14.0 / 3.0 * alpha_d * inv_h * inv_h }
    }
    fn h(&self) -> Real {
        self.h
    }
    #[inline(always)]
    fn w(&self, r: Real) -> Real {
        let q = r * self.inv_h;
        if q < 2.0 {
            let t = 1.0 - 0.5 * q;
            let t2 = t * t;
            self.alpha_d * t2 * t2 * t2 * ((35.0 / 12.0) * q * q + 3.0 * q + 1.0)
        } else {
            0.0
        }
    }
    #[inline(always)]
    fn grad_factor_in<F: PairFloat>(&self, r: F) -> F {
        let q = r * F::of(self.inv_h);
        if q < F::of(2.0) {
            // dW/dq = -14/3 alpha_D q (1 - q/2)^5 (1 + 5/2 q), so
            // (dW/dr)/r = -14/3 alpha_D (1 - q/2)^5 (1 + 5/2 q) / h^2.
            let t = F::of(1.0) - F::of(0.5) * q;
            let t2 = t * t;
            F::of(self.grad_coef) * (t2 * t2 * t) * (F::of(1.0) + F::of(2.5) * q)
        } else {
            F::of(0.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sum of `W * dx^dim` over a fine lattice centred on the origin.
    fn lattice_integral<K: Kernel>(k: &K, dim: usize, dx: Real) -> Real {
        let n = (k.support() / dx).ceil() as i64 + 1;
        let mut sum = 0.0;
        let cell = dx.powi(dim as i32);
        if dim == 2 {
            for i in -n..=n {
                for j in -n..=n {
                    let r = ((i * i + j * j) as Real).sqrt() * dx;
                    sum += k.w(r) * cell;
                }
            }
        } else {
            for i in -n..=n {
                for j in -n..=n {
                    for l in -n..=n {
                        let r = ((i * i + j * j + l * l) as Real).sqrt() * dx;
                        sum += k.w(r) * cell;
                    }
                }
            }
        }
        sum
    }

    fn check_normalisation<K: Kernel>() {
        for dim in [2, 3] {
            let h = 0.1;
            let k = K::new(h, dim);
            let integral = lattice_integral(&k, dim, h / 20.0);
            assert!((integral - 1.0).abs() < 1e-3, "{:?} dim {dim}: integral {integral}", K::KIND);
        }
    }

    fn check_gradient<K: Kernel>() {
        let h = 0.37;
        for dim in [2, 3] {
            let k = K::new(h, dim);
            for i in 1..200 {
                let r = i as Real * 2.0 * h / 200.0;
                let eps = 1e-6 * h;
                let fd = (k.w(r + eps) - k.w(r - eps)) / (2.0 * eps);
                let analytic = k.grad_factor(r) * r;
                let scale = k.w(0.0) / h;
                assert!(
                    (fd - analytic).abs() < 1e-6 * scale,
                    "{:?} dim {dim} r/h {}: fd {fd} analytic {analytic}",
                    K::KIND,
                    r / h
                );
            }
        }
    }

    fn check_support<K: Kernel>() {
        let h = 0.5;
        for dim in [2, 3] {
            let k = K::new(h, dim);
            assert_eq!(k.w(2.0 * h), 0.0);
            assert_eq!(k.grad_factor(2.0 * h), 0.0);
            assert_eq!(k.w(2.0 * h * 1.0001), 0.0);
            assert!(k.w(2.0 * h * 0.999) > 0.0);
            assert!(k.grad_factor(2.0 * h * 0.999) < 0.0);
        }
    }

    #[test]
    fn cubic_spline_integrates_to_one() {
        check_normalisation::<CubicSpline>();
    }
    #[test]
    fn wendland_integrates_to_one() {
        check_normalisation::<WendlandC2>();
    }
    #[test]
    fn cubic_spline_gradient_matches_finite_differences() {
        check_gradient::<CubicSpline>();
    }
    #[test]
    fn wendland_gradient_matches_finite_differences() {
        check_gradient::<WendlandC2>();
    }
    #[test]
    fn wendland_c4_integrates_to_one() {
        check_normalisation::<WendlandC4>();
    }
    #[test]
    fn wendland_c4_gradient_matches_finite_differences() {
        check_gradient::<WendlandC4>();
    }
    #[test]
    fn wendland_c4_support_ends_at_2h() {
        check_support::<WendlandC4>();
    }
    #[test]
    fn cubic_spline_support_ends_at_2h() {
        check_support::<CubicSpline>();
    }
    #[test]
    fn wendland_support_ends_at_2h() {
        check_support::<WendlandC2>();
    }
}
