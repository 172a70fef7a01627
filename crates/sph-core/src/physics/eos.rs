//! Tait equation of state (Batchelor 1967; Monaghan 1994): `P = B ((rho/rho0)^gamma - 1)`.

use super::Constants;
use crate::math::Real;

/// Pressure [Pa] from density.
#[inline(always)]
pub fn pressure(c: &Constants, rho: Real) -> Real {
    let x = rho / c.rho0;
    let xg = if c.gamma == 7.0 {
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
    if c.gamma == 7.0 {
        c.c0 * x * x * x
    } else {
        c.c0 * x.powf(0.5 * (c.gamma - 1.0))
    }
}

/// Density at pressure `p`: the inverse of [`pressure`], used for hydrostatic initialisation.
pub fn density_at_pressure(c: &Constants, p: Real) -> Real {
    c.rho0 * (1.0 + p / c.b_tait).max(0.0).powf(1.0 / c.gamma)
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
