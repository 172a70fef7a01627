//! Dynamic boundary condition (Crespo et al. 2007; see [`crate::scene::Boundary::Dbc`]): wall
//! particles integrate continuity from their fluid neighbours, and the integrator keeps their
//! densities at or above `rho0`, so that a wall never sucks fluid in (DualSPHysics).

use rayon::prelude::*;

use super::{FluidForces, MovingWalls, WallModel};
use crate::kernel::Kernel;
use crate::math::{Dim, Real, Vector};
use crate::neighbours::{CellGrid, GROUP_FLUID};
use crate::particles::Particles;
use crate::physics::forces::{for_each_pair, Fields, StepLimits};
use crate::physics::{Constants, NEIGHBOUR_TASK};

pub(super) struct Dbc;

impl<D: Dim, K: Kernel> WallModel<D, K> for Dbc {
    fn name(&self) -> &'static str {
        "dbc"
    }

    fn before_forces(&mut self, _: &Constants, _: &K, _: &CellGrid<D>, _: &mut Particles<D>, _: &MovingWalls<'_, D>) {}

    fn forces(&self, c: &Constants, kernel: &K, grid: &CellGrid<D>, fields: Fields<'_, D>, drho_walls: &mut [Real], fluid: FluidForces<'_>) -> StepLimits {
        // The walls' continuity and the fluid's forces read the same fields and write apart:
        // one fork-join for both, so that the threads wait for each other once, not twice
        // (a thread the host stalls holds up every join; docs/benchmarks.md). The fluid's loop
        // runs first on this thread and the walls' waits for the other: the walls first on
        // both held the second thread's start of the fluid's loop back by the walls' whole time.
        rayon::join(fluid, || boundary_density_rate(c, kernel, grid, fields, drho_walls)).0
    }

    fn integrated_density_floor(&self, c: &Constants) -> Option<Real> {
        Some(c.rho0)
    }
}

/// Continuity for wall particles (dynamic boundary condition, Crespo et al. 2007): walls gather
/// `drho_a/dt = sum_b m v_ab.grad_a W_ab` over fluid neighbours only.
pub fn boundary_density_rate<D: Dim, K: Kernel>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: Fields<'_, D>,
    drho: &mut [Real],
) {
    let support2 = c.support * c.support;
    drho.par_iter_mut().enumerate().with_max_len(NEIGHBOUR_TASK).for_each(|(a, drho_a)| {
        let (pa, va) = (f.pos[a], f.vel[a]);
        let mut sum = 0.0;
        for_each_pair(grid, support2, GROUP_FLUID, f.pos, pa, |b, r, _, dist| {
            let fk = kernel.grad_factor(dist);
            sum += c.mass * (va - f.vel[b]).dot(r * fk);
        });
        *drho_a = sum;
    });
}
