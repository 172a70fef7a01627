//! Wall models: how the wall particles (the tank's walls, obstacles and the paddle) take part
//! in a step. The solver holds the model its scene chose ([`wall_model`]) and asks it, at each
//! force evaluation, to set the walls' state before the loops and to compute the walls' own
//! rates next to the fluid's; the integrator asks whether it advances the walls' densities.
//! A new model is one more [`Boundary`] arm, one more line in [`wall_model`] and one file.

mod adami;
mod dbc;
mod mdbc;

pub use adami::wall_density_from_fluid;
pub use dbc::boundary_density_rate;

use crate::error::Result;
use crate::kernel::Kernel;
use crate::math::{Dim, Real, Vector};
use crate::motion::PaddlePose;
use crate::neighbours::CellGrid;
use crate::particles::Particles;
use crate::physics::eos;
use crate::physics::forces::{Fields, StepLimits};
use crate::physics::Constants;
use crate::scene::{Boundary, Scene};

/// The fluid's force loop, run by the wall model next to the walls' own work.
pub(crate) type FluidForces<'a> = &'a mut (dyn FnMut() -> StepLimits + Send);

/// `moving_acc(ids, out)`: writes the accelerations of the moving wall particles of the ids
/// `ids` (storage order) into `out`.
pub(crate) type MovingWallAcc<'a, D> = &'a dyn Fn(&[u32], &mut [<D as Dim>::V]);

/// The moving walls (the paddle) as the force evaluation sees them.
pub(crate) struct MovingWalls<'a, D: Dim> {
    pub acc: MovingWallAcc<'a, D>,
    /// The paddle's present pose (that of its particles' positions); None without a paddle.
    pub pose: Option<PaddlePose>,
}

/// Where a point fixed to the paddle at the pose `pose`, at `rest` when the paddle is at rest,
/// is, and its velocity (the paddle moves in the flume's x-z plane); `rest` and no velocity
/// without a paddle.
pub(crate) fn on_paddle<D: Dim>(pose: Option<PaddlePose>, rest: D::V) -> (D::V, D::V) {
    let Some(pose) = pose else { return (rest, D::V::ZERO) };
    let up = D::DIM - 1;
    let (xz, uw) = pose.apply(rest.get(0), rest.get(up));
    let (mut x, mut v) = (rest, D::V::ZERO);
    x.set(0, xz[0]);
    x.set(up, xz[1]);
    v.set(0, uw[0]);
    v.set(up, uw[1]);
    (x, v)
}

/// One wall model. The particles' wall slots are `0..fluid_start`, fixed walls first, then the
/// moving ones (the paddle).
pub(crate) trait WallModel<D: Dim, K: Kernel>: Send + Sync {
    /// The model's name in reports (the scene's `boundary.model`).
    fn name(&self) -> &'static str;

    /// Sets up what the model keeps of the walls' geometry, once the solver is built (the
    /// fixed walls sorted for good): `moving_ref` holds the paddle particles' rest positions,
    /// indexed by `id - n_fixed`.
    fn prepare(&mut self, _scene: &Scene, _p: &Particles<D>, _moving_ref: &[D::V]) -> Result<()> {
        Ok(())
    }

    /// Sets what the force loops read of the walls, before them (after the cell sort).
    fn before_forces(&mut self, c: &Constants, kernel: &K, grid: &CellGrid<D>, p: &mut Particles<D>, moving: &MovingWalls<'_, D>);

    /// Runs `fluid` (the fluid's forces) and writes the walls' density rates into `drho_walls`;
    /// returns the fluid's step limits.
    fn forces(&self, c: &Constants, kernel: &K, grid: &CellGrid<D>, fields: Fields<'_, D>, drho_walls: &mut [Real], fluid: FluidForces<'_>) -> StepLimits;

    /// The floor under the walls' densities when the integrator advances them by their rates;
    /// None when it leaves them alone.
    fn integrated_density_floor(&self, c: &Constants) -> Option<Real>;

    /// The pressure a wall particle reports, from its density.
    fn pressure(&self, c: &Constants, rho: Real) -> Real {
        eos::pressure(c, rho)
    }

    /// Bytes of the model's own arrays.
    fn memory_bytes(&self) -> usize {
        0
    }
}

/// The wall model of `boundary`. `n_moving`: the wall particles that move (0 without a paddle).
pub(crate) fn wall_model<D: Dim, K: Kernel>(boundary: Boundary, n_moving: usize) -> Box<dyn WallModel<D, K>> {
    match boundary {
        Boundary::Dbc => Box::new(dbc::Dbc),
        Boundary::Adami => Box::new(adami::Adami::<D>::new(n_moving)),
        Boundary::Mdbc { slip } => Box::new(mdbc::Mdbc::<D>::new(slip)),
    }
}
