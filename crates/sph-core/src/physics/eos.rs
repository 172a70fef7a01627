//! Tait equation of state (Batchelor 1967; Monaghan 1994): `P = B ((rho/rho0)^gamma - 1)`.
//!
//! The only home of the law: the stiffness, the f64 pressure and sound speed of one particle
//! (the particle itself in the force loops, walls, initialisation, output) and [`TaitPair`],
//! the same law in the pair float type for the neighbours of the batched force loop. The two
//! forms of gamma = 7 differ in their last bits (`rho / rho0` against `rho * (1 / rho0)`, and the
//! order of the products), so a change to the law changes both here.

use super::Constants;
use crate::math::{PairFloat, Real};

/// Tait stiffness `B = c0^2 rho0 / gamma` [Pa], which makes `dP/drho = c0^2` at `rho0`.
pub fn stiffness(c0: Real, rho0: Real, gamma: Real) -> Real {
    c0 * c0 * rho0 / gamma
}

/// Whether the exponent is 7, the usual value, for which powers are products and the batched
/// force loop forms the neighbours' pressures in its vectorised loop.
#[inline(always)]
pub fn seventh_power(c: &Constants) -> bool {
    c.gamma == 7.0
}

/// Pressure [Pa] from density.
#[inline(always)]
pub fn pressure(c: &Constants, rho: Real) -> Real {
    let x = rho / c.rho0;
    let xg = if seventh_power(c) {
        let x2 = x * x;
        x2 * x2 * x2 * x
    } else {
        x.powf(c.gamma)
    };
    c.b_tait * (xg - 1.0)
}

/// Local sound speed `c = c0 (rho/rho0)^((gamma - 1)/2)` [m/s].
#[inline(always)]
pub fn sound_speed(c: &Constants, rho: Real) -> Real {
    let x = rho * c.inv_rho0;
    if seventh_power(c) {
        c.c0 * x * x * x
    } else {
        c.c0 * x.powf(0.5 * (c.gamma - 1.0))
    }
}

/// Density at pressure `p`: the inverse of [`pressure`], used for hydrostatic initialisation.
pub fn density_at_pressure(c: &Constants, p: Real) -> Real {
    c.rho0 * (1.0 + p / c.b_tait).max(0.0).powf(1.0 / c.gamma)
}

/// The gamma = 7 law in the pair float type `F` of the batched force loop, with its constants
/// rounded to `F` once.
#[derive(Clone, Copy)]
pub struct TaitPair<F: PairFloat> {
    inv_rho0: F,
    b_tait: F,
    c0: F,
}

impl<F: PairFloat> TaitPair<F> {
    #[inline(always)]
    pub fn new(c: &Constants) -> Self {
        Self { inv_rho0: F::of(c.inv_rho0), b_tait: F::of(c.b_tait), c0: F::of(c.c0) }
    }

    /// Pressure and sound speed at density `rho`, with `x = rho / rho0` taken as
    /// `rho * (1 / rho0)`: `(B (x^7 - 1), c0 x^3)`.
    #[inline(always)]
    pub fn seventh_of_density(&self, rho: F) -> (F, F) {
        let x = rho * self.inv_rho0;
        let x3 = x * x * x;
        (self.b_tait * (x3 * x3 * x - F::of(1.0)), self.c0 * x3)
    }

    /// Pressure and sound speed from the relative density `e = rho/rho0 - 1` (formed in f64):
    /// `(1 + e)^7 - 1` by Horner in `e` (binomial coefficients), without the cancellation near
    /// `rho0` that `x^7 - 1` has, so the pressure keeps single precision's relative precision.
    #[inline(always)]
    pub fn seventh_of_relative(&self, e: F) -> (F, F) {
        let (one, seven, twenty_one, thirty_five) = (F::of(1.0), F::of(7.0), F::of(21.0), F::of(35.0));
        let x = one + e;
        let x3 = x * x * x;
        let poly = e * (seven + e * (twenty_one + e * (thirty_five + e * (thirty_five + e * (twenty_one + e * (seven + e))))));
        (self.b_tait * poly, self.c0 * x3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    #[test]
    fn inverse_and_sound_speed() {
        let s = Scene::from_json(
            r#"{"dim": 2, "dp": 0.01, "tank": {"min": [0, 0], "max": [1, 1]}, "fluid": [{"min": [0, 0], "max": [1, 0.5]}]}"#,
        )
        .expect("scene");
        let c = Constants::new(&s);
        assert!((c.c0 - 20.0 * (9.81f64 * 0.5).sqrt()).abs() < 1e-12);
        let p = 1000.0 * 9.81 * 0.5;
        let rho = density_at_pressure(&c, p);
        assert!((pressure(&c, rho) - p).abs() < 1e-6 * p);
        assert_eq!(pressure(&c, c.rho0), 0.0);
        assert!((sound_speed(&c, c.rho0) - c.c0).abs() < 1e-12);
        // dP/drho = c^2
        let eps = 1e-3;
        let dpdrho = (pressure(&c, rho + eps) - pressure(&c, rho - eps)) / (2.0 * eps);
        assert!((dpdrho - sound_speed(&c, rho).powi(2)).abs() < 1e-6 * dpdrho);
    }
}
