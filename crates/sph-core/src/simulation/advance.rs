//! The integrator's pass over the particles: one parallel sweep that advances densities,
//! positions and velocities, and on a step's last sweep also shifts, damps, runs the NaN and
//! density monitor and excludes what left the domain.
//!
//! Every one of those is a per-particle update. As separate parallel loops over all particles
//! (two of the integrator, the monitor, the exclusion) they read each particle's state up to
//! four times from L3, and on two threads each loop was a fork-join that woke the second
//! thread: the 2D dam break spent some 200-250 us per step in them on two threads, no less than
//! on one (phase timers, measured in eb24c1d). Here each task takes one chunk through all of them
//! while it is in the core's L2 cache. The result is the same as the separate
//! loops' bit for bit: each particle's arithmetic is unchanged, and the monitor reports the
//! lowest bad id whichever chunk holds it.

use super::{ShiftState, Solver};
use crate::diagnostics::find_unstable;
use crate::error::InstabilityKind;
use crate::kernel::Kernel;
use crate::math::{Dim, Real, Vector};
use crate::particles::{KIND_EXCLUDED, KIND_FLUID};
use crate::scene::{Damping, ShiftingModel};
use crate::threads::{for_each_chunk, Chunks};

/// How a particle's density and motion advance in a sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Rule {
    /// Verlet (Monaghan 1989; DualSPHysics' form): `x += v dt + a dt^2 / 2`, and the velocity and
    /// density from the values one step back over `2 dt`, or by Euler over `dt` on a restart.
    Verlet { euler: bool },
    /// Symplectic predictor (Leimkuhler & Patrick; DualSPHysics' form): a half step from the
    /// start of the step, which the sweep first saves as the history.
    Predictor,
    /// Symplectic corrector from the saved start: `v1 = v0 + a dt`, `x1 = x_half + v1 dt / 2`,
    /// `rho1 = rho0 (2 - eps) / (2 + eps)` with `eps = -drho / rho dt`.
    Corrector,
}

/// What a sweep's monitor found.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Findings {
    /// The bad particle with the lowest id: `(id, slot, kind)`.
    pub bad: Option<(u32, usize, InstabilityKind)>,
    /// Fluid particles excluded in this sweep.
    pub newly_excluded: usize,
}

impl Findings {
    fn merge(self, other: Self) -> Self {
        let bad = match (self.bad, other.bad) {
            (Some(a), Some(b)) => Some(if b.0 < a.0 { b } else { a }),
            (a, b) => a.or(b),
        };
        Findings { bad, newly_excluded: self.newly_excluded + other.newly_excluded }
    }
}

/// Slots per task of a sweep: its state (some 100 bytes a slot in 2D) stays in the core's L2
/// cache from one of the chunk's loops to the next.
const SWEEP_CHUNK: usize = 2048;

impl<D: Dim, K: Kernel> Solver<D, K> {
    /// Advances every particle by `rule` over `dt`. With `last` (the step's last sweep) it then
    /// shifts and damps the fluid, tests every slot for NaN and for its density band, and
    /// excludes fluid particles outside the domain; the paddle must already be at the step's end.
    ///
    /// Each task runs the updates as separate tight loops over its chunk, which vectorise: one
    /// loop doing all of them per particle held too many values for the registers and took
    /// twice the time of the separate passes over all particles.
    pub(super) fn sweep(&mut self, rule: Rule, dt: Real, last: bool) -> Findings {
        let fs = self.p.fluid_start();
        let wall_floor = self.walls.integrated_density_floor(&self.c);
        let band = self.c.density_limits();
        let domain = self.domain;
        let shift = if last { self.shift.as_ref() } else { None };
        let damping = if last { self.scene.damping } else { None };
        let p = &mut self.p;
        let (acc, drho, ids) = (&p.acc[..], &p.drho[..], &p.id[..]);
        let (hist_v, hist_r) = self.history.arrays_mut();
        let n = p.pos.len();
        assert!([p.vel.len(), p.rho.len(), p.kind.len(), hist_v.len(), hist_r.len()].iter().all(|&l| l == n), "a swept array's length differs");
        let (pos, vel) = (Chunks::new(&mut p.pos, SWEEP_CHUNK), Chunks::new(&mut p.vel, SWEEP_CHUNK));
        let (rho, kind) = (Chunks::new(&mut p.rho, SWEEP_CHUNK), Chunks::new(&mut p.kind, SWEEP_CHUNK));
        let (hist_v, hist_r) = (Chunks::new(hist_v, SWEEP_CHUNK), Chunks::new(hist_r, SWEEP_CHUNK));
        // each thread keeps about the same slots from one loop to the next (see for_each_chunk)
        for_each_chunk(
            pos.count(),
            Findings::default,
            |c| {
                // SAFETY: for_each_chunk hands each chunk index to one task
                let (pos, vel, rho, kind, hist_v, hist_r) =
                    unsafe { (pos.get(c), vel.get(c), rho.get(c), kind.get(c), hist_v.get(c), hist_r.get(c)) };
                let start = c * SWEEP_CHUNK;
                let slots = start..start + pos.len();
                if rule == Rule::Predictor {
                    hist_v.copy_from_slice(vel);
                    hist_r.copy_from_slice(rho);
                }
                // the chunk's walls are its slots before `fs`, its fluid the rest
                let walls = fs.clamp(slots.start, slots.end) - start;
                let drho = &drho[slots.clone()];
                if let Some(floor) = wall_floor {
                    advance_density(rule, dt, &mut rho[..walls], &drho[..walls], &mut hist_r[..walls]);
                    rho[..walls].iter_mut().for_each(|r| *r = r.max(floor));
                }
                advance_density(rule, dt, &mut rho[walls..], &drho[walls..], &mut hist_r[walls..]);
                let fluid = slots.start.max(fs) - fs..slots.end.max(fs) - fs;
                let (x, v) = (&mut pos[walls..], &mut vel[walls..]);
                advance_motion(rule, dt, x, v, &acc[fluid.clone()], &mut hist_v[walls..]);
                if let Some(s) = shift {
                    shift_positions::<D>(s, dt, x, v, &s.grad[fluid.clone()], &s.div[fluid]);
                }
                if let Some(d) = damping {
                    damp(d, dt, x, v);
                }
                if !last {
                    return Findings::default();
                }
                Findings {
                    bad: find_unstable(pos, vel, rho, &ids[slots.clone()], band).map(|(id, j, kind)| (id, start + j, kind)),
                    newly_excluded: exclude::<D>(&mut kind[walls..], &mut vel[walls..], &pos[walls..], domain),
                }
            },
            Findings::merge,
        )
    }
}

/// Densities of a run of slots over `dt` (see [`Rule`]); `hist` is the rule's history.
fn advance_density(rule: Rule, dt: Real, rho: &mut [Real], drho: &[Real], hist: &mut [Real]) {
    let it = rho.iter_mut().zip(drho).zip(hist);
    match rule {
        Rule::Verlet { euler: true } => it.for_each(|((r, &d), h)| {
            let next = *r + dt * d;
            *h = *r;
            *r = next;
        }),
        Rule::Verlet { euler: false } => it.for_each(|((r, &d), h)| {
            let next = *h + 2.0 * dt * d;
            *h = *r;
            *r = next;
        }),
        Rule::Predictor => it.for_each(|((r, &d), _)| *r += 0.5 * dt * d),
        Rule::Corrector => it.for_each(|((r, &d), h)| {
            let eps = -d / *r * dt;
            *r = *h * (2.0 - eps) / (2.0 + eps);
        }),
    }
}

/// Positions and velocities of a run of fluid slots over `dt` (see [`Rule`]).
fn advance_motion<V: Vector>(rule: Rule, dt: Real, pos: &mut [V], vel: &mut [V], acc: &[V], hist: &mut [V]) {
    let half = 0.5 * dt;
    let it = pos.iter_mut().zip(vel.iter_mut()).zip(acc).zip(hist);
    match rule {
        Rule::Verlet { euler } => it.for_each(|(((x, v), &a), h)| {
            *x += *v * dt + a * (0.5 * dt * dt);
            let next = if euler { *v + a * dt } else { *h + a * (2.0 * dt) };
            *h = *v;
            *v = next;
        }),
        Rule::Predictor => it.for_each(|(((x, v), &a), _)| {
            *x += *v * half;
            *v += a * half;
        }),
        // x1 = x0 + (v0 + v1) dt/2 = x_half + v1 dt/2: no copy of x0 is kept
        Rule::Corrector => it.for_each(|(((x, v), &a), &mut v0)| {
            let v1 = v0 + a * dt;
            *x += v1 * half;
            *v = v1;
        }),
    }
}

/// Moves each fluid particle by its shift (see [`crate::scene::Shifting`]): `lind`,
/// `-a_fs A h |u| dt grad C` with `u` its velocity at the end of the step; `delta_plus`,
/// `-A h U_max dt s` with `s` its shift direction (`grad`).
fn shift_positions<D: Dim>(s: &ShiftState<D>, dt: Real, pos: &mut [D::V], vel: &[D::V], grad: &[D::V], div: &[Real]) {
    if s.model == ShiftingModel::DeltaPlus {
        let scale = -s.a_h * s.u_max * dt;
        pos.iter_mut().zip(grad).for_each(|(x, &g)| *x += g * scale);
        return;
    }
    let span = D::DIM as Real - s.threshold;
    for (((x, v), &g), &div) in pos.iter_mut().zip(vel).zip(grad).zip(div) {
        let surface = ((div - s.threshold) / span).clamp(0.0, 1.0);
        if surface > 0.0 {
            *x += g * (-surface * s.a_h * v.length() * dt);
        }
    }
}

/// Velocity damping zone (see [`crate::scene::Damping`]).
fn damp<V: Vector>(d: Damping, dt: Real, pos: &[V], vel: &mut [V]) {
    let inv_len = 1.0 / (d.x_end - d.x_start);
    for (v, x) in vel.iter_mut().zip(pos) {
        let s = ((x.get(0) - d.x_start) * inv_len).clamp(0.0, 1.0);
        if s > 0.0 {
            *v = *v * (1.0 - dt * d.strength * s * s).max(0.0);
        }
    }
}

/// Freezes the fluid particles of a run of slots that left the `domain` box; returns how many.
fn exclude<D: Dim>(kind: &mut [u8], vel: &mut [D::V], pos: &[D::V], (lo, hi): (D::V, D::V)) -> usize {
    let mut newly = 0;
    for ((k, v), x) in kind.iter_mut().zip(vel).zip(pos) {
        let inside = (0..D::DIM).all(|a| x.get(a) >= lo.get(a) && x.get(a) <= hi.get(a));
        if *k == KIND_FLUID && !inside && x.is_finite() {
            *k = KIND_EXCLUDED;
            *v = D::V::ZERO;
            newly += 1;
        }
    }
    newly
}
