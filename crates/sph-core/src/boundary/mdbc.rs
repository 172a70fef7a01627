//! Modified dynamic boundary condition (English, Dominguez, Vacondio, Crespo, Stansby, Lind,
//! Chiapolino & Gomez-Gesteira 2022, Comp. Part. Mech. 9, 1-15; see
//! [`crate::scene::Boundary::Mdbc`]). Before every force evaluation each wall particle `w`
//! takes its density from its ghost node `g`, its mirror image through the wall surface
//! (`crate::geometry::ghost_offsets`; the paddle's ghosts move with it):
//!
//! - the first-order corrected SPH interpolation at the ghost over the fluid (their Eqs. 8-10,
//!   Liu & Liu 2006): `A [rho_g, -grad rho_g] = b` with
//!   `A = sum_b V_b [[W, r_gb W], [grad W, r_gb (x) grad W]]` (rows: the value, then the gradient
//!   components) and `b = sum_b m_b [W, grad W]`, `r_gb = r_g - r_b`, `V_b = m_b / rho_b`;
//! - where `|det A|` falls below 1e-3 (too few or one-sided neighbours; DualSPHysics'
//!   `determlimit`; `det A` is dimensionless and about 1 in a full support), the Shepard value
//!   `rho_g = sum_b m_b W / sum_b V_b W` and no gradient (their Eq. 11); without fluid
//!   neighbours, rho0;
//! - `rho_w = rho_g + (r_w - r_g) . grad rho_g` (their Eq. 12), floored at rho0: DualSPHysics
//!   keeps wall densities at or above rho0 so that a wall never sucks fluid in (as the DBC and
//!   Adami arms here).
//!
//! With a slip mode other than the wall's own velocity, the wall particle's velocity is set
//! from the Shepard velocity at its ghost (see [`Slip`]); it is what the fluid's continuity and
//! viscous terms read, as DualSPHysics' `velrhop` of an mDBC wall. The integrator leaves wall
//! densities alone.

use rayon::prelude::*;

use super::{on_paddle, FluidForces, MovingWalls, WallModel};
use crate::error::Result;
use crate::geometry::ghost_offsets;
use crate::kernel::Kernel;
use crate::math::{Dim, Real, Vector};
use crate::neighbours::{CellGrid, GROUP_FLUID};
use crate::particles::{Particles, KIND_EXCLUDED};
use crate::physics::forces::{Fields, StepLimits};
use crate::physics::{Constants, NEIGHBOUR_TASK};
use crate::scene::{Scene, Slip};

/// Smallest `|det A|` for the first-order interpolation (DualSPHysics' `determlimit`).
const DET_LIMIT: Real = 1e-3;

pub(super) struct Mdbc<D: Dim> {
    slip: Slip,
    /// Ghost node of each fixed wall slot (the fixed walls are sorted once, at the build); the
    /// particle's own position where it has none.
    fixed_ghost: Vec<D::V>,
    /// The paddle particles' rest positions and their ghost nodes at rest, by `id - n_fixed`.
    moving_rest: Vec<D::V>,
    moving_ghost_rest: Vec<D::V>,
    /// Per paddle slot, at the present pose: ghost node and the wall's velocity.
    moving_ghost: Vec<D::V>,
    moving_vel: Vec<D::V>,
}

impl<D: Dim> Mdbc<D> {
    pub(super) fn new(slip: Slip) -> Self {
        Self {
            slip,
            fixed_ghost: Vec::new(),
            moving_rest: Vec::new(),
            moving_ghost_rest: Vec::new(),
            moving_ghost: Vec::new(),
            moving_vel: Vec::new(),
        }
    }
}

impl<D: Dim, K: Kernel> WallModel<D, K> for Mdbc<D> {
    fn name(&self) -> &'static str {
        "mdbc"
    }

    fn prepare(&mut self, scene: &Scene, p: &Particles<D>, moving_ref: &[D::V]) -> Result<()> {
        let fixed = &p.pos[..p.n_fixed];
        self.fixed_ghost = ghost_offsets::<D>(scene, fixed, false)?
            .iter()
            .zip(fixed)
            .map(|(&o, &x)| x + o)
            .collect();
        self.moving_rest = moving_ref.to_vec();
        self.moving_ghost_rest = ghost_offsets::<D>(scene, moving_ref, true)?
            .iter()
            .zip(moving_ref)
            .map(|(&o, &x)| x + o)
            .collect();
        self.moving_ghost = vec![D::V::ZERO; p.n_moving];
        self.moving_vel = vec![D::V::ZERO; p.n_moving];
        Ok(())
    }

    fn before_forces(
        &mut self,
        c: &Constants,
        kernel: &K,
        grid: &CellGrid<D>,
        p: &mut Particles<D>,
        moving: &MovingWalls<'_, D>,
    ) {
        let (nf, fs) = (p.n_fixed, p.fluid_start());
        let (rest, ghost_rest) = (&self.moving_rest, &self.moving_ghost_rest);
        let (ids, pose) = (&p.id[nf..fs], moving.pose);
        self.moving_ghost
            .par_iter_mut()
            .zip(self.moving_vel.par_iter_mut())
            .zip(ids.par_iter())
            .for_each(|((g, v), &id)| {
                let k = id as usize - nf;
                *g = on_paddle::<D>(pose, ghost_rest[k]).0;
                *v = on_paddle::<D>(pose, rest[k]).1;
            });
        let (fixed_ghost, moving_ghost, moving_vel, slip) = (
            &self.fixed_ghost,
            &self.moving_ghost,
            &self.moving_vel,
            self.slip,
        );
        let Particles {
            pos,
            vel,
            rho,
            kind,
            ..
        } = p;
        let (rho_walls, rho_fluid) = rho.split_at_mut(fs);
        let (vel_walls, vel_fluid) = vel.split_at_mut(fs);
        let fluid = FluidView::<D> {
            pos,
            kind,
            rho: rho_fluid,
            vel: vel_fluid,
            fs,
        };
        rho_walls
            .par_iter_mut()
            .zip(vel_walls.par_iter_mut())
            .enumerate()
            .with_max_len(NEIGHBOUR_TASK)
            .for_each(|(w, (rho_w, vel_w))| {
                let (ghost, v_m) = if w < nf {
                    (fixed_ghost[w], D::V::ZERO)
                } else {
                    (moving_ghost[w - nf], moving_vel[w - nf])
                };
                let (rho, v_g) = fluid.wall_state(c, kernel, grid, ghost, pos[w]);
                *rho_w = rho.max(c.rho0);
                if slip == Slip::WallVelocity {
                    return;
                }
                *vel_w = match v_g {
                    None => v_m,
                    Some(v_g) if slip == Slip::NoSlip => v_m * 2.0 - v_g,
                    Some(v_g) => {
                        // n: the unit normal out of the wall, towards the ghost
                        let n = (ghost - pos[w]) * (1.0 / (ghost - pos[w]).length());
                        v_g + n * (2.0 * (v_m - v_g).dot(n))
                    }
                };
            });
    }

    fn forces(
        &self,
        _: &Constants,
        _: &K,
        _: &CellGrid<D>,
        _: Fields<'_, D>,
        drho_walls: &mut [Real],
        fluid: FluidForces<'_>,
    ) -> StepLimits {
        // densities set before the forces; the integrator leaves them alone
        drho_walls.fill(0.0);
        fluid()
    }

    fn integrated_density_floor(&self, _: &Constants) -> Option<Real> {
        None
    }

    fn memory_bytes(&self) -> usize {
        let v = std::mem::size_of::<D::V>();
        (self.fixed_ghost.capacity()
            + self.moving_rest.capacity()
            + self.moving_ghost_rest.capacity()
            + self.moving_ghost.capacity()
            + self.moving_vel.capacity())
            * v
    }
}

/// The fluid's fields an interpolation at a ghost node reads (fluid slots from `fs`).
struct FluidView<'a, D: Dim> {
    pos: &'a [D::V],
    kind: &'a [u8],
    rho: &'a [Real],
    vel: &'a [D::V],
    fs: usize,
}

impl<D: Dim> FluidView<'_, D> {
    /// The density a wall particle at `wall` takes from its ghost node at `ghost` (before
    /// the floor at rho0), and the Shepard velocity of the fluid at the ghost (None without
    /// fluid there or without a ghost).
    fn wall_state<K: Kernel>(
        &self,
        c: &Constants,
        kernel: &K,
        grid: &CellGrid<D>,
        ghost: D::V,
        wall: D::V,
    ) -> (Real, Option<D::V>) {
        let to_wall = wall - ghost;
        if to_wall.length_squared() == 0.0 {
            return (c.rho0, None);
        }
        let support2 = c.support * c.support;
        // A (rows: the value, then the gradient's components; columns: the value, then the
        // offsets' components) and b, as the module's docs
        let mut a = [[0.0; 4]; 4];
        let mut b = [0.0; 4];
        let mut v_sum = D::V::ZERO;
        // every fluid particle within the support, one at the ghost itself included (the
        // ghost of a wall particle often sits on the fluid's lattice)
        grid.for_each_near(GROUP_FLUID, ghost, |j| {
            let r = ghost - self.pos[j];
            let r2 = r.length_squared();
            if r2 >= support2 || self.kind[j] == KIND_EXCLUDED {
                return;
            }
            let dist = r2.sqrt();
            let wk = kernel.w(dist);
            let grad = if r2 > 0.0 {
                r * kernel.grad_factor(dist)
            } else {
                D::V::ZERO
            };
            let vol = c.mass / self.rho[j - self.fs];
            b[0] += c.mass * wk;
            a[0][0] += vol * wk;
            for k in 0..D::DIM {
                b[1 + k] += c.mass * grad.get(k);
                a[0][1 + k] += r.get(k) * vol * wk;
                a[1 + k][0] += grad.get(k) * vol;
                for l in 0..D::DIM {
                    a[1 + k][1 + l] += r.get(l) * grad.get(k) * vol;
                }
            }
            v_sum += self.vel[j - self.fs] * (vol * wk);
        });
        if a[0][0] <= 0.0 {
            return (c.rho0, None);
        }
        let v_g = v_sum * (1.0 / a[0][0]);
        let rho = match solve(a, b, D::DIM + 1) {
            // x = [rho_g, -grad rho_g]
            Some(x) => x[0] - (0..D::DIM).map(|k| x[1 + k] * to_wall.get(k)).sum::<Real>(),
            None => b[0] / a[0][0],
        };
        (rho, Some(v_g))
    }
}

/// Solves `a x = b` for the leading `n x n` block by Gaussian elimination with partial
/// pivoting; None when `|det a| < DET_LIMIT` (the determinant is the product of the pivots).
fn solve(mut a: [[Real; 4]; 4], mut b: [Real; 4], n: usize) -> Option<[Real; 4]> {
    let mut det = 1.0;
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .unwrap_or(col);
        if pivot != col {
            a.swap(pivot, col);
            b.swap(pivot, col);
            det = -det;
        }
        det *= a[col][col];
        if a[col][col] == 0.0 {
            return None;
        }
        let pivot_row = a[col];
        for row in col + 1..n {
            let f = a[row][col] / pivot_row[col];
            for (x, p) in a[row][col..n].iter_mut().zip(&pivot_row[col..n]) {
                *x -= f * p;
            }
            b[row] -= f * b[col];
        }
    }
    if det.is_nan() || det.abs() < DET_LIMIT {
        return None;
    }
    let mut x = [0.0; 4];
    for row in (0..n).rev() {
        let tail: Real = (row + 1..n).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - tail) / a[row][row];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solve_inverts_a_well_posed_system_and_refuses_a_singular_one() {
        let a = [
            [2.0, 1.0, 0.0, 0.0],
            [1.0, -3.0, 0.5, 0.0],
            [0.0, 0.5, -1.0, 0.0],
            [0.0; 4],
        ];
        let x_true = [1.0, -2.0, 0.5, 0.0];
        let mut b = [0.0; 4];
        for i in 0..3 {
            b[i] = (0..3).map(|k| a[i][k] * x_true[k]).sum();
        }
        let x = solve(a, b, 3).expect("regular");
        assert!((0..3).all(|i| (x[i] - x_true[i]).abs() < 1e-14), "{x:?}");
        let singular = [
            [1.0, 2.0, 0.0, 0.0],
            [2.0, 4.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0; 4],
        ];
        assert!(solve(singular, b, 3).is_none());
        // |det| = 1e-4 < DET_LIMIT: the Shepard value instead
        let small = [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1e-2, 0.0, 0.0],
            [0.0, 0.0, 1e-2, 0.0],
            [0.0; 4],
        ];
        assert!(solve(small, b, 3).is_none());
    }
}
