//! Kernel gradient correction (J. Bonet, T.-S. L. Lok, "Variational and momentum preservation
//! aspects of Smooth Particle Hydrodynamic formulations", Comput. Methods Appl. Mech. Engrg. 180
//! (1999) 97-115, section 3): each fluid particle's kernel gradient is multiplied by
//! `L_a = B_a^-1`, `B_a = sum_b V_b (r_b - r_a) (x) grad_a W_ab` (over wall and fluid
//! neighbours; `grad_a W_ab` lies along `r_ab`, so `B_a` is symmetric), which makes the SPH
//! gradient of any linear field exact where `B_a` is invertible, whatever the particle
//! disorder.
//!
//! Applied to the pressure term of the momentum equation as the corrected gradient of the
//! pressure difference, `dv_a/dt = -(1/rho_a) sum_b V_b (P_b - P_a) L_a . grad_a W_ab + g`, over
//! wall and fluid neighbours: exact for a linear pressure field (hydrostatics) on any particle
//! set where `B_a` is invertible. The symmetric form `P_a/rho_a^2 + P_b/rho_b^2`, which keeps
//! pair forces equal and opposite, keeps a zeroth-order error `2 P_a/rho_a sum_b V_b grad W`
//! under disorder that no matrix on the gradient removes (measured: the same residual
//! acceleration, about 2 g, on a disordered still tank with and without a correction); this
//! form gives up exact momentum conservation for consistency. Continuity, density diffusion
//! and viscosity keep the plain gradient.
//!
//! Near the free surface the kernel support is cut and `B_a` loses rank (its smallest eigenvalue
//! is about 0.5 on a flat surface, 1 inside the water), and its inverse would amplify the
//! gradient along the normal; and the difference form, which conserves neither momentum nor
//! energy, fed energy into still water at the surface (a still tank blew up in 150 steps).
//! There the particle keeps the plain symmetric term `P_a/rho_a^2 + P_b/rho_b^2`. The
//! threshold is the smallest eigenvalue below which a particle counts as at the surface
//! ([`KernelCorrection::min_eigenvalue`], by default Marrone et al.'s (2010) 0.75, the band the
//! delta-plus shifting treats as the surface).
//!
//! Next to walls too: the difference form has no term that pushes a particle off a wall whose
//! pressure equals its own (the symmetric form's `P_a + P_b` does), and in flume2d-long
//! particles passed under the moving piston (t = 4.19 s with free-slip walls, 3.56 s with
//! no-slip ones) when particles next to walls were corrected. So a particle is corrected only
//! where its support holds fluid alone. Even so flume2d-long at H/dp 5 lost particles through
//! its floor at t = 9.17 s (docs/physics-options.md): no preset uses the correction.
//!
//! The correction runs in the pair-at-a-time force loop (`forces::fluid_forces_scalar` with
//! `KGC`), after one extra neighbour pass per force evaluation that forms `L_a`.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::forces::{for_each_pair, Fields};
use super::{Constants, NEIGHBOUR_TASK};
use crate::error::{Error, Result};
use crate::kernel::Kernel;
use crate::math::{Dim, Real};
use crate::neighbours::{CellGrid, GROUPS, GROUP_FLUID};
use crate::particles::KIND_EXCLUDED;
use crate::scene::serde_default as default;
use crate::scene::{ForcePrecision, Scene};

/// The scene's `kernel_correction` table (absent: no correction). Defaults in
/// `scene/defaults.rs`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KernelCorrection {
    /// Smallest eigenvalue of `B_a` (1 inside the water, about 0.5 on a flat surface) from which
    /// a particle is corrected; below it the particle keeps the plain gradient.
    #[serde(default = "default::kgc_min_eigenvalue")]
    pub min_eigenvalue: Real,
}

impl KernelCorrection {
    /// Checks the table and the options it cannot run with; errors name the key.
    pub fn validate(&self, scene: &Scene) -> Result<()> {
        if !self.min_eigenvalue.is_finite() || self.min_eigenvalue <= 0.0 || self.min_eigenvalue > 1.0 {
            return Err(Error::invalid(
                "kernel_correction.min_eigenvalue",
                format!("must lie in (0, 1] (1 is the bulk's eigenvalue), got {}", self.min_eigenvalue),
            ));
        }
        if scene.force_precision == ForcePrecision::F32 {
            return Err(Error::invalid("force_precision", "the kernel correction runs in the f64 pair-at-a-time loop; use f64"));
        }
        if scene.tensile_correction.is_some() {
            return Err(Error::invalid("tensile_correction", "is not combined with the kernel correction"));
        }
        if scene.riemann.is_some() {
            return Err(Error::invalid("riemann", "is not combined with the kernel correction"));
        }
        Ok(())
    }
}

/// `L_a` of every fluid particle (indexed from the first fluid particle): `B_a^-1` where no wall
/// particle is within the support and the smallest eigenvalue of `B_a` is at least
/// `min_eigenvalue`; elsewhere (and for excluded particles) zero, which marks a particle that
/// keeps the plain symmetric pressure term. Sums over wall and fluid neighbours in the grid's fixed order.
pub fn correction_matrices<D: Dim, K: Kernel>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: Fields<'_, D>,
    min_eigenvalue: Real,
    out: &mut [D::Sym],
) {
    let support2 = c.support * c.support;
    out.par_iter_mut().enumerate().with_max_len(NEIGHBOUR_TASK).for_each(|(i, l_a)| {
        let a = f.fluid_start + i;
        *l_a = D::Sym::default();
        if f.kind[a] == KIND_EXCLUDED {
            return;
        }
        let mut b = D::Sym::default();
        let mut walls = false;
        for group in 0..GROUPS {
            for_each_pair(grid, support2, group, f.pos, f.pos[a], |nb, r, _, dist| {
                // (r_b - r_a) (x) grad_a W_ab V_b = -F V_b r_ab (x) r_ab
                D::sym_add_outer(&mut b, r, r, -c.mass / f.rho[nb] * kernel.grad_factor(dist));
                walls |= group != GROUP_FLUID;
            });
        }
        if !walls && D::sym_min_eigenvalue(&b) >= min_eigenvalue {
            if let Some(inv) = D::sym_inverse(&b) {
                *l_a = inv;
            }
        }
    });
}
