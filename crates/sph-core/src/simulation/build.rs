//! Building a solver from a scene: particles sampled and initialised hydrostatically, the grid,
//! the integrator's history, the wall model, the paddle and the gauges.

use super::{History, Scratch, ShiftState, Solver, NEIGHBOUR_REACH};
use crate::absorption::AbsorberState;
use crate::boundary::wall_model;
use crate::error::{Error, Result};
use crate::geometry;
use crate::kernel::Kernel;
use crate::math::{Dim, Real, Vector};
use crate::neighbours::{CellGrid, GROUP_FIXED, GROUP_FLUID, GROUP_MOVING};
use crate::particles::{Particles, KIND_FIXED, KIND_FLUID, KIND_MOVING, PERMUTE_BLOCK};
use crate::physics::eos::density_at_pressure;
use crate::physics::forces::fluid_force_loop;
use crate::physics::split_positions::SplitPositions;
use crate::physics::Constants;
use crate::probes::{GaugeRecord, GaugeSpec};
use crate::scene::{Integrator, Scene, ShiftingModel, Viscosity};

impl<D: Dim, K: Kernel> Solver<D, K> {
    pub fn new(scene: Scene) -> Result<Self> {
        scene.validate()?;
        let c = Constants::new(&scene);
        // A step this small means the flow has blown up: 1e-6 of the initial acoustic step.
        let dt_floor = 1e-6 * c.h / c.c0;
        check_gauge_intervals(&scene.gauges, dt_floor)?;
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
        let tau = if matches!(scene.viscosity, Viscosity::LaminarSps { .. }) { vec![D::Sym::default(); n_fluid] } else { Vec::new() };
        let kgc = if scene.kernel_correction.is_some() { vec![D::Sym::default(); n_fluid] } else { Vec::new() };
        let shift = scene.shifting.map(|sh| ShiftState {
            model: sh.model,
            u_max: 0.0,
            a_h: sh.coefficient * c.h,
            threshold: sh.threshold(D::DIM),
            grad: vec![D::V::ZERO; n_fluid],
            div: vec![0.0; n_fluid],
            normal: if sh.model == ShiftingModel::DeltaPlus { vec![D::V::ZERO; n_fluid] } else { Vec::new() },
        });
        // the sort gathers through the fluid accelerations where they hold n values of 8 bytes
        let gather = if n_fluid * D::DIM >= n { Vec::new() } else { vec![0u64; n] };
        let blocks = n.div_ceil(PERMUTE_BLOCK);
        let scratch = Scratch { perm: vec![0; n], gather, ranks: vec![0; blocks], moved: Vec::with_capacity(blocks), split: SplitPositions::default() };
        let walls = wall_model::<D, K>(scene.boundary, if scene.paddle.is_some() { n_moving } else { 0 });
        let fluid_loop = fluid_force_loop::<D, K>(&scene.viscosity, &scene.diffusion, scene.riemann.as_ref(), scene.kernel_correction.is_some());
        let mut solver = Self {
            scene,
            c,
            kernel,
            fluid_loop,
            p,
            grid,
            history,
            tau,
            kgc,
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
            wall_body: Vec::new(),
            domain: (lo, hi),
            n_excluded: 0,
            energy0: (0.0, 0.0),
            stop: Default::default(),
            snapshots: Default::default(),
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
        for (i, (spec, rec)) in solver.scene.gauges.iter().zip(&mut solver.gauges).enumerate() {
            if let GaugeSpec::Pressure { on_wall: true, .. } = spec {
                rec.points = geometry::wall_sensor_points::<D>(&solver.scene, &format!("gauges[{i}]"), &rec.points)?;
            }
        }
        solver.move_boundaries(0.0);
        // Fixed walls never move: sort them once.
        solver.sort_group(GROUP_FIXED);
        solver.grid.forget_slot_cells(GROUP_FIXED);
        solver.walls.prepare(&solver.scene, &solver.p, &solver.moving_ref)?;
        if solver.scene.gauges.iter().any(|g| matches!(g, GaugeSpec::Force { .. })) {
            solver.wall_body = geometry::wall_bodies::<D>(&solver.scene, &solver.p.pos[..n_fixed])?;
        }
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

}

/// Refuses a gauge interval below the time step floor `dt_floor`. A gauge samples at most once
/// per step and no step is shorter than the floor (below it the run stops as unstable), so a
/// shorter interval asks for nothing more; and it bounds the gauges' catch-up of their next
/// sample time (`ProbeView::sample_due`) to `dt / dt_floor` additions a step, where an interval
/// below the resolution of t (1e-20) would never reach the present.
fn check_gauge_intervals(gauges: &[GaugeSpec], dt_floor: Real) -> Result<()> {
    for (i, g) in gauges.iter().enumerate() {
        let interval = g.interval();
        if interval < dt_floor {
            return Err(Error::invalid(
                format!("gauges[{i}].interval"),
                format!(
                    "{interval:e} s is below the time step floor {dt_floor:.3e} s (1e-6 h/c0; a gauge samples at most once a step)"
                ),
            ));
        }
    }
    Ok(())
}
