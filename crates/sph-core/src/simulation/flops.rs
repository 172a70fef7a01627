//! The roofline's measurement (feature `flop-count`): the operations of one fluid force
//! evaluation, counted, and the wall time of the real loop on the same state.

use std::time::Instant;

use super::{fields_of, on_pool, Solver};
use crate::kernel::Kernel;
use crate::math::{Dim, Vector};
use crate::physics::flop_count::{self, PairOps};
use crate::physics::forces::{counted_force_loop, Fields};

/// One force evaluation's operations and the time the real loop takes for it.
#[derive(Clone, Debug)]
pub struct PairFlops {
    /// The operations of the batched loop, counted on the present state.
    pub ops: PairOps,
    /// Fluid pairs within the support at the present state ([`Solver::fluid_pair_count`]).
    pub pairs: u64,
    /// Wall time [s] of each of the repeated evaluations of the scene's own (uncounted) fluid
    /// loop on that state, in the rayon pool as a step runs it; the walls' loops not included.
    pub loop_seconds: Vec<f64>,
    /// Whether the counted evaluation gave the real loop's accelerations and density rates bit
    /// for bit (it must: the same operations in the same order).
    pub same_bits: bool,
}

impl<D: Dim, K: Kernel> Solver<D, K> {
    /// Counts the operations of one fluid force evaluation at the present state and times
    /// `repeats` evaluations of the real loop on it. `None` for a scene that runs the
    /// pair-at-a-time loop (the SPS closure, the kernel correction).
    pub fn pair_flops(&mut self, repeats: u32) -> Option<PairFlops> {
        let scene = &self.scene;
        let counted = counted_force_loop::<D, K>(&scene.viscosity, &scene.diffusion, scene.riemann.as_ref(), scene.kernel_correction.is_some())?;
        // sorts the groups and sets the walls' densities, as a step does before the fluid loop
        self.compute_forces();
        let (c, kernel, grid, fluid_loop) = (self.c, &self.kernel, &self.grid, self.fluid_loop);
        // the positions split for a single-precision loop, as `compute_forces` left them
        let fields = Fields { split: c.pair_f32.then_some(&self.scratch.split), ..fields_of(&self.p, &[]) };
        let n = self.p.n_fluid();
        let (mut acc, mut drho) = (vec![D::V::ZERO; n], vec![0.0; n]);
        flop_count::reset();
        on_pool(|| counted(&c, kernel, grid, fields, &mut acc, &mut drho));
        let ops = flop_count::read();
        let (counted_acc, counted_drho) = (acc.clone(), drho.clone());
        let loop_seconds = (0..repeats)
            .map(|_| {
                let t0 = Instant::now();
                on_pool(|| fluid_loop(&c, kernel, grid, fields, &mut acc, &mut drho));
                t0.elapsed().as_secs_f64()
            })
            .collect();
        let same_bits = acc == counted_acc && drho.iter().zip(&counted_drho).all(|(a, b)| a.to_bits() == b.to_bits());
        Some(PairFlops { ops, pairs: self.fluid_pair_count(), loop_seconds, same_bits })
    }
}
