//! Prescribed boundary motion: the wave-maker paddle (DESIGN.md section 3).
//!
//! A motion law gives the paddle displacement `X(t)` [m] and its rate `X'(t)` at the still-water
//! level; Python computes the law's coefficients (Biesel, Madsen, spectra, Goring) and the core
//! evaluates it every step. A piston translates by `X` along x; a flap rotates about its hinge by
//! `theta = atan(X / (z_swl - z_hinge))`, so that its face at the still-water level moves by `X`.

use serde::{Deserialize, Serialize};

use crate::absorption::Absorption;
use crate::error::{Error, Result};
use crate::math::Real;

/// Shape of the start-up ramp applied to a harmonic law.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum RampShape {
    /// `min(1, t / T_r)`.
    #[default]
    Linear,
    /// `tanh(4 t / T_r)`: smooth in velocity, 0.9993 at `T_r`.
    Tanh,
}

/// A paddle displacement law `X(t)`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum MotionLaw {
    /// `X(t) = r(t) sum_i a_i sin(omega_i t + phi_i)` with start-up ramp `r`: first and second
    /// order regular waves (Biesel; Madsen 1971) and irregular waves (one component per
    /// spectral line).
    Harmonic {
        /// `[amplitude (m), angular frequency (rad/s), phase (rad)]` per component.
        components: Vec<[Real; 3]>,
        /// Ramp duration [s]; 0 for none.
        #[serde(default)]
        ramp_duration: Real,
        #[serde(default)]
        ramp_shape: RampShape,
    },
    /// Displacement `x` [m] at times `t` [s], linearly interpolated (the rate is the slope of
    /// the segment); held at the first and last values outside the table. Solitary waves
    /// (Goring 1978) and measured paddle records use it.
    Table { t: Vec<Real>, x: Vec<Real> },
}

impl MotionLaw {
    pub fn validate(&self, field: &str) -> Result<()> {
        match self {
            MotionLaw::Harmonic { components, ramp_duration, .. } => {
                if !ramp_duration.is_finite() || *ramp_duration < 0.0 {
                    return Err(Error::invalid(format!("{field}.ramp_duration"), format!("must be finite and >= 0, got {ramp_duration}")));
                }
                for (i, c) in components.iter().enumerate() {
                    if c.iter().any(|v| !v.is_finite()) {
                        return Err(Error::invalid(format!("{field}.components[{i}]"), "values must be finite"));
                    }
                    if c[1] < 0.0 {
                        return Err(Error::invalid(format!("{field}.components[{i}]"), format!("angular frequency must be >= 0, got {}", c[1])));
                    }
                }
            }
            MotionLaw::Table { t, x } => {
                if t.len() != x.len() {
                    return Err(Error::invalid(format!("{field}.x"), format!("has {} values but t has {}", x.len(), t.len())));
                }
                if t.len() < 2 {
                    return Err(Error::invalid(format!("{field}.t"), "needs at least 2 samples"));
                }
                if let Some(v) = t.iter().chain(x).find(|v| !v.is_finite()) {
                    return Err(Error::invalid(field, format!("values must be finite, got {v}")));
                }
                if let Some(i) = t.windows(2).position(|w| w[1] <= w[0]) {
                    return Err(Error::invalid(format!("{field}.t"), format!("must increase strictly (t[{}] >= t[{}])", i, i + 1)));
                }
            }
        }
        Ok(())
    }

    /// Largest displacement toward -x the law can reach [m] (a bound for harmonic laws).
    pub fn max_backward_excursion(&self) -> Real {
        match self {
            MotionLaw::Harmonic { components, .. } => components.iter().map(|c| c[0].abs()).sum(),
            MotionLaw::Table { x, .. } => x.iter().fold(0.0, |m: Real, &v| m.max(-v)),
        }
    }

    /// Displacement [m] and its rate [m/s] at time `t`.
    pub fn eval(&self, t: Real) -> (Real, Real) {
        match self {
            MotionLaw::Harmonic { components, ramp_duration, ramp_shape } => {
                let (mut x, mut v) = (0.0, 0.0);
                for &[a, w, phi] in components {
                    let (s, c) = (w * t + phi).sin_cos();
                    x += a * s;
                    v += a * w * c;
                }
                let (r, dr) = ramp(*ramp_shape, *ramp_duration, t);
                (r * x, r * v + dr * x)
            }
            MotionLaw::Table { t: ts, x: xs } => {
                let n = ts.len();
                if t <= ts[0] {
                    return (xs[0], 0.0);
                }
                if t >= ts[n - 1] {
                    return (xs[n - 1], 0.0);
                }
                // first index with ts[i] > t
                let i = ts.partition_point(|&s| s <= t);
                let (t0, t1, x0, x1) = (ts[i - 1], ts[i], xs[i - 1], xs[i]);
                let slope = (x1 - x0) / (t1 - t0);
                (x0 + slope * (t - t0), slope)
            }
        }
    }
}

/// Ramp value and its time derivative.
fn ramp(shape: RampShape, duration: Real, t: Real) -> (Real, Real) {
    if duration <= 0.0 {
        return (1.0, 0.0);
    }
    match shape {
        RampShape::Linear => {
            if t < duration {
                (t.max(0.0) / duration, if t > 0.0 { 1.0 / duration } else { 0.0 })
            } else {
                (1.0, 0.0)
            }
        }
        RampShape::Tanh => {
            let k = 4.0 / duration;
            let th = (k * t.max(0.0)).tanh();
            (th, k * (1.0 - th * th))
        }
    }
}

/// Which way the paddle moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PaddleKind {
    Piston,
    /// Rotates about a horizontal hinge (along y in 3D) at `(x, hinge_z)`.
    Flap,
}

/// A wave-maker paddle: a plate of wall particles whose face is at `x` at rest, spanning the
/// tank's height (and width in 3D), `layers` thick behind the face, moved by `law`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paddle {
    pub kind: PaddleKind,
    /// Face position at rest [m].
    pub x: Real,
    /// Hinge height of a flap [m]; default: the tank floor. Below it the plate is a fixed wall.
    #[serde(default)]
    pub hinge_z: Option<Real>,
    /// Still-water level [m] where the flap's displacement `X` is measured; default: the top of
    /// the highest fluid box.
    #[serde(default)]
    pub swl_z: Option<Real>,
    pub law: MotionLaw,
    /// Active wave absorption (see [`crate::absorption`]); none when left out.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub absorption: Option<Absorption>,
}

/// Rigid motion of the paddle at one instant, applied to reference positions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PaddlePose {
    /// Translation along x by `dx`, at speed `u`.
    Piston { dx: Real, u: Real },
    /// Rotation by `theta` about `(hinge_x, hinge_z)` in the x-z plane at rate `omega`; positive
    /// `theta` moves the top of the flap toward +x.
    Flap { hinge_x: Real, hinge_z: Real, theta: Real, omega: Real },
}

impl Paddle {
    /// Pose at time `t`; `swl_z` and `hinge_z` resolved by the solver.
    pub fn pose(&self, t: Real, hinge_z: Real, swl_z: Real) -> PaddlePose {
        let (x, v) = self.law.eval(t);
        self.pose_at(x, v, hinge_z, swl_z)
    }

    /// Pose at time `t` with the displacement `dx` [m] and rate `du` [m/s] at the still-water
    /// level added to the law's (active absorption's correction).
    pub fn pose_displaced(&self, t: Real, hinge_z: Real, swl_z: Real, dx: Real, du: Real) -> PaddlePose {
        let (x, v) = self.law.eval(t);
        self.pose_at(x + dx, v + du, hinge_z, swl_z)
    }

    /// Pose with the displacement `x` [m] and its rate `v` [m/s] at the still-water level.
    fn pose_at(&self, x: Real, v: Real, hinge_z: Real, swl_z: Real) -> PaddlePose {
        match self.kind {
            PaddleKind::Piston => PaddlePose::Piston { dx: x, u: v },
            PaddleKind::Flap => {
                let lever = (swl_z - hinge_z).max(Real::EPSILON);
                let theta = (x / lever).atan();
                let omega = v * lever / (lever * lever + x * x);
                PaddlePose::Flap { hinge_x: self.x, hinge_z, theta, omega }
            }
        }
    }
}

impl PaddlePose {
    /// Position and velocity `(x, z)` of a point whose rest position is `(x0, z0)`.
    #[inline]
    pub fn apply(&self, x0: Real, z0: Real) -> ([Real; 2], [Real; 2]) {
        match *self {
            PaddlePose::Piston { dx, u } => ([x0 + dx, z0], [u, 0.0]),
            PaddlePose::Flap { hinge_x, hinge_z, theta, omega } => {
                let (s, c) = theta.sin_cos();
                let (rx, rz) = (x0 - hinge_x, z0 - hinge_z);
                let (qx, qz) = (rx * c + rz * s, -rx * s + rz * c);
                ([hinge_x + qx, hinge_z + qz], [omega * qz, -omega * qx])
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fd_rate(law: &MotionLaw, t: Real) -> Real {
        let e = 1e-6;
        (law.eval(t + e).0 - law.eval(t - e).0) / (2.0 * e)
    }

    #[test]
    fn harmonic_rate_is_the_derivative_with_ramps() {
        for shape in [RampShape::Linear, RampShape::Tanh] {
            let law = MotionLaw::Harmonic {
                components: vec![[0.05, 4.9, 0.0], [0.004, 9.8, 0.3]],
                ramp_duration: 2.0,
                ramp_shape: shape,
            };
            for t in [0.3, 1.1, 1.7, 2.5, 7.0] {
                let (_, v) = law.eval(t);
                assert!((v - fd_rate(&law, t)).abs() < 1e-6, "{shape:?} t {t}: {v} vs {}", fd_rate(&law, t));
            }
            assert_eq!(law.eval(0.0).0, 0.0);
        }
    }

    #[test]
    fn table_interpolates_and_holds() {
        let law = MotionLaw::Table { t: vec![0.0, 1.0, 3.0], x: vec![0.0, 0.2, -0.2] };
        assert_eq!(law.eval(0.5), (0.1, 0.2));
        assert!((law.eval(2.0).0).abs() < 1e-15);
        assert_eq!(law.eval(2.0).1, -0.2);
        assert_eq!(law.eval(5.0), (-0.2, 0.0));
        assert!(MotionLaw::Table { t: vec![0.0, 0.0], x: vec![0.0, 1.0] }.validate("law").is_err());
    }

    #[test]
    fn flap_face_at_swl_moves_by_the_displacement() {
        let p = Paddle {
            kind: PaddleKind::Flap,
            x: 1.0,
            hinge_z: None,
            swl_z: None,
            law: MotionLaw::Table { t: vec![0.0, 1.0], x: vec![0.0, 0.1] },
            absorption: None,
        };
        let pose = p.pose(1.0, 0.0, 0.5);
        let (pos, _) = pose.apply(1.0, 0.5);
        // the face point at the SWL moves along the arc; its horizontal offset over the lever is tan(theta)
        let (theta, lever) = ((0.1f64 / 0.5).atan(), 0.5);
        assert!((pos[0] - (1.0 + lever * theta.sin())).abs() < 1e-12);
        let pose = p.pose(0.5, 0.0, 0.5);
        let e = 1e-7;
        let (a, v) = pose.apply(1.0, 0.4);
        let (b, _) = p.pose(0.5 + e, 0.0, 0.5).apply(1.0, 0.4);
        assert!(((b[0] - a[0]) / e - v[0]).abs() < 1e-5);
        assert!(((b[1] - a[1]) / e - v[1]).abs() < 1e-5);
    }
}
