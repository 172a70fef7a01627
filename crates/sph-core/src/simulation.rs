//! The solver: a scene's particles advanced in time, one monomorphised step per combination of
//! dimension, kernel, viscosity model and density diffusion.
//!
//! One step reads top to bottom in [`Solver::step_once`]: sort by cell, equation of state,
//! (SPS stress), forces, time step, integration, monitors.

use rayon::prelude::*;

mod advance;
use advance::Rule;

use crate::diagnostics::Diagnostics;
use crate::error::{Error, InstabilityKind, Result};
use crate::geometry;
use crate::kernel::Kernel;
use crate::math::{Dim, Real, Vector};
use crate::neighbours::{CellGrid, GROUP_FIXED, GROUP_FLUID, GROUP_MOVING};
use crate::absorption::AbsorberState;
use crate::boundary::{wall_model, WallModel};
use crate::motion::{Paddle, PaddlePose};
use crate::phases::{self, Phase};
use crate::particles::{mark_moved_blocks, permute_carried, Carried, Particles, PERMUTE_BLOCK, KIND_EXCLUDED, KIND_FIXED, KIND_FLUID, KIND_MOVING};
use crate::probes::{GaugeRecord, ProbeView};
use crate::threads::with_workers_polling;
use crate::physics::eos::{density_at_pressure, pressure};
use crate::physics::forces::{fluid_forces, shifting_fields, sps_stress, Fields, StepLimits};
use crate::physics::{Constants, VISC_LAMINAR_SPS};
use crate::scene::{Integrator, Scene};

/// Cells of half the kernel support: fewer candidate pairs than `2h` cells (see `neighbours.rs`).
const NEIGHBOUR_REACH: usize = 2;

/// Derived parameters of a run, for reports.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Params {
    pub dim: usize,
    pub dp: Real,
    pub h: Real,
    pub support: Real,
    pub cell_size: Real,
    pub n_cells: usize,
    pub mass: Real,
    pub rho0: Real,
    pub c0: Real,
    pub b_tait: Real,
    pub gamma: Real,
    pub boundary_layers: usize,
    pub kernel: &'static str,
    pub viscosity: &'static str,
    pub diffusion: &'static str,
    pub integrator: &'static str,
    /// Wall boundary model: "dbc" or "adami".
    pub boundary: &'static str,
    /// Particle shifting's coefficient `A` (none without shifting).
    pub shifting: Option<Real>,
    /// Arithmetic of the force loop's pair terms: "f64" or "f32".
    pub force_precision: &'static str,
    /// Smallest time step allowed before the run is declared unstable [s].
    pub dt_floor: Real,
}

/// Shepard-normalised SPH interpolation at a set of points (DESIGN.md section 4).
#[derive(Clone, Debug, Default)]
pub struct Interpolated {
    /// `sum_b V_b W` (about 1 inside the fluid, 0 far outside).
    pub kernel_sum: Vec<Real>,
    pub density: Vec<Real>,
    pub pressure: Vec<Real>,
    /// Flattened `(M, dim)`.
    pub velocity: Vec<Real>,
}

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
    /// Active absorption's correction `(offset, rate, since)`; None without absorption.
    pub paddle_correction: Option<(Real, Real, Real)>,
}

/// The object-safe face of a solver, whatever its compile-time options.
pub trait Simulation: Send + Sync {
    fn dim(&self) -> usize;
    fn time(&self) -> Real;
    fn steps(&self) -> u64;
    /// Last time step taken [s] (0 before the first step).
    fn dt(&self) -> Real;
    fn n_particles(&self) -> usize;
    fn n_fluid(&self) -> usize;
    /// Advances `n` steps.
    fn step(&mut self, n: u64) -> Result<()>;
    /// Advances until `time >= until` (the last step is not shortened).
    fn run_until(&mut self, until: Real) -> Result<()>;
    /// Flattened `(N, dim)` positions in storage order.
    fn positions(&self) -> &[Real];
    fn velocities(&self) -> &[Real];
    fn densities(&self) -> &[Real];
    /// Pressures from the equation of state, computed from the densities (not stored).
    fn pressures(&self) -> Vec<Real>;
    fn kinds(&self) -> &[u8];
    fn ids(&self) -> &[u32];
    /// Bytes of the solver's own arrays (particles, integrator history, grid, optional fields).
    fn memory_bytes(&self) -> usize;
    /// See [`Solver::fluid_pair_count`].
    fn fluid_pairs(&self) -> u64;
    /// See [`Solver::force_evaluations_per_step`].
    fn force_evaluations_per_step(&self) -> u32;
    fn params(&self) -> Params;
    /// Interpolates fluid fields at flattened `(M, dim)` points.
    fn interpolate(&self, points: &[Real]) -> Result<Interpolated>;
    /// Gauge records, in the scene's order.
    fn gauges(&self) -> &[GaugeRecord];
    /// Fluid particles excluded after leaving the domain.
    fn n_excluded(&self) -> usize;
    fn checkpoint(&self) -> Checkpoint;
    /// Continues from a checkpoint of a run of the same scene.
    fn restore(&mut self, checkpoint: &Checkpoint) -> Result<()>;
}

/// Integrator history.
#[derive(Debug, Clone)]
enum History<D: Dim> {
    /// Velocities and densities at the start of the step (the corrector advances positions
    /// from the predictor's half step, so no copy of them is needed).
    Symplectic { vel0: Vec<D::V>, rho0: Vec<Real> },
    /// Velocities and densities one step back, and the step counter for the Euler restart.
    Verlet { vel_prev: Vec<D::V>, rho_prev: Vec<Real>, euler_every: u32 },
}

impl<D: Dim> History<D> {
    /// The history's velocity and density arrays, whichever the scheme.
    fn arrays_mut(&mut self) -> (&mut Vec<D::V>, &mut Vec<Real>) {
        match self {
            History::Symplectic { vel0, rho0 } => (vel0, rho0),
            History::Verlet { vel_prev, rho_prev, .. } => (vel_prev, rho_prev),
        }
    }
}

/// Particle shifting's per-fluid-particle fields (see [`crate::scene::Shifting`]), computed
/// after the step's last force evaluation (no cell sort comes between them and their use).
#[derive(Debug, Clone)]
struct ShiftState<D: Dim> {
    /// `A h` of Skillen et al.'s `D = A h |u| dt`.
    a_h: Real,
    /// Free-surface threshold of the particle divergence (the bulk's is `dim`).
    threshold: Real,
    grad: Vec<D::V>,
    div: Vec<Real>,
}

#[derive(Debug, Clone, Default)]
struct Scratch {
    perm: Vec<u32>,
    /// One entry per [`PERMUTE_BLOCK`] slots: the block's rank among those the last sort moved
    /// a particle in, or `NOT_MOVED` (see `mark_moved_blocks`).
    ranks: Vec<u32>,
    /// The blocks the last sort moved a particle in.
    moved: Vec<u32>,
    /// Gather buffer of `permute_carried`, shared by all arrays (see there). Empty when the fluid
    /// accelerations are large enough to serve instead (`Solver::sort_group`).
    gather: Vec<u64>,
}

pub struct Solver<D: Dim, K: Kernel, const VISC: u8, const DIFF: u8> {
    scene: Scene,
    c: Constants,
    kernel: K,
    p: Particles<D>,
    grid: CellGrid<D>,
    history: History<D>,
    /// SPS stress per fluid particle; empty without the SPS closure.
    tau: Vec<D::Sym>,
    shift: Option<ShiftState<D>>,
    scratch: Scratch,
    time: Real,
    steps: u64,
    dt: Real,
    dt_floor: Real,
    /// Rest positions of the paddle particles, indexed by `id - n_fixed` (ids travel with the
    /// particles through the cell sort, so this array never needs permuting). Empty without a
    /// paddle.
    moving_ref: Vec<D::V>,
    /// Resolved hinge height and still-water level of the paddle.
    paddle_levels: (Real, Real),
    /// Time of the paddle's current pose (the last `move_boundaries`).
    paddle_time: Real,
    /// Active absorption's correction of the paddle's displacement; None without absorption.
    absorber: Option<AbsorberState>,
    /// The wall model, chosen by the scene's `boundary`.
    walls: Box<dyn WallModel<D, K>>,
    gauges: Vec<GaugeRecord>,
    /// Box outside which fluid particles are excluded.
    domain: (D::V, D::V),
    n_excluded: usize,
    /// Initial mechanical energy and potential energy above the floor [J] (energy monitor).
    energy0: (Real, Real),
}

impl<D: Dim, K: Kernel, const VISC: u8, const DIFF: u8> Solver<D, K, VISC, DIFF> {
    pub fn new(scene: Scene) -> Result<Self> {
        scene.validate()?;
        let c = Constants::new(&scene);
        let kernel = K::new(c.h, D::DIM);
        let geometry::Sampled { walls, wall_surface, fluid, fluid_surface, moving, moving_surface } =
            geometry::sample::<D>(&scene)?;
        let n_fixed = walls.len();
        let n_moving = moving.len();
        let n = n_fixed + n_moving + fluid.len();
        let up = D::DIM - 1;

        let hydrostatic = |surface: Real, z: Real| -> Real {
            density_at_pressure(&c, c.rho0 * c.gravity * (surface - z).max(0.0))
        };
        let mut pos = Vec::with_capacity(n);
        let mut rho = Vec::with_capacity(n);
        for (p, s) in walls.iter().zip(&wall_surface).chain(moving.iter().zip(&moving_surface)) {
            pos.push(*p);
            rho.push(s.map_or(c.rho0, |s| hydrostatic(s, p.get(up))));
        }
        for (p, &s) in fluid.iter().zip(&fluid_surface) {
            pos.push(*p);
            rho.push(hydrostatic(s, p.get(up)));
        }
        // The sampled lattice (about 40 bytes a particle) is dead once copied: freed before the
        // other arrays are allocated, building peaks below running (docs/benchmarks.md).
        drop((walls, wall_surface, fluid, fluid_surface, moving_surface));
        let mut kind = vec![KIND_FIXED; n_fixed];
        kind.resize(n_fixed + n_moving, KIND_MOVING);
        kind.resize(n, KIND_FLUID);
        let n_fluid = n - n_fixed - n_moving;
        let p = Particles::<D> {
            pos,
            vel: vec![D::V::ZERO; n],
            rho,
            id: (0..n as u32).collect(),
            kind,
            acc: vec![D::V::ZERO; n_fluid],
            drho: vec![0.0; n],
            n_fixed,
            n_moving,
        };

        // Grid: the tank plus its walls, and as much again above the tank for splashes.
        let layers = scene.layers() as Real * scene.dp;
        let mut lo = D::V::from_slice(&scene.tank.min) - D::V::splat(layers);
        let mut hi = D::V::from_slice(&scene.tank.max) + D::V::splat(layers);
        let height = scene.tank.max[up] - scene.tank.min[up];
        hi.set(up, hi.get(up) + height);
        lo = lo.min(hi);
        let grid = CellGrid::<D>::new(lo, hi, c.support, NEIGHBOUR_REACH);

        let history = match scene.integrator {
            Integrator::Symplectic => History::Symplectic {
                vel0: vec![D::V::ZERO; n],
                rho0: vec![0.0; n],
            },
            Integrator::Verlet { euler_every } => {
                History::Verlet { vel_prev: p.vel.clone(), rho_prev: p.rho.clone(), euler_every }
            }
        };
        let tau = if VISC == VISC_LAMINAR_SPS { vec![D::Sym::default(); n_fluid] } else { Vec::new() };
        let shift = scene.shifting.map(|sh| ShiftState {
            a_h: sh.coefficient * c.h,
            threshold: sh.threshold(D::DIM),
            grad: vec![D::V::ZERO; n_fluid],
            div: vec![0.0; n_fluid],
        });
        // A step this small means the flow has blown up: 1e-6 of the initial acoustic step.
        let dt_floor = 1e-6 * c.h / c.c0;
        // the sort gathers through the fluid accelerations where they hold n values of 8 bytes
        let gather = if n_fluid * D::DIM >= n { Vec::new() } else { vec![0u64; n] };
        let blocks = n.div_ceil(PERMUTE_BLOCK);
        let scratch = Scratch { perm: vec![0; n], gather, ranks: vec![0; blocks], moved: Vec::with_capacity(blocks) };
        let walls = wall_model::<D, K>(scene.boundary, if scene.paddle.is_some() { n_moving } else { 0 });
        let mut solver = Self {
            scene,
            c,
            kernel,
            p,
            grid,
            history,
            tau,
            shift,
            scratch,
            time: 0.0,
            steps: 0,
            dt: 0.0,
            dt_floor,
            moving_ref: moving,
            paddle_levels: (0.0, 0.0),
            paddle_time: 0.0,
            absorber: None,
            walls,
            gauges: Vec::new(),
            domain: (lo, hi),
            n_excluded: 0,
            energy0: (0.0, 0.0),
        };
        solver.energy0 = solver.diagnostics().energy_baseline(solver.scene.tank.min[D::DIM - 1]);
        if let Some(paddle) = &solver.scene.paddle {
            let hinge = paddle.hinge_z.unwrap_or(solver.scene.tank.min[up]);
            let swl = paddle.swl_z.unwrap_or_else(|| solver.scene.still_water_level());
            solver.paddle_levels = (hinge, swl);
            if paddle.absorption.is_some() {
                solver.absorber = Some(AbsorberState::default());
            }
        }
        solver.gauges = solver.scene.gauges.iter().map(|g| GaugeRecord::new(g, D::DIM)).collect();
        solver.move_boundaries(0.0);
        // Fixed walls never move: sort them once.
        solver.sort_group(GROUP_FIXED);
        solver.grid.forget_slot_cells(GROUP_FIXED);
        solver.sort_group(GROUP_MOVING);
        solver.sort_group(GROUP_FLUID);
        // a group without particles needs no cell starts (the groups' sizes never change)
        for g in [GROUP_FIXED, GROUP_MOVING, GROUP_FLUID] {
            if solver.group_range(g).is_empty() {
                solver.grid.release_group(g);
            }
        }
        solver.sample_gauges();
        Ok(solver)
    }

    /// Places the paddle particles where the motion law puts them at time `t`, with its velocity.
    fn move_boundaries(&mut self, t: Real) {
        let Some(paddle) = &self.scene.paddle else { return };
        let (hinge, swl) = self.paddle_levels;
        let pose: PaddlePose = match self.absorber {
            Some(state) => paddle.pose_displaced(t, hinge, swl, state.offset_at(t), state.rate),
            None => paddle.pose(t, hinge, swl),
        };
        self.paddle_time = t;
        let range = self.p.n_fixed..self.p.fluid_start();
        let up = D::DIM - 1;
        let (n_fixed, reference) = (self.p.n_fixed as u32, &self.moving_ref);
        let ids = &self.p.id[range.clone()];
        let (pos, vel) = (&mut self.p.pos[range.clone()], &mut self.p.vel[range]);
        pos.par_iter_mut().zip(vel.par_iter_mut()).zip(ids.par_iter()).for_each(|((x, v), &id)| {
            let r = reference[(id - n_fixed) as usize];
            let (xz, uw) = pose.apply(r.get(0), r.get(up));
            *x = r;
            x.set(0, xz[0]);
            x.set(up, xz[1]);
            *v = in_flume_plane::<D>(uw);
        });
    }


    /// Pairs one fluid force evaluation sums over: each fluid particle that is not excluded with
    /// every other particle, of any group, closer than the support, at the present positions.
    /// The cost of a step is about proportional to it; per particle it depends on how much of a
    /// scene lies within a support of a wall or of the free surface (`watersim bench` reports
    /// the time per pair next to the time per particle). A diagnostic, not for every step: it
    /// sorts a copy of the positions into a copy of the grid (the solver's own grid was sorted
    /// at the last force evaluation, before the positions moved) and holds, while it runs, 9
    /// bytes per particle, a copy of the positions and a copy of the grid (cell starts, and 4
    /// to 6 bytes per particle: the cell of each slot and the movers' scratch).
    pub fn fluid_pair_count(&self) -> u64 {
        let mut grid = self.grid.clone();
        let n = self.p.len();
        let (mut perm, mut keys): (Vec<u32>, _) = ((0..n as u32).collect(), vec![0u32; n]);
        for g in [GROUP_FIXED, GROUP_MOVING, GROUP_FLUID] {
            let range = self.group_range(g);
            if grid.has_group(g) {
                grid.sort_group(g, range.clone(), &self.p.pos, &mut perm[range.clone()], &mut keys);
            }
        }
        let sorted: Vec<D::V> = perm.iter().map(|&i| self.p.pos[i as usize]).collect();
        let kinds: Vec<u8> = perm.iter().map(|&i| self.p.kind[i as usize]).collect();
        let support2 = self.c.support * self.c.support;
        (self.p.fluid_start()..n)
            .into_par_iter()
            .filter(|&a| kinds[a] != KIND_EXCLUDED)
            .map(|a| {
                let x = sorted[a];
                let mut pairs = 0u64;
                for g in [GROUP_FIXED, GROUP_MOVING, GROUP_FLUID] {
                    grid.for_each_near(g, x, |b| pairs += (b != a && (x - sorted[b]).length_squared() < support2) as u64);
                }
                pairs
            })
            .sum()
    }

    /// Fluid force evaluations per time step: two with Symplectic (predictor and corrector),
    /// one with Verlet.
    pub fn force_evaluations_per_step(&self) -> u32 {
        match self.history {
            History::Symplectic { .. } => 2,
            History::Verlet { .. } => 1,
        }
    }

    fn group_range(&self, g: usize) -> std::ops::Range<usize> {
        let (nf, fs) = (self.p.n_fixed, self.p.fluid_start());
        match g {
            GROUP_FIXED => 0..nf,
            GROUP_MOVING => nf..fs,
            _ => fs..self.p.len(),
        }
    }

    /// Sorts one group by cell and carries every per-particle array along.
    fn sort_group(&mut self, g: usize) {
        let range = self.group_range(g);
        if range.is_empty() {
            return;
        }
        let Scratch { perm, gather, ranks, moved } = &mut self.scratch;
        let Particles { pos, vel, rho, id, kind, acc, .. } = &mut self.p;
        // The gather buffer: the fluid accelerations where they are large enough (8 bytes a
        // particle less to hold). They are dead here: every sort comes right before a force
        // evaluation, which overwrites all of them, and nothing reads them in between.
        let gather: &mut [u64] = if gather.is_empty() { bytemuck::cast_slice_mut(acc.as_mut_slice()) } else { gather };
        let perm = &mut perm[..range.len()];
        // the cell keys live in the gather buffer: they are dead before `permute` reuses it
        let keys = bytemuck::cast_slice_mut::<u64, u32>(gather);
        let mut timer = phases::Timer::start();
        self.grid.sort_group(g, range.clone(), pos, perm, keys);
        timer.lap(Phase::SortGrid);
        let perm = &*perm;
        let moved_blocks = mark_moved_blocks(perm, range.start, ranks, moved);
        timer.lap(Phase::SortMark);
        if moved_blocks == 0 {
            return;
        }
        phases::count_moved_blocks(moved_blocks);
        let (hist_v, hist_r) = self.history.arrays_mut();
        let arrays = Carried { vectors: [pos, vel, hist_v], reals: [rho, hist_r], id, kind };
        permute_carried(arrays, range, perm, ranks, moved, gather);
        timer.lap(Phase::SortPermute);
    }

    /// Records every gauge whose next sample time has come.
    fn sample_gauges(&mut self) {
        let mut records = std::mem::take(&mut self.gauges);
        self.probes().sample_due(&self.scene.gauges, &mut records, self.time);
        self.gauges = records;
    }

    /// The gauges' view of the present state.
    fn probes(&self) -> ProbeView<'_, D, K> {
        ProbeView { p: &self.p, grid: &self.grid, kernel: &self.kernel, c: &self.c, tank: &self.scene.tank }
    }

    /// Kinetic plus potential energy of the fluid still in the domain [J].
    pub fn fluid_energy(&self) -> Real {
        self.diagnostics().fluid_energy()
    }

    /// The checks' view of the present state.
    fn diagnostics(&self) -> Diagnostics<'_, D> {
        Diagnostics { p: &self.p, c: &self.c, step: self.steps, time: self.time }
    }

    /// The particle arrays (storage order).
    pub fn particles(&self) -> &Particles<D> {
        &self.p
    }

    /// Mutable particle arrays, for tests and injected perturbations. Do not resize them.
    pub fn particles_mut(&mut self) -> &mut Particles<D> {
        &mut self.p
    }

    pub fn constants(&self) -> &Constants {
        &self.c
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
        self.walls.before_forces(&c, &self.kernel, &self.grid, &mut self.p, &moving_acc);
        if VISC == VISC_LAMINAR_SPS {
            let fields = fields_of(&self.p, &[]);
            sps_stress(&c, &self.kernel, &self.grid, fields, &mut self.tau);
        }
        // field by field: `drho` and `acc` are borrowed mutably next to them
        let p = &mut self.p;
        let fields = Fields::<D> { pos: &p.pos, vel: &p.vel, rho: &p.rho, kind: &p.kind, tau: &self.tau, fluid_start: fs };
        let (drho_walls, drho_fluid) = p.drho.split_at_mut(fs);
        let (kernel, grid) = (&self.kernel, &self.grid);
        let mut fluid = || fluid_forces::<D, K, VISC, DIFF>(&c, kernel, grid, fields, &mut p.acc, drho_fluid);
        let limits = self.walls.forces(&c, kernel, grid, fields, drho_walls, &mut fluid);
        timer.lap(Phase::Forces);
        limits
    }

    /// Particle shifting's fields from the current (sorted) state; nothing without shifting.
    fn compute_shifting(&mut self) {
        let Some(shift) = &mut self.shift else { return };
        let fields = fields_of(&self.p, &[]);
        shifting_fields(&self.c, &self.kernel, &self.grid, fields, &mut shift.grad, &mut shift.div);
    }

    /// Variable time step (Monaghan & Kos 1999; DESIGN.md section 2).
    fn time_step(&self, lim: StepLimits) -> Result<Real> {
        let dt_f = if lim.max_acc > 0.0 { (self.c.h / lim.max_acc).sqrt() } else { Real::INFINITY };
        let dt = self.c.cfl * dt_f.min(lim.min_dt_cv);
        if !dt.is_finite() || dt < self.dt_floor {
            // the particle whose limit set the step (force or viscous/acoustic)
            let slot = if dt_f < lim.min_dt_cv { lim.acc_slot } else { lim.cv_slot };
            let slot = (slot < self.p.len()).then_some(slot);
            return Err(self.diagnostics().instability(
                InstabilityKind::TimeStepCollapse,
                slot,
                format!("time step {dt:e} s below the floor {:e} s", self.dt_floor),
            ));
        }
        Ok(dt)
    }

    /// Active absorption: the paddle's correction for the step starting now, from the surface
    /// elevation in front of the paddle (see [`crate::absorption`]). Evaluated on the state at
    /// the step's start, before the paddle moves in it.
    fn absorb(&mut self) {
        let (Some(state), Some(paddle)) = (self.absorber, &self.scene.paddle) else { return };
        let Some(absorption) = &paddle.absorption else { return };
        let up = D::DIM - 1;
        let (tank, t) = (&self.scene.tank, self.time);
        // the vertical through the face at the still-water level plus the offset, mid-width
        let face = paddle.x + paddle.law.eval(t).0 + state.offset_at(t);
        let mut foot = D::V::ZERO;
        for k in 0..D::DIM {
            foot.set(k, 0.5 * (tank.min[k] + tank.max[k]));
        }
        foot.set(0, face + absorption.probe_offset);
        foot.set(up, tank.min[up]);
        let mut top = foot;
        top.set(up, tank.max[up]);
        let surface = self.probes().last_wet_along(foot, top);
        let eta = surface.is_finite().then(|| surface - self.paddle_levels.1);
        self.absorber = Some(absorption.advance(state, t, eta));
    }

    /// One time step.
    fn step_once(&mut self) -> Result<()> {
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
    }
}

/// Runs `op` on a thread of rayon's pool. A step has some 80 parallel loops; called from
/// outside the pool, each one is a job injected into it that the calling thread sleeps on (a
/// futex wake-up and sleep per loop, about a tenth of a 2D step on two threads). On a pool
/// thread each loop is a fork-join among the workers. Results do not change: how a loop is
/// split depends on the thread count only. The other threads poll for work while `op` runs
/// ([`with_workers_polling`]), so that none falls asleep between two loops of a step.
fn on_pool<R: Send>(op: impl FnOnce() -> R + Send) -> R {
    rayon::scope(|_| with_workers_polling(op))
}

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

/// The read-only fields of a force or shifting pass over the particles `p`.
fn fields_of<'a, D: Dim>(p: &'a Particles<D>, tau: &'a [D::Sym]) -> Fields<'a, D> {
    Fields { pos: &p.pos, vel: &p.vel, rho: &p.rho, kind: &p.kind, tau, fluid_start: p.fluid_start() }
}

fn flat<V: Vector>(v: &[V]) -> &[Real] {
    bytemuck::cast_slice(v)
}

impl<D: Dim, K: Kernel, const VISC: u8, const DIFF: u8> Simulation for Solver<D, K, VISC, DIFF> {
    fn dim(&self) -> usize {
        D::DIM
    }
    fn time(&self) -> Real {
        self.time
    }
    fn steps(&self) -> u64 {
        self.steps
    }
    fn dt(&self) -> Real {
        self.dt
    }
    fn n_particles(&self) -> usize {
        self.p.len()
    }
    fn n_fluid(&self) -> usize {
        self.p.n_fluid()
    }
    fn step(&mut self, n: u64) -> Result<()> {
        on_pool(|| {
            for _ in 0..n {
                let mut timer = phases::Timer::start();
                self.step_once()?;
                timer.lap(Phase::Step);
            }
            Ok(())
        })
    }
    fn run_until(&mut self, until: Real) -> Result<()> {
        if !until.is_finite() {
            return Err(Error::invalid("until", format!("must be finite, got {until}")));
        }
        on_pool(|| {
            while self.time < until {
                self.step_once()?;
            }
            Ok(())
        })
    }
    fn positions(&self) -> &[Real] {
        flat(&self.p.pos)
    }
    fn velocities(&self) -> &[Real] {
        flat(&self.p.vel)
    }
    fn densities(&self) -> &[Real] {
        &self.p.rho
    }
    fn pressures(&self) -> Vec<Real> {
        let fs = self.p.fluid_start();
        let (c, walls) = (&self.c, &self.walls);
        self.p.rho.par_iter().enumerate().map(|(i, &r)| if i < fs { walls.pressure(c, r) } else { pressure(c, r) }).collect()
    }
    fn kinds(&self) -> &[u8] {
        &self.p.kind
    }
    fn ids(&self) -> &[u32] {
        &self.p.id
    }
    fn fluid_pairs(&self) -> u64 {
        self.fluid_pair_count()
    }
    fn force_evaluations_per_step(&self) -> u32 {
        Solver::force_evaluations_per_step(self)
    }
    fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        let v = size_of::<D::V>();
        let r = size_of::<Real>();
        let history = match &self.history {
            History::Symplectic { vel0, rho0 } => vel0.capacity() * v + rho0.capacity() * r,
            History::Verlet { vel_prev, rho_prev, .. } => vel_prev.capacity() * v + rho_prev.capacity() * r,
        };
        let s = &self.scratch;
        let scratch = s.perm.capacity() * 4 + s.gather.capacity() * 8 + (s.ranks.capacity() + s.moved.capacity()) * 4;
        self.p.memory_bytes()
            + history
            + self.tau.capacity() * size_of::<D::Sym>()
            + self.shift.as_ref().map_or(0, |s| s.grad.capacity() * v + s.div.capacity() * r)
            + self.moving_ref.capacity() * v
            + self.walls.memory_bytes()
            + self.grid.memory_bytes()
            + scratch
    }
    fn params(&self) -> Params {
        use crate::scene::{Diffusion, Viscosity};
        let s = &self.scene;
        Params {
            dim: D::DIM,
            dp: self.c.dp,
            h: self.c.h,
            support: self.c.support,
            cell_size: self.c.support / NEIGHBOUR_REACH as Real,
            n_cells: self.grid.n_cells(),
            mass: self.c.mass,
            rho0: self.c.rho0,
            c0: self.c.c0,
            b_tait: self.c.b_tait,
            gamma: self.c.gamma,
            boundary_layers: s.layers(),
            kernel: K::KIND.name(),
            viscosity: match s.viscosity {
                Viscosity::Artificial { .. } => "artificial",
                Viscosity::Laminar { .. } => "laminar",
                Viscosity::LaminarSps { .. } => "laminar_sps",
            },
            diffusion: match s.diffusion {
                Diffusion::None => "none",
                Diffusion::Molteni { .. } => "molteni",
                Diffusion::Fourtakas { .. } => "fourtakas",
            },
            integrator: match s.integrator {
                Integrator::Symplectic => "symplectic",
                Integrator::Verlet { .. } => "verlet",
            },
            force_precision: if self.c.pair_f32 { "f32" } else { "f64" },
            boundary: self.walls.name(),
            shifting: s.shifting.map(|sh| sh.coefficient),
            dt_floor: self.dt_floor,
        }
    }
    fn interpolate(&self, points: &[Real]) -> Result<Interpolated> {
        if !points.len().is_multiple_of(D::DIM) {
            return Err(Error::invalid("points", format!("length {} is not a multiple of dim = {}", points.len(), D::DIM)));
        }
        if let Some(x) = points.iter().find(|x| !x.is_finite()) {
            return Err(Error::invalid("points", format!("coordinates must be finite, got {x}")));
        }
        let m = points.len() / D::DIM;
        let probes = self.probes();
        let rows: Vec<(Real, Real, Real, D::V)> = (0..m)
            .into_par_iter()
            .map(|i| probes.shepard(D::V::from_slice(&points[i * D::DIM..(i + 1) * D::DIM])))
            .collect();
        let mut out = Interpolated::default();
        for (w, rho, pr, v) in rows {
            out.kernel_sum.push(w);
            out.density.push(rho);
            out.pressure.push(pr);
            out.velocity.extend_from_slice(v.as_slice());
        }
        Ok(out)
    }
    fn gauges(&self) -> &[GaugeRecord] {
        &self.gauges
    }
    fn n_excluded(&self) -> usize {
        self.n_excluded
    }
    fn checkpoint(&self) -> Checkpoint {
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
            paddle_correction: self.absorber.map(|a| (a.offset, a.rate, a.since)),
        }
    }
    fn restore(&mut self, c: &Checkpoint) -> Result<()> {
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
        match (self.absorber.is_some(), c.paddle_correction.is_some()) {
            (true, false) => return Err(Error::invalid("checkpoint.paddle_correction", "missing: this scene's paddle absorbs waves")),
            (false, true) => {
                return Err(Error::invalid("checkpoint.paddle_correction", "this scene's paddle does not absorb waves: the checkpoint is from another scene"));
            }
            _ => {}
        }
        // ids must be a permutation that keeps every particle in its group
        let fs = self.p.fluid_start() as u32;
        let nf = self.p.n_fixed as u32;
        for (slot, &id) in c.ids.iter().enumerate() {
            let group_of = |i: u32| if i < nf { 0 } else if i < fs { 1 } else { 2 };
            if id as usize >= n || group_of(id) != group_of(slot as u32) {
                return Err(Error::invalid("checkpoint.ids", format!("slot {slot} holds id {id} of another group")));
            }
        }
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
        if let (Some(state), Some((offset, rate, since))) = (&mut self.absorber, c.paddle_correction) {
            *state = AbsorberState { offset, rate, since };
        }
        // The saved order is already sorted: the stable sort keeps it and rebuilds the cells.
        self.sort_group(GROUP_FIXED);
        self.grid.forget_slot_cells(GROUP_FIXED);
        self.sort_group(GROUP_MOVING);
        self.sort_group(GROUP_FLUID);
        Ok(())
    }
}

#[cfg(test)]
mod batched_loop_tests {
    //! The batched (SIMD) force loop against the pair-at-a-time loop on moving dam breaks: the
    //! same sums in another order, so equal to rounding.
    use super::*;
    use crate::kernel::{CubicSpline, WendlandC2};
    use crate::math::{Dim2, Dim3};
    use crate::physics::batched::{fluid_forces_batched, fluid_forces_variant};
    use crate::physics::forces::fluid_forces_scalar;
    use crate::physics::{DIFF_FOURTAKAS, DIFF_MOLTENI, DIFF_NONE, VISC_ARTIFICIAL, VISC_LAMINAR};

    fn check<D: Dim, K: Kernel, const VISC: u8, const DIFF: u8>(json: &str) {
        let mut s = Solver::<D, K, VISC, DIFF>::new(Scene::from_json(json).expect("scene")).expect("solver");
        s.step(40).expect("stable");
        s.compute_forces();
        let n = s.p.n_fluid();
        let fields = fields_of(&s.p, &[]);
        let (mut acc_s, mut drho_s) = (vec![D::V::ZERO; n], vec![0.0; n]);
        let (mut acc_b, mut drho_b) = (vec![D::V::ZERO; n], vec![0.0; n]);
        let lim_s = fluid_forces_scalar::<D, K, VISC, DIFF>(&s.c, &s.kernel, &s.grid, fields, &mut acc_s, &mut drho_s);
        let lim_b = fluid_forces_batched::<D, K, VISC, DIFF>(&s.c, &s.kernel, &s.grid, fields, &mut acc_b, &mut drho_b);
        let acc_scale = acc_s.iter().map(|a| a.length()).fold(0.0, f64::max);
        let drho_scale = drho_s.iter().map(|d| d.abs()).fold(0.0, f64::max);
        assert!(acc_scale > s.c.gravity && drho_scale > 0.0, "the scene must move");
        for i in 0..n {
            assert!((acc_s[i] - acc_b[i]).length() <= 1e-11 * acc_scale, "acc of fluid particle {i}");
            assert!((drho_s[i] - drho_b[i]).abs() <= 1e-11 * drho_scale, "drho of fluid particle {i}");
        }
        assert!((lim_s.max_acc - lim_b.max_acc).abs() <= 1e-11 * lim_s.max_acc);
        assert!((lim_s.min_dt_cv - lim_b.min_dt_cv).abs() <= 1e-11 * lim_s.min_dt_cv);

        // Pair terms in f32: the same sums to f32's precision. The pressure terms of a pair are
        // about as large as the sum over a particle's neighbours (hydrostatic balance), so the
        // error is a few f32 roundings of the largest force.
        let mut c32 = s.c;
        c32.pair_f32 = true;
        let (mut acc_f, mut drho_f) = (vec![D::V::ZERO; n], vec![0.0; n]);
        let lim_f = fluid_forces_batched::<D, K, VISC, DIFF>(&c32, &s.kernel, &s.grid, fields, &mut acc_f, &mut drho_f);
        let acc_err = (0..n).map(|i| (acc_s[i] - acc_f[i]).length()).fold(0.0, f64::max) / acc_scale;
        let drho_err = (0..n).map(|i| (drho_s[i] - drho_f[i]).abs()).fold(0.0, f64::max) / drho_scale;
        // measured: up to 1.5e-6 (acc) and 9e-7 (drho) of the largest value
        assert!(acc_err < 5e-6 && drho_err < 5e-6, "f32 pair terms: acc error {acc_err:e}, drho error {drho_err:e}");
        assert!((lim_s.max_acc - lim_f.max_acc).abs() <= 5e-6 * lim_s.max_acc);
        assert!((lim_s.min_dt_cv - lim_f.min_dt_cv).abs() <= 5e-6 * lim_s.min_dt_cv);

        // The AVX2 variant (intrinsic candidate scan, wide arithmetic) and the portable one
        // give the same bits.
        if crate::physics::batched::uses_avx2() {
            let (mut acc_p, mut drho_p) = (vec![D::V::ZERO; n], vec![0.0; n]);
            let (mut acc_x, mut drho_x) = (vec![D::V::ZERO; n], vec![0.0; n]);
            let lim_p = fluid_forces_variant::<D, K, VISC, DIFF>(&s.c, &s.kernel, &s.grid, fields, &mut acc_p, &mut drho_p, false);
            let lim_x = fluid_forces_variant::<D, K, VISC, DIFF>(&s.c, &s.kernel, &s.grid, fields, &mut acc_x, &mut drho_x, true);
            assert!(acc_p == acc_x && drho_p == drho_x, "AVX2 and portable variants differ");
            assert!(lim_p.max_acc == lim_x.max_acc && lim_p.min_dt_cv == lim_x.min_dt_cv);
            let (mut acc_p, mut drho_p) = (vec![D::V::ZERO; n], vec![0.0; n]);
            let (mut acc_x, mut drho_x) = (vec![D::V::ZERO; n], vec![0.0; n]);
            fluid_forces_variant::<D, K, VISC, DIFF>(&c32, &s.kernel, &s.grid, fields, &mut acc_p, &mut drho_p, false);
            fluid_forces_variant::<D, K, VISC, DIFF>(&c32, &s.kernel, &s.grid, fields, &mut acc_x, &mut drho_x, true);
            assert!(acc_p == acc_x && drho_p == drho_x, "AVX2 and portable variants differ in f32");
        }
    }

    /// Still water starts hydrostatic, at rest: density diffusion with the hydrostatic part
    /// removed must add nothing, at the free surface and next to the bed as in the bulk.
    /// (Fourtakas' density form, Eq. 13, gives every pair a positive leftover here, of order
    /// 1 kg/m^3/s per particle by the estimate in docs/wave-flume.md, "The mean water level":
    /// still water expanded.)
    #[test]
    fn fourtakas_diffusion_leaves_still_water_alone() {
        // f32 pair terms round each pressure to about 1e-7 of itself; what is left is noise of
        // that order (measured: 5e-5 kg/m^3/s), not Eq. 13's systematic gain
        for (boundary, precision, bound) in [("dbc", "f64", 1e-6), ("adami", "f64", 1e-6), ("dbc", "f32", 1e-3), ("adami", "f32", 1e-3)] {
            let json = format!(
                r#"{{"dim": 2, "dp": 0.0375, "coefsound": 10, "tank": {{"min": [0, 0], "max": [1.5, 0.5]}},
                    "fluid": [{{"min": [0, 0], "max": [1.5, 0.3]}}], "boundary": {{"model": "{boundary}"}},
                    "diffusion": {{"model": "fourtakas", "delta": 0.1}}, "force_precision": "{precision}"}}"#
            );
            let mut s = Solver::<Dim2, WendlandC2, VISC_ARTIFICIAL, DIFF_FOURTAKAS>::new(Scene::from_json(&json).expect("scene"))
                .expect("solver");
            s.compute_forces();
            let fs = s.p.fluid_start();
            let worst = s.p.drho[fs..].iter().fold(0.0 as Real, |m, d| m.max(d.abs()));
            assert!(worst < bound, "{boundary} {precision}: |drho/dt| up to {worst} kg/m^3/s in still water");
        }
    }

    fn dambreak(dim: usize, extra: &str) -> String {
        if dim == 2 {
            format!(
                r#"{{"dim": 2, "dp": 0.02, "tank": {{"min": [0, 0], "max": [1.0, 0.6]}},
                    "fluid": [{{"min": [0, 0], "max": [0.3, 0.4]}}] {extra}}}"#
            )
        } else {
            format!(
                r#"{{"dim": 3, "dp": 0.04, "tank": {{"min": [0, 0, 0], "max": [1.0, 0.3, 0.5]}},
                    "fluid": [{{"min": [0, 0, 0], "max": [0.3, 0.3, 0.4]}}] {extra}}}"#
            )
        }
    }

    #[test]
    fn wendland_artificial_fourtakas_2d_and_3d() {
        let extra = r#", "viscosity": {"model": "artificial", "alpha": 0.1}, "diffusion": {"model": "fourtakas", "delta": 0.1}"#;
        check::<Dim2, WendlandC2, VISC_ARTIFICIAL, DIFF_FOURTAKAS>(&dambreak(2, extra));
        check::<Dim3, WendlandC2, VISC_ARTIFICIAL, DIFF_FOURTAKAS>(&dambreak(3, extra));
    }

    #[test]
    fn cubic_laminar_molteni_and_no_diffusion() {
        let lam = r#", "kernel": "cubic_spline", "viscosity": {"model": "laminar", "nu": 1e-4}, "diffusion": {"model": "molteni", "delta": 0.1}"#;
        check::<Dim2, CubicSpline, VISC_LAMINAR, DIFF_MOLTENI>(&dambreak(2, lam));
        check::<Dim3, CubicSpline, VISC_LAMINAR, DIFF_MOLTENI>(&dambreak(3, lam));
        let none = r#", "kernel": "cubic_spline", "diffusion": {"model": "none"}"#;
        check::<Dim2, CubicSpline, VISC_ARTIFICIAL, DIFF_NONE>(&dambreak(2, none));
    }

    #[test]
    fn the_monitor_names_the_lowest_id_among_bad_particles_in_any_chunk() {
        type S = Solver<Dim2, WendlandC2, VISC_ARTIFICIAL, DIFF_FOURTAKAS>;
        // 2D dam break of dp 0.005: 4,800 fluid particles, three of the sweep's chunks
        let json = r#"{"dim": 2, "dp": 0.005, "tank": {"min": [0, 0], "max": [1.0, 0.6]}, "fluid": [{"min": [0, 0], "max": [0.3, 0.4]}]}"#;
        let mut s = S::new(Scene::from_json(json).expect("scene")).expect("solver");
        // a sweep over no time is the monitor alone: nothing moves, every slot is tested
        let monitor = |s: &mut S| s.sweep(Rule::Verlet { euler: true }, 0.0, true).bad.map(|(id, _, kind)| (kind, id));
        assert_eq!(monitor(&mut s), None);
        let n = s.p.len();
        assert!(n > 2 * 2048, "{n} particles");
        let slot_of = |s: &S, id: u32| s.p.id.iter().position(|&i| i == id).unwrap();
        // a density out of band on the highest id, then a NaN on a lower id in another chunk,
        // then an infinity on the lowest id: the lowest bad id is reported wherever its slot is
        let (lowest, highest) = (s.p.id.iter().copied().min().unwrap(), s.p.id.iter().copied().max().unwrap());
        let high = slot_of(&s, highest);
        s.p.rho[high] = s.c.rho0 * (1.0 + 2.0 * s.c.density_band);
        assert_eq!(monitor(&mut s), Some((InstabilityKind::DensityOutOfRange, highest)));
        let other = if high < n / 2 { n - 10 } else { 10 };
        let id_other = s.p.id[other];
        assert!(id_other != lowest && id_other != highest);
        s.p.pos[other].x = Real::NAN;
        assert_eq!(monitor(&mut s), Some((InstabilityKind::NonFinite, id_other)));
        let low = slot_of(&s, lowest);
        s.p.vel[low].y = Real::INFINITY;
        assert_eq!(monitor(&mut s), Some((InstabilityKind::NonFinite, lowest)));
    }

    /// The pair count against every pair tested, after steps that moved the particles since
    /// the grid's last sort, and the evaluations per step of both integrators.
    #[test]
    fn fluid_pair_count_is_every_pair_within_the_support() {
        for (dim, integrator, evaluations) in [(2, "symplectic", 2), (3, "verlet", 1)] {
            let extra = format!(r#", "integrator": {{"scheme": "{integrator}"}}"#);
            let json = dambreak(dim, &extra);
            let count = |s: &dyn super::Simulation| -> u64 {
                let (pos, kind, d) = (s.positions(), s.kinds(), s.dim());
                let support2 = s.params().support.powi(2);
                let mut pairs = 0;
                for a in (0..kind.len()).filter(|&a| kind[a] == KIND_FLUID) {
                    for b in (0..kind.len()).filter(|&b| b != a) {
                        let r2: Real = (0..d).map(|k| (pos[d * a + k] - pos[d * b + k]).powi(2)).sum();
                        pairs += (r2 < support2) as u64;
                    }
                }
                pairs
            };
            let mut s: Box<dyn super::Simulation> = if dim == 2 {
                Box::new(Solver::<Dim2, WendlandC2, VISC_ARTIFICIAL, DIFF_FOURTAKAS>::new(Scene::from_json(&json).expect("scene")).expect("solver"))
            } else {
                Box::new(Solver::<Dim3, WendlandC2, VISC_ARTIFICIAL, DIFF_FOURTAKAS>::new(Scene::from_json(&json).expect("scene")).expect("solver"))
            };
            assert_eq!(s.fluid_pairs(), count(s.as_ref()));
            s.step(150).expect("stable");
            let moved = s.fluid_pairs();
            assert_eq!(moved, count(s.as_ref()));
            // a full support holds some 20 (2D) to 100 (3D) neighbours; the walls and the surface fewer
            assert!(moved > 5 * s.n_fluid() as u64, "{dim}D: {moved} pairs for {} fluid particles", s.n_fluid());
            assert_eq!(s.force_evaluations_per_step(), evaluations);
        }
    }
}
