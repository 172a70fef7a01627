//! One time step, read top to bottom in `step_once`: active absorption, forces (cell sort,
//! wall model, SPS stress, fluid loop), time step, integration with the paddle moved to the
//! step's end, monitors and gauges.

use rayon::prelude::*;

use super::advance::Rule;
use super::{fields_of, History, Solver};
use crate::boundary::{on_paddle, MovingWalls};
use crate::error::{InstabilityKind, Result};
use crate::kernel::Kernel;
use crate::math::{Dim, Real, Vector};
use crate::motion::{Paddle, PaddlePose};
use crate::neighbours::{GROUP_FLUID, GROUP_MOVING};
use crate::phases::{self, Phase};
use crate::physics::forces::{shifting_fields, sps_stress, Fields, StepLimits};
use crate::physics::delta_plus::delta_plus_fields;
use crate::physics::kgc::correction_matrices;
use crate::scene::{ShiftingModel, Viscosity};

impl<D: Dim, K: Kernel> Solver<D, K> {
    /// Places the paddle particles where the motion law puts them at time `t`, with its velocity.
    pub(super) fn move_boundaries(&mut self, t: Real) {
        let Some(pose) = self.paddle_pose(t) else { return };
        self.paddle_time = t;
        let range = self.p.n_fixed..self.p.fluid_start();
        let (n_fixed, reference) = (self.p.n_fixed as u32, &self.moving_ref);
        let ids = &self.p.id[range.clone()];
        let (pos, vel) = (&mut self.p.pos[range.clone()], &mut self.p.vel[range]);
        pos.par_iter_mut().zip(vel.par_iter_mut()).zip(ids.par_iter()).for_each(|((x, v), &id)| {
            (*x, *v) = on_paddle::<D>(Some(pose), reference[(id - n_fixed) as usize]);
        });
    }

    /// The paddle's pose at time `t` (with active absorption's correction); None without a
    /// paddle.
    fn paddle_pose(&self, t: Real) -> Option<PaddlePose> {
        let paddle = self.scene.paddle.as_ref()?;
        let (hinge, swl) = self.paddle_levels;
        Some(match self.absorber {
            Some(state) => paddle.pose_displaced(t, hinge, swl, state.offset_at(t), state.rate),
            None => paddle.pose(t, hinge, swl),
        })
    }

    /// Records every gauge whose next sample time has come.
    pub(super) fn sample_gauges(&mut self) {
        let mut records = std::mem::take(&mut self.gauges);
        self.probes().sample_due(&self.scene.gauges, &mut records, self.time);
        self.gauges = records;
    }

    /// Sorts the moving groups and computes accelerations and density rates.
    pub fn compute_forces(&mut self) -> StepLimits {
        self.sort_group(GROUP_MOVING);
        self.sort_group(GROUP_FLUID);
        let c = self.c;
        let fs = self.p.fluid_start();
        let mut timer = phases::Timer::start();
        let (paddle, (hinge, swl), paddle_time, reference) = (&self.scene.paddle, self.paddle_levels, self.paddle_time, &self.moving_ref);
        let n_fixed = self.p.n_fixed as u32;
        let moving_acc = |ids: &[u32], out: &mut [D::V]| {
            if let Some(paddle) = paddle {
                paddle_accelerations::<D>(paddle, hinge, swl, paddle_time, ids, n_fixed, reference, out);
            }
        };
        let moving = MovingWalls::<D> { acc: &moving_acc, pose: self.paddle_pose(paddle_time) };
        self.walls.before_forces(&c, &self.kernel, &self.grid, &mut self.p, &moving);
        if matches!(self.scene.viscosity, Viscosity::LaminarSps { .. }) {
            let fields = fields_of(&self.p, &[]);
            sps_stress(&c, &self.kernel, &self.grid, fields, &mut self.tau);
        }
        if let Some(kgc) = self.scene.kernel_correction {
            let fields = fields_of(&self.p, &[]);
            correction_matrices(&c, &self.kernel, &self.grid, fields, kgc.min_eigenvalue, &mut self.kgc);
        }
        if c.pair_f32 {
            self.scratch.split.update(&self.grid, &self.p.pos);
        }
        let split = c.pair_f32.then_some(&self.scratch.split);
        // field by field: `drho` and `acc` are borrowed mutably next to them
        let p = &mut self.p;
        let fields = Fields::<D> { pos: &p.pos, vel: &p.vel, rho: &p.rho, kind: &p.kind, tau: &self.tau, kgc: &self.kgc, fluid_start: fs, split };
        let (drho_walls, drho_fluid) = p.drho.split_at_mut(fs);
        let (kernel, grid, fluid_loop) = (&self.kernel, &self.grid, self.fluid_loop);
        let mut fluid = || fluid_loop(&c, kernel, grid, fields, &mut p.acc, drho_fluid);
        let limits = self.walls.forces(&c, kernel, grid, fields, drho_walls, &mut fluid);
        timer.lap(Phase::Forces);
        limits
    }

    /// Particle shifting's fields from the current (sorted) state; nothing without shifting.
    fn compute_shifting(&mut self) {
        let Some(shift) = &mut self.shift else { return };
        let fields = fields_of(&self.p, &[]);
        let (c, kernel, grid) = (&self.c, &self.kernel, &self.grid);
        match shift.model {
            ShiftingModel::Lind => shifting_fields(c, kernel, grid, fields, &mut shift.grad, &mut shift.div),
            ShiftingModel::DeltaPlus => {
                shift.u_max = delta_plus_fields(c, kernel, grid, fields, &mut shift.grad, &mut shift.normal, &mut shift.div);
            }
        }
    }

    /// Variable time step (Monaghan & Kos 1999; DESIGN.md section 2).
    fn time_step(&self, lim: StepLimits) -> Result<Real> {
        let dt_f = if lim.max_acc > 0.0 { (self.c.h / lim.max_acc).sqrt() } else { Real::INFINITY };
        let dt = self.c.cfl * dt_f.min(lim.min_dt_cv);
        if !dt.is_finite() || dt < self.dt_floor {
            // the particle whose limit set the step (force or viscous/acoustic)
            let slot = if dt_f < lim.min_dt_cv { lim.acc_slot } else { lim.cv_slot };
            let slot = (slot < self.p.len()).then_some(slot);
            let (kind, message) = if dt.is_finite() {
                (InstabilityKind::TimeStepCollapse, format!("time step {dt:.3e} s below the floor {:.3e} s", self.dt_floor))
            } else {
                // NaN from a NaN acceleration or speed; infinite when nothing limits the step
                let why = format!("largest acceleration {:.3e} m/s^2, smallest viscous/acoustic step {:.3e} s", lim.max_acc, lim.min_dt_cv);
                (InstabilityKind::NonFiniteTimeStep, format!("time step {dt} s ({why})"))
            };
            return Err(self.diagnostics().instability(kind, slot, message));
        }
        Ok(dt)
    }

    /// Active absorption: the paddle's correction for the step starting now, from the surface
    /// elevation in front of the paddle (see [`crate::absorption`]). Evaluated on the state at
    /// the step's start, before the paddle moves in it.
    fn absorb(&mut self) {
        let (Some(state), Some(paddle)) = (self.absorber, &self.scene.paddle) else { return };
        let Some(absorption) = &paddle.absorption else { return };
        let (tank, t) = (&self.scene.tank, self.time);
        // the vertical through the face at the still-water level plus the offset, mid-width
        let face = paddle.x + paddle.law.eval(t).0 + state.offset_at(t);
        let mut x = D::V::ZERO;
        for k in 0..D::DIM {
            x.set(k, 0.5 * (tank.min[k] + tank.max[k]));
        }
        x.set(0, face + absorption.probe_offset);
        let surface = self.probes().surface_above(x);
        let eta = surface.is_finite().then(|| surface - self.paddle_levels.1);
        self.absorber = Some(absorption.advance(state, t, eta));
    }

    /// One time step.
    pub(super) fn step_once(&mut self) -> Result<()> {
        self.absorb();
        let (dt, rule) = match self.history {
            History::Symplectic { .. } => {
                let lim = self.compute_forces();
                let dt = self.time_step(lim)?;
                let mut timer = phases::Timer::start();
                self.sweep(Rule::Predictor, dt, false);
                timer.lap(Phase::Sweep);
                // the corrector's forces with the paddle at mid-step
                self.move_boundaries(self.time + 0.5 * dt);
                let _ = self.compute_forces();
                self.compute_shifting();
                (dt, Rule::Corrector)
            }
            History::Verlet { euler_every, .. } => {
                let lim = self.compute_forces();
                let dt = self.time_step(lim)?;
                self.compute_shifting();
                // Euler on the first step (no history yet) and every `euler_every` steps
                (dt, Rule::Verlet { euler: self.steps.is_multiple_of(euler_every as u64) })
            }
        };
        self.dt = dt;
        self.time += dt;
        self.steps += 1;
        // the paddle at the step's end before the sweep's monitor tests its slots
        self.move_boundaries(self.time);
        let mut timer = phases::Timer::start();
        let found = self.sweep(rule, dt, true);
        timer.lap(Phase::Sweep);
        self.n_excluded += found.newly_excluded;
        if let Some((_, slot, kind)) = found.bad {
            return Err(self.diagnostics().monitor_error(slot, kind));
        }
        if found.newly_excluded > 0 {
            self.diagnostics().check_lost_fraction(self.n_excluded, self.scene.lost_fraction_limit)?;
        }
        if self.scene.paddle.is_none() {
            self.diagnostics().check_energy(self.energy0, self.scene.energy_growth_limit)?;
        }
        if !self.gauges.is_empty() {
            self.sample_gauges();
        }
        Ok(())
    }}

/// The accelerations of the paddle particles of the ids `ids` at the pose of time `t` (Adami
/// walls need the wall's acceleration), by a central difference of the motion law's velocities
/// over 2e-5 s. `reference`: rest positions indexed by `id - n_fixed`.
#[allow(clippy::too_many_arguments)]
fn paddle_accelerations<D: Dim>(paddle: &Paddle, hinge: Real, swl: Real, t: Real, ids: &[u32], n_fixed: u32, reference: &[D::V], out: &mut [D::V]) {
    const DT: Real = 1e-5;
    let t0 = (t - DT).max(0.0);
    let (before, after) = (paddle.pose(t0, hinge, swl), paddle.pose(t0 + 2.0 * DT, hinge, swl));
    let up = D::DIM - 1;
    out.par_iter_mut().zip(ids.par_iter()).for_each(|(a, &id)| {
        let r = reference[(id - n_fixed) as usize];
        let (_, u0) = before.apply(r.get(0), r.get(up));
        let (_, u1) = after.apply(r.get(0), r.get(up));
        *a = in_flume_plane::<D>([(u1[0] - u0[0]) / (2.0 * DT), (u1[1] - u0[1]) / (2.0 * DT)]);
    });
}

/// A vector in the flume's x-z plane (the paddle moves in it): `xz[0]` along x, `xz[1]`
/// vertical, zero across the width.
fn in_flume_plane<D: Dim>(xz: [Real; 2]) -> D::V {
    let mut v = D::V::ZERO;
    v.set(0, xz[0]);
    v.set(D::DIM - 1, xz[1]);
    v
}

