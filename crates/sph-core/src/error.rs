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
    pub fn invalid(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Error::InvalidScene { field: field.into(), reason: reason.into() }
    }
}

pub type Result<T> = std::result::Result<T, Error>;
