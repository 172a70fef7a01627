//! The force of the fluid on a solid body and its moment ([`super::GaugeSpec::Force`]).
//!
//! The body is the set of fixed wall particles of one obstacle
//! ([`crate::geometry::wall_bodies`]: those sampled from it, and those of a side wall that is
//! a plane of symmetry inside it where it crosses that wall). Each of them feels,
//! from each fluid neighbour `a`, the opposite of the pair force the fluid particle feels from
//! it in the momentum equation (Monaghan 1992, with the scene's viscosity; see
//! [`crate::physics::forces::fluid_forces_scalar`]):
//!
//! `F_w = sum_a m^2 [(P_a/rho_a^2 + P_w/rho_w^2 + Pi_aw) grad_a W_aw
//!        - 4 nu (r_aw.grad_a W_aw) / ((rho_a + rho_w)(r_aw^2 + eta^2)) v_aw]`,
//!
//! so that the fluid's momentum and the body's balance pair by pair. `P_w` is the wall
//! particle's pressure from its density: DBC's integrated density, or Adami's density of the
//! pressure extrapolated from the fluid at the last force evaluation. The body's force is the
//! sum of its particles' `F_w`, and its moment about a point `x_0` the sum of
//! `(x_w - x_0) x F_w`.

use rayon::prelude::*;

use super::ProbeView;
use crate::kernel::Kernel;
use crate::math::{Dim, Real, Vector};
use crate::neighbours::GROUP_FLUID;
use crate::particles::KIND_EXCLUDED;
use crate::physics::eos::{pressure, sound_speed};
use crate::physics::forces::for_each_pair;

/// The body index of a wall particle that belongs to no obstacle (the tank's walls).
pub const NO_BODY: u16 = u16::MAX;

/// Wall slots per partial sum. The partial sums of these fixed chunks are added in order, so a
/// body's force does not depend on the thread count.
const CHUNK: usize = 256;

/// The force of the fluid on the wall particles of obstacle `body` ([`ProbeView::wall_body`])
/// and its moment about `point` (three components; in 2D only the first, about y, is set).
pub fn body_force<D: Dim, K: Kernel>(view: &ProbeView<'_, D, K>, body: u16, point: D::V) -> (D::V, [Real; 3]) {
    let pos = &view.p.pos;
    let partial: Vec<(D::V, [Real; 3])> = view
        .wall_body
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(k, bodies)| {
            let (mut force, mut moment) = (D::V::ZERO, [0.0; 3]);
            for (j, _) in bodies.iter().enumerate().filter(|(_, &b)| b == body) {
                let w = k * CHUNK + j;
                let f = wall_particle_force(view, w);
                force += f;
                add_moment::<D>(&mut moment, pos[w] - point, f);
            }
            (force, moment)
        })
        .collect();
    partial.into_iter().fold((D::V::ZERO, [0.0; 3]), |(f, m), (pf, pm)| (f + pf, [m[0] + pm[0], m[1] + pm[1], m[2] + pm[2]]))
}

/// `F_w` of the module's formula for the wall particle in slot `w`.
fn wall_particle_force<D: Dim, K: Kernel>(view: &ProbeView<'_, D, K>, w: usize) -> D::V {
    let (p, c, kernel) = (view.p, view.c, view.kernel);
    let (xw, vw, rhow) = (p.pos[w], p.vel[w], p.rho[w]);
    let pw_rho2 = pressure(c, rhow) / (rhow * rhow);
    let cw = sound_speed(c, rhow);
    let (alpha, nu) = c.viscous_coefficients(true);
    let mut sum = D::V::ZERO;
    for_each_pair(view.grid, c.support * c.support, GROUP_FLUID, &p.pos, xw, |a, r_wa, r2, dist| {
        if p.kind[a] == KIND_EXCLUDED {
            return;
        }
        let rhoa = p.rho[a];
        let r_aw = -r_wa;
        let grad = r_aw * kernel.grad_factor(dist);
        let v_aw = p.vel[a] - vw;
        let inv_r2_eta2 = 1.0 / (r2 + c.eta2);
        let inv_sum_rho = 1.0 / (rhoa + rhow);
        // Pi_aw acts on approaching pairs only (v_aw.r_aw < 0); alpha is 0 for laminar viscosity
        let vr = v_aw.dot(r_aw);
        let pi = -alpha * (sound_speed(c, rhoa) + cw) * inv_sum_rho * c.h * vr.min(0.0) * inv_r2_eta2;
        let p_term = pressure(c, rhoa) / (rhoa * rhoa) + pw_rho2 + pi;
        // nu is 0 for artificial viscosity
        let laminar = 4.0 * nu * r_aw.dot(grad) * inv_r2_eta2 * inv_sum_rho;
        sum += grad * p_term - v_aw * laminar;
    });
    sum * (c.mass * c.mass)
}

/// Adds `r x f` to `moment`: the full vector in 3D, its y component `r_z f_x - r_x f_z` in 2D
/// (x-z plane) as `moment[0]`.
fn add_moment<D: Dim>(moment: &mut [Real; 3], r: D::V, f: D::V) {
    if D::DIM == 2 {
        moment[0] += r.get(1) * f.get(0) - r.get(0) * f.get(1);
    } else {
        moment[0] += r.get(1) * f.get(2) - r.get(2) * f.get(1);
        moment[1] += r.get(2) * f.get(0) - r.get(0) * f.get(2);
        moment[2] += r.get(0) * f.get(1) - r.get(1) * f.get(0);
    }
}
