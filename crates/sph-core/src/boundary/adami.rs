//! Adami, Hu & Adams (2012) walls (see [`crate::scene::Boundary::Adami`]): before every force
//! evaluation each wall particle takes the pressure extrapolated from its fluid neighbours and
//! the density of that pressure; the integrator leaves wall densities alone.

use rayon::prelude::*;

use super::{FluidForces, MovingWalls, WallModel};
use crate::kernel::Kernel;
use crate::math::{Dim, Real, Vector};
use crate::neighbours::{CellGrid, GROUP_FLUID};
use crate::particles::{Particles, KIND_EXCLUDED};
use crate::physics::eos::{density_at_pressure, pressure};
use crate::physics::forces::{for_each_pair, Fields, StepLimits};
use crate::physics::{Constants, NEIGHBOUR_TASK};

pub(super) struct Adami<D: Dim> {
    /// Accelerations of the paddle particles in storage order (`a_w` of Eq. 27); empty when no
    /// wall moves.
    moving_acc: Vec<D::V>,
}

impl<D: Dim> Adami<D> {
    /// `n_moving`: the wall particles that move (the paddle's), 0 without a paddle.
    pub(super) fn new(n_moving: usize) -> Self {
        Self { moving_acc: vec![D::V::ZERO; n_moving] }
    }
}

impl<D: Dim, K: Kernel> WallModel<D, K> for Adami<D> {
    fn name(&self) -> &'static str {
        "adami"
    }

    fn before_forces(&mut self, c: &Constants, kernel: &K, grid: &CellGrid<D>, p: &mut Particles<D>, moving: &MovingWalls<'_, D>) {
        let fs = p.fluid_start();
        if !self.moving_acc.is_empty() {
            (moving.acc)(&p.id[p.n_fixed..fs], &mut self.moving_acc);
        }
        let (rho_walls, rho_fluid) = p.rho.split_at_mut(fs);
        wall_density_from_fluid(c, kernel, grid, &p.pos, &p.kind, rho_fluid, p.n_fixed, &self.moving_acc, rho_walls);
    }

    fn forces(&self, _: &Constants, _: &K, _: &CellGrid<D>, _: Fields<'_, D>, drho_walls: &mut [Real], fluid: FluidForces<'_>) -> StepLimits {
        // densities set before the forces; the integrator leaves them alone
        drho_walls.fill(0.0);
        fluid()
    }

    fn integrated_density_floor(&self, _: &Constants) -> Option<Real> {
        None
    }

    fn memory_bytes(&self) -> usize {
        self.moving_acc.capacity() * std::mem::size_of::<D::V>()
    }
}

/// Wall densities of Adami, Hu & Adams (2012) Eq. 27 (see [`crate::scene::Boundary::Adami`]):
/// for each wall particle `w` (slots `0..rho_walls.len()`), the Shepard average over its fluid
/// neighbours of `p_f + rho_f (g - a_w) . r_wf`, floored at 0, turned into a density by the
/// equation of state; `rho0` without fluid neighbours. `wall_acc` holds the accelerations of the
/// moving wall particles (slots from `n_fixed`), empty when no wall moves.
#[allow(clippy::too_many_arguments)]
pub fn wall_density_from_fluid<D: Dim, K: Kernel>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    pos: &[D::V],
    kind: &[u8],
    rho_fluid: &[Real],
    n_fixed: usize,
    wall_acc: &[D::V],
    rho_walls: &mut [Real],
) {
    let support2 = c.support * c.support;
    let fs = rho_walls.len();
    let mut g = D::V::ZERO;
    g.set(D::DIM - 1, -c.gravity);
    rho_walls.par_iter_mut().enumerate().with_max_len(NEIGHBOUR_TASK).for_each(|(w, rho_w)| {
        let body = if w >= n_fixed && !wall_acc.is_empty() { g - wall_acc[w - n_fixed] } else { g };
        let (mut w_sum, mut p_sum) = (0.0, 0.0);
        for_each_pair(grid, support2, GROUP_FLUID, pos, pos[w], |b, r, _, dist| {
            if kind[b] == KIND_EXCLUDED {
                return;
            }
            let wk = kernel.w(dist);
            let rho_b = rho_fluid[b - fs];
            // r = r_w - r_f: below the water, (g . r) > 0 adds the hydrostatic head
            p_sum += (pressure(c, rho_b) + rho_b * body.dot(r)) * wk;
            w_sum += wk;
        });
        let p = if w_sum > 0.0 { (p_sum / w_sum).max(0.0) } else { 0.0 };
        *rho_w = density_at_pressure(c, p);
    });
}
