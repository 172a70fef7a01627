//! The core's one error type. Bad user data is an error, never a panic (rerun's CODE_STYLE).

use thiserror::Error;

/// What went wrong, with enough context for the user to act on it.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// A scene field is wrong: `field` is its path (e.g. `viscosity.alpha`).
    #[error("{field}: {reason}")]
    InvalidScene { field: String, reason: String },

    /// The run went unstable. `kind` names the monitor that fired.
    #[error("{kind} at step {step} (t = {time:.6} s), particle {particle} at {position:?}: {message}")]
    Instability {
        kind: InstabilityKind,
        step: u64,
        time: f64,
        /// Original particle id (creation order), not the storage slot.
        particle: u32,
        position: Vec<f64>,
        message: String,
    },

    /// The run was asked to stop (its stop flag set, by the binding on Ctrl-C or SIGTERM): it
    /// stopped between two steps, and the state is the one after `step`, complete and
    /// consistent, so a checkpoint of it resumes the run bit for bit.
    #[error("run interrupted after step {step} (t = {time} s)")]
    Interrupted { step: u64, time: f64 },
}

/// Which stability monitor fired.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InstabilityKind {
    /// A position, velocity or density became NaN or infinite.
    NonFinite,
    /// A density left the band around rho0.
    DensityOutOfRange,
    /// The time step fell below its floor.
    TimeStepCollapse,
    /// The time step came out NaN or infinite (a NaN acceleration or sound speed, or nothing
    /// left to limit it), not a small step: told apart from [`Self::TimeStepCollapse`].
    NonFiniteTimeStep,
    /// More fluid particles left the domain than the scene allows.
    OutOfDomain,
    /// Mechanical energy grew without forcing.
    EnergyGrowth,
}

impl std::fmt::Display for InstabilityKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl InstabilityKind {
    pub fn name(self) -> &'static str {
        match self {
            InstabilityKind::NonFinite => "non_finite",
            InstabilityKind::DensityOutOfRange => "density_out_of_range",
            InstabilityKind::TimeStepCollapse => "time_step_collapse",
            InstabilityKind::NonFiniteTimeStep => "non_finite_time_step",
            InstabilityKind::OutOfDomain => "out_of_domain",
            InstabilityKind::EnergyGrowth => "energy_growth",
        }
    }
}

impl Error {
    /// A refused scene field and why. Numbers in the reason are written short (see
    /// [`short_numbers`]).
    pub fn invalid(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Error::InvalidScene { field: field.into(), reason: short_numbers(&reason.into()) }
    }
}

/// Decimal numbers longer than this many characters are rewritten in exponent form.
const LONG_NUMBER: usize = 20;

/// `text` with every decimal number longer than [`LONG_NUMBER`] characters written in exponent
/// form, as `%g` would: Rust's `Display` writes an `f64` in full positional notation (1e-300 as
/// 302 characters, 1e300 as 301), and the refusals format user values with it in many places.
/// A number that long is always a float's positional form (an integer of up to 20 digits, any
/// `u64`, stays as it is), so parsing it back loses nothing that was shown.
pub fn short_numbers(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < bytes.len() {
        if !bytes[i].is_ascii_digit() {
            let next = text[i..].chars().next().map_or(1, char::len_utf8);
            out.push_str(&text[i..i + next]);
            i += next;
            continue;
        }
        let start = i;
        while i < bytes.len() && (bytes[i].is_ascii_digit() || (bytes[i] == b'.' && i + 1 < bytes.len() && bytes[i + 1].is_ascii_digit())) {
            i += 1;
        }
        let number = &text[start..i];
        match number.parse::<f64>() {
            Ok(x) if number.len() > LONG_NUMBER => out.push_str(&format!("{x:e}")),
            _ => out.push_str(number),
        }
    }
    out
}

pub type Result<T> = std::result::Result<T, Error>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refusals_write_long_numbers_short() {
        let tiny = format!("dp = {} m", 1e-300_f64);
        assert!(tiny.len() > 300);
        assert_eq!(short_numbers(&tiny), "dp = 1e-300 m");
        assert_eq!(short_numbers(&format!("x = {}, got {}", 1e300_f64, -2.5e-30_f64)), "x = 1e300, got -2.5e-30");
        // what is short already stays as it is: integers up to a u64, indices, plain decimals
        let plain = "gauges[12].x = 0.30000000000000004 and 18446744073709551615 particles; v1.2";
        assert_eq!(short_numbers(plain), plain);
        assert_eq!(short_numbers("é 1.5"), "é 1.5");
    }
}
