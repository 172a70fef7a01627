//! Active wave absorption at the paddle (AWAS): the paddle's displacement gets a correction that
//! moves it with the water of the waves coming back from the flume, so that they leave through
//! the paddle instead of being reflected into the flume again.
//!
//! Schaffer & Klopman (2000, J. Waterway Port Coastal Ocean Eng. 126(2)), as DualSPHysics'
//! AWAS (Altomare et al. 2017, Coastal Eng. 127, eqs. 8-10), which corrects pistons only; the
//! correction is written here for the displacement `X` at the still-water level, so that it
//! serves a flap as well. The surface elevation measured in front of the paddle, `eta_M`, is
//! the target elevation `eta_T` of the generated wave plus the elevation `eta_R` of the waves
//! arriving from the flume. A wave of elevation `eta_R` travelling toward the paddle carries the
//! water at the velocity the paddle must have to let it through: in linear theory the paddle's
//! displacement rate and the elevation it makes are in phase, with the ratio `omega / (H/S)`
//! (the paddle's transfer function `H/S`, Biesel & Suquet 1951), `sqrt(g/d)` in shallow water
//! for a piston. The correction rate is
//!
//! `dX_c/dt = -G (eta_M - eta_T) - X_c / tau`
//!
//! with `G` that ratio at the wave's (peak) frequency (the caller's wave theory computes it) and
//! the drift term (time constant `tau`, several wave periods) pulling the correction's mean back
//! to zero, so that the paddle keeps its stroke centred (the drift correction of Altomare et
//! al. 2017, section 2.3).
//!
//! The probe stands `x_p` in front of the face (it cannot read the water through the paddle's
//! own particles), so it sees a wave coming back `x_p / c` before the paddle does, and the
//! paddle's own correction wave, with its evanescent near field, after it. Two things make up
//! for that, both computed by the caller from the wave law and `x_p`: the target is the
//! elevation the generated wave has at the probe, not at the face; and the difference passes
//! through a first-order lag `T_l de/dt = (eta_M - eta_T) - e` before it drives the paddle, the
//! phase lag `atan(omega T_l)` it gives at the wave's frequency being the one that makes the
//! correction cancel the returning wave at the paddle (with a perfect absorber the probe sees
//! the returning wave alone, which reaches the paddle `x_p / c` later: a delay of `k x_p`,
//! plus the near field's share). The gain includes the lag's loss of amplitude.
//!
//! The difference also has a mean that no wave carries: the still water's own settling, the
//! waves' set-down, and the probe riding on the face, which oscillates with the wave so that
//! it reads the crests a little further out than the troughs. Integrated, a steady difference
//! `e_0` moves the paddle's mean position by `-G tau e_0` (a flap's `G tau` of a hundred makes a
//! millimetre of it a decimetre, more than its stroke, and the paddle's wave then leaves from
//! the wrong place). The difference's running mean `m` (`tau_m dm/dt = (eta_M - eta_T) - m`) is
//! therefore taken off:
//!
//! `dX_c/dt = -G (e - m) - X_c / tau`
//!
//! The mean removal and the drift term in cascade are a second-order high-pass from the
//! difference to `X_c`: a slow rise of the difference at the rate `r` (the settling of the
//! particles) holds the paddle back by `G tau_m tau r` as long as it lasts, so the mean's time
//! constant `tau_m` may be shorter than the drift's (a few periods rather than ten).
//!
//! The solver evaluates it once per step before moving the paddle: `eta_M` from the fluid at
//! the start of the step, `e` updated over the step just done as if `eta_M - eta_T` had been
//! its present value throughout, the rate held over the new step.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::math::Real;
use crate::motion::MotionLaw;

/// What the absorption needs from a scene, part of the paddle's spec (`paddle.absorption`),
/// checked as it is read.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, try_from = "Fields")]
pub struct Absorption {
    /// Target surface elevation at the paddle `eta_T(t)` [m above the still water]: the wave
    /// the paddle's law generates, as linear theory gives it at the paddle (a harmonic signal or
    /// a table, in the forms of the motion law).
    pub target: MotionLaw,
    /// `G`: the paddle's displacement rate at the still-water level per metre of elevation
    /// [1/s] (`omega / (H/S)` of the paddle at the wave's frequency).
    pub gain: Real,
    /// Where `eta_M` is measured: this far in front of the paddle's face at the still-water
    /// level [m] (far enough to read the water, not the paddle's own particles).
    pub probe_offset: Real,
    /// Time constant `tau` of the drift correction [s].
    pub drift_time: Real,
    /// Time constant `T_l` of the lag applied to `eta_M - eta_T` [s] (0: none).
    pub lag_time: Real,
    /// Time constant `tau_m` of the running mean taken off the difference [s] (None: `tau`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_time: Option<Real>,
}

/// The correction's state: displacement `X_c` [m] and its rate [m/s] over the current step,
/// and the lagged difference `e` and the mean `m` that set the rate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AbsorberState {
    /// `X_c` at `since` [m].
    pub offset: Real,
    /// `dX_c/dt` held since `since` [m/s].
    pub rate: Real,
    /// Start of the current step [s].
    pub since: Real,
    /// `e` at `since` [m].
    pub lagged: Real,
    /// `m` at `since` [m].
    pub mean: Real,
}

/// The fields as read, before [`Absorption::validate`].
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Fields {
    target: MotionLaw,
    gain: Real,
    probe_offset: Real,
    drift_time: Real,
    #[serde(default)]
    lag_time: Real,
    #[serde(default)]
    mean_time: Option<Real>,
}

impl TryFrom<Fields> for Absorption {
    type Error = Error;
    fn try_from(f: Fields) -> Result<Self> {
        let a = Absorption { target: f.target, gain: f.gain, probe_offset: f.probe_offset, drift_time: f.drift_time, lag_time: f.lag_time, mean_time: f.mean_time };
        a.validate("").map(|()| a)
    }
}

impl Absorption {
    /// Refuses a non-positive or non-finite parameter or a bad target law, naming the field
    /// under `field` (empty: the field alone, for the path serde adds).
    pub fn validate(&self, field: &str) -> Result<()> {
        let under = |name: &str| if field.is_empty() { name.to_string() } else { format!("{field}.{name}") };
        self.target.validate(&under("target"))?;
        for (name, value) in [("gain", self.gain), ("probe_offset", self.probe_offset), ("drift_time", self.drift_time)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::invalid(under(name), format!("must be a positive number, got {value}")));
            }
        }
        if !(self.lag_time.is_finite() && self.lag_time >= 0.0) {
            return Err(Error::invalid(under("lag_time"), format!("must be zero or a positive number, got {}", self.lag_time)));
        }
        if let Some(value) = self.mean_time.filter(|v| !(v.is_finite() && *v > 0.0)) {
            return Err(Error::invalid(under("mean_time"), format!("must be a positive number, got {value}")));
        }
        Ok(())
    }

    /// The state for the step starting at `t`: `eta_measured` [m above the still water] the
    /// elevation read in front of the paddle now (None: no water found, no correction from it).
    pub fn advance(&self, state: AbsorberState, t: Real, eta_measured: Option<Real>) -> AbsorberState {
        let offset = state.offset_at(t);
        let reflected = eta_measured.map_or(0.0, |eta| eta - self.target.eval(t).0);
        // each filter's exact solution over the step for an input held at its present value
        let relax = |previous: Real, time: Real| reflected + (previous - reflected) * (-(t - state.since) / time).exp();
        let lagged = if self.lag_time > 0.0 { relax(state.lagged, self.lag_time) } else { reflected };
        let mean = relax(state.mean, self.mean_time.unwrap_or(self.drift_time));
        AbsorberState { offset, rate: -self.gain * (lagged - mean) - offset / self.drift_time, since: t, lagged, mean }
    }
}

impl AbsorberState {
    /// `X_c` at time `t` within the current step [m].
    #[inline]
    pub fn offset_at(&self, t: Real) -> Real {
        self.offset + self.rate * (t - self.since)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn absorption() -> Absorption {
        Absorption {
            target: MotionLaw::Harmonic { components: vec![[0.02, 2.0, 0.0]], ramp_duration: 0.0, ramp_shape: Default::default() },
            gain: 3.0,
            probe_offset: 0.05,
            drift_time: 10.0,
            lag_time: 0.0,
            mean_time: None,
        }
    }

    #[test]
    fn no_reflected_wave_no_correction() {
        let a = absorption();
        let t = 0.7;
        let s = a.advance(AbsorberState::default(), t, Some(a.target.eval(t).0));
        assert_eq!(s.rate, 0.0);
        assert_eq!(s.offset_at(t + 0.01), 0.0);
    }

    #[test]
    fn the_paddle_moves_with_the_water_of_a_reflected_wave() {
        let a = absorption();
        let t = 1.3;
        // a crest coming back: the paddle retreats (the water under a crest travelling toward
        // -x moves toward -x) at G times its elevation
        let start = AbsorberState { since: t, ..Default::default() };
        let s = a.advance(start, t, Some(a.target.eval(t).0 + 0.01));
        assert!((s.rate + 0.03).abs() < 1e-15);
        assert!((s.offset_at(t + 0.1) + 0.003).abs() < 1e-15);
        // dry probe: only the drift term
        let s2 = a.advance(s, t + 0.1, None);
        assert!((s2.rate - 0.003 / 10.0).abs() < 1e-15);
    }

    #[test]
    fn drift_correction_returns_the_offset_to_zero() {
        let a = absorption();
        let mut s = AbsorberState { offset: 0.05, ..Default::default() };
        let dt = 0.01;
        for i in 0..3000 {
            let t = i as Real * dt;
            s = a.advance(s, t, Some(a.target.eval(t).0));
        }
        // 30 s = 3 tau: e^-3 of the initial offset
        let left = s.offset_at(30.0) / 0.05;
        assert!((left - (-3.0f64).exp()).abs() < 0.01, "{left}");
    }

    #[test]
    fn a_steady_difference_leaves_the_paddle_where_it_was() {
        // integrated, 1 mm of steady difference would hold the paddle G tau e_0 = 30 mm back;
        // its running mean taken off, the correction comes back to zero within a few tau
        let a = absorption();
        let (e0, dt) = (0.001, 0.01);
        let mut s = AbsorberState::default();
        let mut furthest: Real = 0.0;
        for i in 0..10_000 {
            let t = i as Real * dt;
            s = a.advance(s, t, Some(a.target.eval(t).0 + e0));
            furthest = furthest.max(-s.offset);
        }
        let held = a.gain * a.drift_time * e0;
        assert!(furthest < 0.4 * held, "{furthest}");
        assert!(s.offset.abs() < 0.01 * held, "{}", s.offset);
    }

    #[test]
    fn a_slow_rise_holds_the_paddle_back_by_g_tau_m_tau_times_its_rate() {
        // the difference rising at r (a settling surface): once the filters have caught up,
        // X_c = -G tau_m tau r, less with a shorter mean time
        let rate = 1e-5;
        let held = |mean_time: Option<Real>| {
            let mut a = absorption();
            a.mean_time = mean_time;
            let (mut s, dt) = (AbsorberState::default(), 0.01);
            for i in 0..20_000 {
                let t = i as Real * dt;
                s = a.advance(s, t, Some(a.target.eval(t).0 + rate * t));
            }
            let tau_m = mean_time.unwrap_or(a.drift_time);
            (s.offset, -a.gain * tau_m * a.drift_time * rate)
        };
        for mean_time in [None, Some(2.0)] {
            let (offset, expected) = held(mean_time);
            assert!((offset / expected - 1.0).abs() < 0.02, "{offset} {expected}");
        }
    }

    #[test]
    fn the_lag_delays_the_difference_by_its_phase() {
        // a difference sin(omega t) through the lag: in the steady state -G A sin(omega t - phi)
        // with A = 1 / sqrt(1 + (omega T_l)^2), phi = atan(omega T_l)
        let mut a = absorption();
        a.lag_time = 0.05;
        a.gain = 1.0;
        a.drift_time = 1e12;
        let omega = 2.0;
        let (mut s, dt) = (AbsorberState::default(), 1e-4);
        for i in 0..100_000 {
            let t = i as Real * dt;
            s = a.advance(s, t, Some(a.target.eval(t).0 + (omega * t).sin()));
        }
        let t = s.since;
        let (gain, phase) = (1.0 / (1.0 + (omega * a.lag_time).powi(2)).sqrt(), (omega * a.lag_time).atan());
        assert!((s.rate + gain * (omega * t - phase).sin()).abs() < 1e-3, "{}", s.rate);
    }

    #[test]
    fn bad_parameters_name_the_field() {
        let mut a = absorption();
        a.gain = 0.0;
        let e = a.validate("paddle.absorption").unwrap_err().to_string();
        assert!(e.contains("paddle.absorption.gain"), "{e}");
        let mut a = absorption();
        a.drift_time = Real::NAN;
        assert!(a.validate("paddle.absorption").unwrap_err().to_string().contains("drift_time"));
        let mut a = absorption();
        a.lag_time = -1.0;
        assert!(a.validate("paddle.absorption").unwrap_err().to_string().contains("lag_time"));
        let mut a = absorption();
        a.mean_time = Some(0.0);
        assert!(a.validate("paddle.absorption").unwrap_err().to_string().contains("mean_time"));
    }
}
