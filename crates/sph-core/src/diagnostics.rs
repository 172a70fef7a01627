//! The run's health: the fluid's energy, and the checks that end a run that has blown up or
//! lost its water, each with the error that names the step, the time and a particle
//! (docs/stability.md). The NaN and density-band test runs inside the integrator's sweep
//! ([`find_unstable`], per chunk of slots); the others after a step.

use rayon::prelude::*;

use crate::error::{Error, InstabilityKind, Result};
use crate::math::{Dim, Real, Vector};
use crate::particles::{Particles, KIND_EXCLUDED, KIND_FLUID};
use crate::physics::Constants;

/// Steps between two evaluations of the energy monitor.
const ENERGY_CHECK_EVERY: u64 = 50;

/// What the checks read: the particles, the run's constants and its clock.
pub(crate) struct Diagnostics<'a, D: Dim> {
    pub p: &'a Particles<D>,
    pub c: &'a Constants,
    pub step: u64,
    pub time: Real,
}

impl<D: Dim> Diagnostics<'_, D> {
    /// Kinetic plus potential energy of the fluid still in the domain [J].
    pub fn fluid_energy(&self) -> Real {
        let fs = self.p.fluid_start();
        let (g, m) = (self.c.gravity, self.c.mass);
        let p = self.p;
        // fixed chunks reduced in order: the sum does not depend on the thread count
        const CHUNK: usize = 4096;
        let chunks: Vec<Real> = p.pos[fs..]
            .par_chunks(CHUNK)
            .zip(p.vel[fs..].par_chunks(CHUNK))
            .zip(p.kind[fs..].par_chunks(CHUNK))
            .map(|((x, v), k)| {
                (0..x.len())
                    .filter(|&i| k[i] == KIND_FLUID)
                    .map(|i| m * (0.5 * v[i].length_squared() + g * x[i].vertical()))
                    .sum::<Real>()
            })
            .collect();
        chunks.iter().sum()
    }

    /// Potential energy the fluid would have with every particle on the floor at `floor_z` [J].
    fn floor_energy_offset(&self, floor_z: Real) -> Real {
        let n = self.p.kind[self.p.fluid_start()..].iter().filter(|&&k| k == KIND_FLUID).count();
        n as Real * self.c.mass * self.c.gravity * floor_z
    }

    /// The energy monitor's baseline: the fluid's energy and its potential energy above the
    /// floor at `floor_z` [J].
    pub fn energy_baseline(&self, floor_z: Real) -> (Real, Real) {
        (self.fluid_energy(), self.fluid_energy() - self.floor_energy_offset(floor_z))
    }

    /// Errors when more fluid particles left the domain (the sweep excludes them, `n_excluded`
    /// so far) than the fraction `limit` of the fluid.
    pub fn check_lost_fraction(&self, n_excluded: usize, limit: Real) -> Result<()> {
        let fs = self.p.fluid_start();
        let allowed = limit * self.p.n_fluid() as Real;
        if n_excluded as Real > allowed {
            let first = (fs..self.p.len())
                .filter(|&i| self.p.kind[i] == KIND_EXCLUDED)
                .min_by_key(|&i| self.p.id[i]);
            return Err(self.instability(
                InstabilityKind::OutOfDomain,
                first,
                format!(
                    "{} of {} fluid particles left the domain (limit {:.2} %)",
                    n_excluded,
                    self.p.n_fluid(),
                    100.0 * limit
                ),
            ));
        }
        Ok(())
    }

    /// Energy monitor for unforced scenes, every [`ENERGY_CHECK_EVERY`] steps: errors when the
    /// fluid's energy exceeds its baseline `energy0` ([`Self::energy_baseline`]) by more than
    /// the fraction `growth_limit` of the initial potential energy above the floor.
    pub fn check_energy(&self, energy0: (Real, Real), growth_limit: Real) -> Result<()> {
        if !self.step.is_multiple_of(ENERGY_CHECK_EVERY) {
            return Ok(());
        }
        let (e0, pot0) = energy0;
        let e = self.fluid_energy();
        let allowed = e0 + growth_limit * pot0.abs().max(Real::MIN_POSITIVE);
        if e > allowed {
            // name the fastest fluid particle (lowest slot on ties)
            let fs = self.p.fluid_start();
            let fastest = (fs..self.p.len())
                .filter(|&i| self.p.kind[i] != KIND_EXCLUDED)
                .fold(None, |best: Option<(Real, usize)>, i| {
                    let v2 = self.p.vel[i].length_squared();
                    match best {
                        Some((b, _)) if !(v2 > b) => best,
                        _ => Some((v2, i)),
                    }
                })
                .map(|(_, i)| i);
            return Err(self.instability(
                InstabilityKind::EnergyGrowth,
                fastest,
                format!(
                    "fluid energy {e:.6e} J exceeds its initial {e0:.6e} J by {:.2} % of the initial potential energy",
                    100.0 * (e - e0) / pot0.abs().max(Real::MIN_POSITIVE)
                ),
            ));
        }
        Ok(())
    }

    /// The error of an instability of `kind` at the particle in `slot` (the first fluid slot
    /// when no particle is to blame).
    pub fn instability(&self, kind: InstabilityKind, slot: Option<usize>, message: String) -> Error {
        let slot = slot.unwrap_or(self.p.fluid_start().min(self.p.len().saturating_sub(1)));
        Error::Instability {
            kind,
            step: self.step,
            time: self.time,
            particle: self.p.id[slot],
            position: self.p.pos[slot].as_slice().to_vec(),
            message,
        }
    }

    /// The NaN or density-band monitor's error for the particle in `slot` ([`find_unstable`]).
    pub fn monitor_error(&self, slot: usize, kind: InstabilityKind) -> Error {
        let (lo, hi) = self.c.density_limits();
        let message = match kind {
            InstabilityKind::NonFinite => "position, velocity or density is not finite".to_string(),
            _ => format!(
                "density {:.3} kg/m^3 outside [{lo:.3}, {hi:.3}] (rho0 -+ {:.2} %)",
                self.p.rho[slot],
                self.c.density_band * 100.0
            ),
        };
        self.instability(kind, Some(slot), message)
    }
}

/// The NaN/inf and density-band monitor over a run of slots: the bad slot of lowest id, as
/// `(id, index in the run, kind)`. A branch-free test of the whole run first, which vectorises;
/// only a run that fails it is searched slot by slot.
pub(crate) fn find_unstable<V: Vector>(pos: &[V], vel: &[V], rho: &[Real], ids: &[u32], (lo, hi): (Real, Real)) -> Option<(u32, usize, InstabilityKind)> {
    // NaN fails both density compares
    let in_band = |r: Real| (r >= lo) & (r <= hi);
    let ok = pos.iter().zip(vel).zip(rho).fold(true, |ok, ((x, v), &r)| ok & x.is_finite() & v.is_finite() & in_band(r));
    if ok {
        return None;
    }
    (0..pos.len())
        .filter_map(|j| {
            let finite = pos[j].is_finite() && vel[j].is_finite() && rho[j].is_finite();
            if !finite {
                Some((ids[j], j, InstabilityKind::NonFinite))
            } else if !in_band(rho[j]) {
                Some((ids[j], j, InstabilityKind::DensityOutOfRange))
            } else {
                None
            }
        })
        .min_by_key(|&(id, _, _)| id)
}
