//! Consistent copies of the state for readers on other threads while the solver steps.
//!
//! The solver owns its particle arrays and writes them during a step; a reader on another
//! thread cannot look at them then (the binding's NumPy views alias them). Instead it asks
//! through a [`SnapshotExchange`]: the stepping thread answers between two steps, where the
//! state is whole, with a [`Snapshot`] (copies of every array and the scalars that go with
//! them). The request costs the step loop one relaxed atomic load a step while nobody asks.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::Duration;

use crate::math::Real;

/// Copies of the state at one instant between two steps (storage order, as the views).
#[derive(Clone, Debug, PartialEq)]
pub struct Snapshot {
    /// Simulated time [s].
    pub time: Real,
    pub steps: u64,
    /// Last time step [s].
    pub dt: Real,
    /// Flattened `(N, dim)` positions [m].
    pub positions: Vec<Real>,
    /// Flattened `(N, dim)` velocities [m/s].
    pub velocities: Vec<Real>,
    /// Densities [kg/m^3].
    pub densities: Vec<Real>,
    pub kinds: Vec<u8>,
    pub ids: Vec<u32>,
    pub n_excluded: usize,
}

/// Where readers ask the stepping thread for a [`Snapshot`] and wait for it.
#[derive(Debug, Default)]
pub struct SnapshotExchange {
    /// Set by a reader, cleared by the stepping thread when it has answered.
    requested: AtomicBool,
    answer: Mutex<Option<Snapshot>>,
    answered: Condvar,
}

impl SnapshotExchange {
    /// Called by the stepping thread between two steps: when a reader asks, `take` makes the
    /// copy and the readers are woken.
    #[inline]
    pub fn serve(&self, take: impl FnOnce() -> Snapshot) {
        if !self.requested.load(Ordering::Relaxed) {
            return;
        }
        let snapshot = take();
        let mut answer = self.answer.lock().unwrap_or_else(|e| e.into_inner());
        *answer = Some(snapshot);
        self.requested.store(false, Ordering::Relaxed);
        self.answered.notify_all();
    }

    /// Asks the stepping thread for a snapshot and waits up to `wait` for it; `None` if it did
    /// not answer in time (it was between two calls, or its step is longer): the caller then
    /// reads the state itself if it can, or asks again.
    pub fn request(&self, wait: Duration) -> Option<Snapshot> {
        let mut answer = self.answer.lock().unwrap_or_else(|e| e.into_inner());
        // an answer nobody took (its reader had given up) is older than what is asked for now
        *answer = None;
        self.requested.store(true, Ordering::Relaxed);
        let (mut answer, _) = self
            .answered
            .wait_timeout_while(answer, wait, |a| a.is_none())
            .unwrap_or_else(|e| e.into_inner());
        answer.take()
    }
}
