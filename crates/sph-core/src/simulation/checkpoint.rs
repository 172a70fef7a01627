//! Checkpoint and restore: everything needed to continue a run bit for bit.

use super::{flat, History, Solver};
use crate::absorption::AbsorberState;
use crate::error::{Error, Result};
use crate::kernel::Kernel;
use crate::math::{Dim, Real};
use crate::neighbours::{GROUP_FIXED, GROUP_FLUID, GROUP_MOVING};
use crate::particles::{KIND_EXCLUDED, KIND_FIXED, KIND_FLUID, KIND_MOVING};
use crate::probes::GaugeRecord;

/// Everything needed to continue a run exactly: the state in storage order, the integrator's
/// history, the monitors' baselines and the gauge records. The motion law needs no state of its
/// own: it is a function of time.
#[derive(Clone, Debug, Default)]
pub struct Checkpoint {
    pub time: Real,
    pub steps: u64,
    pub dt: Real,
    /// Flattened `(N, dim)`.
    pub positions: Vec<Real>,
    pub velocities: Vec<Real>,
    pub densities: Vec<Real>,
    pub ids: Vec<u32>,
    pub kinds: Vec<u8>,
    /// Verlet only: velocities and densities one step back (empty for Symplectic).
    pub velocities_prev: Vec<Real>,
    pub densities_prev: Vec<Real>,
    pub n_excluded: usize,
    pub energy0: (Real, Real),
    pub gauges: Vec<GaugeRecord>,
    /// Active absorption's correction `(offset, rate, since, lagged, mean)`; None without
    /// absorption.
    pub paddle_correction: Option<(Real, Real, Real, Real, Real)>,
}


impl<D: Dim, K: Kernel> Solver<D, K> {
    /// The state to continue this run from ([`Checkpoint`]).
    pub(super) fn checkpoint_state(&self) -> Checkpoint {
        let (velocities_prev, densities_prev) = match &self.history {
            History::Verlet { vel_prev, rho_prev, .. } => (flat(vel_prev).to_vec(), rho_prev.clone()),
            History::Symplectic { .. } => (Vec::new(), Vec::new()),
        };
        Checkpoint {
            time: self.time,
            steps: self.steps,
            dt: self.dt,
            positions: flat(&self.p.pos).to_vec(),
            velocities: flat(&self.p.vel).to_vec(),
            densities: self.p.rho.clone(),
            ids: self.p.id.clone(),
            kinds: self.p.kind.clone(),
            velocities_prev,
            densities_prev,
            n_excluded: self.n_excluded,
            energy0: self.energy0,
            gauges: self.gauges.clone(),
            paddle_correction: self.absorber.map(|a| (a.offset, a.rate, a.since, a.lagged, a.mean)),
        }
    }
    /// Continues from a checkpoint of a run of the same scene.
    pub(super) fn restore_state(&mut self, c: &Checkpoint) -> Result<()> {
        let n = self.p.len();
        let nd = n * D::DIM;
        let expect = |field: &str, len: usize, want: usize| -> Result<()> {
            if len == want {
                Ok(())
            } else {
                Err(Error::invalid(
                    format!("checkpoint.{field}"),
                    format!("has {len} values, this scene needs {want}: the checkpoint is from another scene"),
                ))
            }
        };
        expect("positions", c.positions.len(), nd)?;
        expect("velocities", c.velocities.len(), nd)?;
        expect("densities", c.densities.len(), n)?;
        expect("ids", c.ids.len(), n)?;
        expect("kinds", c.kinds.len(), n)?;
        expect("gauges", c.gauges.len(), self.gauges.len())?;
        check_values(c, &self.gauges)?;
        for (i, g) in c.gauges.iter().enumerate() {
            let past = &g.crossings.past;
            if !past.is_empty() && (past.len() != n || past.iter().any(|&s| s > 1)) {
                return Err(Error::invalid(format!("checkpoint.gauges[{i}].crossings"), format!("{} sides for {n} particles, each 0 or 1", past.len())));
            }
        }
        match (self.absorber.is_some(), c.paddle_correction.is_some()) {
            (true, false) => return Err(Error::invalid("checkpoint.paddle_correction", "missing: this scene's paddle absorbs waves")),
            (false, true) => {
                return Err(Error::invalid("checkpoint.paddle_correction", "this scene's paddle does not absorb waves: the checkpoint is from another scene"));
            }
            _ => {}
        }
        check_groups(c, self.p.n_fixed, self.p.fluid_start())?;
        if let History::Verlet { vel_prev, rho_prev, .. } = &mut self.history {
            expect("velocities_prev", c.velocities_prev.len(), nd)?;
            expect("densities_prev", c.densities_prev.len(), n)?;
            bytemuck::cast_slice_mut::<D::V, Real>(vel_prev).copy_from_slice(&c.velocities_prev);
            rho_prev.copy_from_slice(&c.densities_prev);
        }
        bytemuck::cast_slice_mut::<D::V, Real>(&mut self.p.pos).copy_from_slice(&c.positions);
        bytemuck::cast_slice_mut::<D::V, Real>(&mut self.p.vel).copy_from_slice(&c.velocities);
        self.p.rho.copy_from_slice(&c.densities);
        self.p.id.copy_from_slice(&c.ids);
        self.p.kind.copy_from_slice(&c.kinds);
        self.time = c.time;
        // a checkpoint is taken between steps, where the paddle stands at its pose of `time`
        self.paddle_time = c.time;
        self.steps = c.steps;
        self.dt = c.dt;
        self.n_excluded = c.n_excluded;
        self.energy0 = c.energy0;
        self.gauges = c.gauges.clone();
        if let (Some(state), Some((offset, rate, since, lagged, mean))) = (&mut self.absorber, c.paddle_correction) {
            *state = AbsorberState { offset, rate, since, lagged, mean };
        }
        // The saved order is already sorted: the stable sort keeps it and rebuilds the cells.
        self.sort_group(GROUP_FIXED);
        self.grid.forget_slot_cells(GROUP_FIXED);
        self.sort_group(GROUP_MOVING);
        self.sort_group(GROUP_FLUID);
        Ok(())
    }
}

/// The checkpoint's scalars and gauge records: a time, step, energy baseline and gauge sample
/// times a run can have reached (a NaN time would never end `run_until`, a non-finite
/// `next_time` would never let its gauge's catch-up finish), and as many values as times.
fn check_values(c: &Checkpoint, gauges: &[GaugeRecord]) -> Result<()> {
    let field = |name: &str| format!("checkpoint.{name}");
    if !(c.time.is_finite() && c.time >= 0.0) {
        return Err(Error::invalid(field("time"), format!("must be finite and >= 0, got {}", c.time)));
    }
    if !(c.dt.is_finite() && c.dt >= 0.0) {
        return Err(Error::invalid(field("dt"), format!("must be finite and >= 0, got {}", c.dt)));
    }
    if !(c.energy0.0.is_finite() && c.energy0.1.is_finite()) {
        return Err(Error::invalid(field("energy0"), format!("must be finite, got {:?}", c.energy0)));
    }
    if let Some(p) = c.paddle_correction {
        if ![p.0, p.1, p.2, p.3, p.4].iter().all(|x| x.is_finite()) {
            return Err(Error::invalid(field("paddle_correction"), format!("must be finite, got {p:?}")));
        }
    }
    for (i, (rec, own)) in c.gauges.iter().zip(gauges).enumerate() {
        let f = |name: &str| field(&format!("gauges[{i}].{name}"));
        if !rec.next_time.is_finite() {
            return Err(Error::invalid(f("next_time"), format!("must be finite, got {}", rec.next_time)));
        }
        if let Some(t) = rec.t.iter().find(|t| !t.is_finite()) {
            return Err(Error::invalid(f("t"), format!("sample times must be finite, got {t}")));
        }
        if rec.values.len() != rec.t.len() * own.width {
            return Err(Error::invalid(
                f("values"),
                format!("has {} values for {} samples of {} values each", rec.values.len(), rec.t.len(), own.width),
            ));
        }
    }
    Ok(())
}

/// The checkpoint's ids and kinds against the scene's groups (`n_fixed` fixed wall slots, then
/// the paddle's up to `fluid_start`, then the fluid): the ids a permutation that keeps every
/// particle in its group, each slot of its group's kind (fluid or excluded in the fluid), and
/// the excluded count that of the excluded kinds.
fn check_groups(c: &Checkpoint, n_fixed: usize, fluid_start: usize) -> Result<()> {
    let n = c.ids.len();
    let group_of = |i: usize| if i < n_fixed { 0 } else if i < fluid_start { 1 } else { 2 };
    let mut seen = vec![false; n];
    for (slot, &id) in c.ids.iter().enumerate() {
        let id = id as usize;
        if id >= n || group_of(id) != group_of(slot) {
            return Err(Error::invalid("checkpoint.ids", format!("slot {slot} holds id {id} of another group")));
        }
        if std::mem::replace(&mut seen[id], true) {
            return Err(Error::invalid("checkpoint.ids", format!("id {id} appears twice")));
        }
    }
    let mut excluded = 0;
    for (slot, &kind) in c.kinds.iter().enumerate() {
        let allowed = match group_of(slot) {
            0 => kind == KIND_FIXED,
            1 => kind == KIND_MOVING,
            _ => kind == KIND_FLUID || kind == KIND_EXCLUDED,
        };
        if !allowed {
            return Err(Error::invalid("checkpoint.kinds", format!("slot {slot} has kind {kind}, not one of its group's")));
        }
        excluded += (kind == KIND_EXCLUDED) as usize;
    }
    if c.n_excluded != excluded {
        return Err(Error::invalid(
            "checkpoint.n_excluded",
            format!("is {}, but {excluded} particles are marked excluded", c.n_excluded),
        ));
    }
    Ok(())
}
