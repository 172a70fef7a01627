//! The particle interaction loops. Each particle gathers its own sums over its neighbours in the
//! grid's fixed order (no scatter, no locks), so results are independent of the thread count.
//!
//! Notation: `r_ab = r_a - r_b`, `v_ab = v_a - v_b`, `grad_a W_ab = r_ab F(r)` with
//! `F = (dW/dr)/r` (see `kernel.rs`).

use rayon::prelude::*;

use super::eos::{pressure, sound_speed};
use super::tensile::{self, TensilePair};
use super::{Constants, NEIGHBOUR_TASK, DIFF_FOURTAKAS, DIFF_MOLTENI, DIFF_NONE, DIFF_RIEMANN, VISC_ARTIFICIAL, VISC_LAMINAR_SPS};
use crate::kernel::Kernel;
use crate::math::{Dim, PairFloat, Real, Vector};
use crate::neighbours::{CellGrid, GROUPS, GROUP_FLUID};
use crate::particles::KIND_EXCLUDED;
use crate::scene::{Diffusion, RiemannSolver, Viscosity};
use super::riemann::{self, OwnState};
use super::split_positions::SplitPositions;

/// Calls `f(b, r_ab, r_ab^2, |r_ab|)` for every particle `b != a` of `group` inside the kernel
/// support of the point `pa`, in the grid's fixed order.
///
/// Measured and dropped (docs/benchmarks.md): a branch-free two-pass variant that compacts the
/// candidates inside the support before the pair work (particle lattices make the in/out branch
/// predictable), and trimming the stencil rows to the support sphere, per group or once for
/// all groups (its per-row arithmetic cost more than the candidates it saved, 2D and 3D).
#[inline(always)]
pub(crate) fn for_each_pair<D: Dim>(
    grid: &CellGrid<D>,
    support2: Real,
    group: usize,
    pos: &[D::V],
    pa: D::V,
    mut f: impl FnMut(usize, D::V, Real, Real),
) {
    grid.for_each_near(group, pa, |b| {
        let r = pa - pos[b];
        let r2 = r.length_squared();
        if r2 < support2 && r2 > 0.0 {
            f(b, r, r2, r2.sqrt());
        }
    });
}

/// Read-only particle fields of one force evaluation.
#[derive(Clone, Copy)]
pub struct Fields<'a, D: Dim> {
    pub pos: &'a [D::V],
    pub vel: &'a [D::V],
    pub rho: &'a [Real],
    /// Particle kinds (excluded fluid particles are skipped).
    pub kind: &'a [u8],
    /// SPS stress `tau / rho^2` per fluid particle (indexed from the first fluid particle); empty
    /// unless the SPS closure is on.
    pub tau: &'a [D::Sym],
    /// Kernel gradient correction `L_a` per fluid particle (indexed from the first fluid
    /// particle, `kgc.rs`); empty unless the correction is on.
    pub kgc: &'a [D::Sym],
    /// First fluid particle.
    pub fluid_start: usize,
    /// The positions split into f32 pairs for the single-precision candidate scan
    /// (`split_positions.rs`), up to date; None: a single-precision loop splits them itself,
    /// into a buffer of its own (the solver passes its own, filled once per evaluation).
    pub split: Option<&'a SplitPositions>,
}

/// What the variable time step needs from the force loop (Monaghan & Kos 1999), with the
/// particles that set each limit (storage slots; `usize::MAX` without fluid), so a collapsing
/// step can name its particle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepLimits {
    /// Largest fluid acceleration magnitude `|f_a|` [m/s^2].
    pub max_acc: Real,
    /// `min_a h / (c_a + max_b |h v_ab.r_ab / (r_ab^2 + eta^2)|)` [s].
    pub min_dt_cv: Real,
    /// Slot of the particle with `max_acc`, and of the one with `min_dt_cv`.
    pub acc_slot: usize,
    pub cv_slot: usize,
}

impl StepLimits {
    pub(crate) const NONE: StepLimits =
        StepLimits { max_acc: 0.0, min_dt_cv: Real::INFINITY, acc_slot: usize::MAX, cv_slot: usize::MAX };
    /// Associative and commutative (ties go to the lower slot), so the result does not depend
    /// on how rayon splits the work.
    pub(crate) fn merge(self, o: StepLimits) -> StepLimits {
        let (max_acc, acc_slot) = if o.max_acc > self.max_acc || (o.max_acc == self.max_acc && o.acc_slot < self.acc_slot) {
            (o.max_acc, o.acc_slot)
        } else {
            (self.max_acc, self.acc_slot)
        };
        let (min_dt_cv, cv_slot) = if o.min_dt_cv < self.min_dt_cv || (o.min_dt_cv == self.min_dt_cv && o.cv_slot < self.cv_slot) {
            (o.min_dt_cv, o.cv_slot)
        } else {
            (self.min_dt_cv, self.cv_slot)
        };
        StepLimits { max_acc, min_dt_cv, acc_slot, cv_slot }
    }
}

/// A fluid force loop ([`fluid_forces`] for one viscosity model and one density diffusion).
pub type FluidForceLoop<D, K> =
    fn(&Constants, &K, &CellGrid<D>, Fields<'_, D>, &mut [<D as Dim>::V], &mut [Real]) -> StepLimits;

/// The fluid force loop of a scene's viscosity model and density diffusion, or of its Riemann
/// solver (`riemann.rs`) with its viscosity model, chosen once when the solver is built: the only place where the two become compile-time constants of the loop
/// (terms a scene leaves off cost nothing in it). The rest of the solver is compiled once per
/// dimension and kernel, not once per model pair.
pub fn fluid_force_loop<D: Dim, K: Kernel>(
    viscosity: &Viscosity,
    diffusion: &Diffusion,
    riemann: Option<&RiemannSolver>,
    kernel_correction: bool,
) -> FluidForceLoop<D, K> {
    use super::VISC_LAMINAR;
    if kernel_correction {
        // the pair-at-a-time loop with the correction (`kgc.rs`); the scene's check refuses it
        // with the tensile correction and the Riemann solver
        macro_rules! corrected {
            ($v:expr) => {
                match diffusion {
                    Diffusion::None => fluid_forces_scalar::<D, K, { $v }, DIFF_NONE, false, true>,
                    Diffusion::Molteni { .. } => fluid_forces_scalar::<D, K, { $v }, DIFF_MOLTENI, false, true>,
                    Diffusion::Fourtakas { .. } => fluid_forces_scalar::<D, K, { $v }, DIFF_FOURTAKAS, false, true>,
                }
            };
        }
        return match viscosity {
            Viscosity::Artificial { .. } => corrected!(VISC_ARTIFICIAL),
            Viscosity::Laminar { .. } => corrected!(VISC_LAMINAR),
            Viscosity::LaminarSps { .. } => corrected!(VISC_LAMINAR_SPS),
        };
    }
    if riemann.is_some() {
        // the scene's check refuses the artificial viscosity and every density diffusion
        // with the Riemann solver (`RiemannSolver::validate`)
        return match viscosity {
            Viscosity::LaminarSps { .. } => fluid_forces::<D, K, VISC_LAMINAR_SPS, DIFF_RIEMANN>,
            Viscosity::Laminar { .. } => fluid_forces::<D, K, VISC_LAMINAR, DIFF_RIEMANN>,
            Viscosity::Artificial { .. } => unreachable!("a validated scene has no artificial viscosity with riemann"),
        };
    }
    macro_rules! by_diffusion {
        ($v:expr) => {
            match diffusion {
                Diffusion::None => fluid_forces::<D, K, { $v }, DIFF_NONE>,
                Diffusion::Molteni { .. } => fluid_forces::<D, K, { $v }, DIFF_MOLTENI>,
                Diffusion::Fourtakas { .. } => fluid_forces::<D, K, { $v }, DIFF_FOURTAKAS>,
            }
        };
    }
    match viscosity {
        Viscosity::Artificial { .. } => by_diffusion!(VISC_ARTIFICIAL),
        Viscosity::Laminar { .. } => by_diffusion!(VISC_LAMINAR),
        Viscosity::LaminarSps { .. } => by_diffusion!(VISC_LAMINAR_SPS),
    }
}

/// [`fluid_force_loop`]'s batched loop with pair floats that count their operations
/// (`flop_count.rs`), for the scenes that run the batched loop; `None` for those that run the
/// pair-at-a-time loop (the SPS closure, the kernel correction), which nothing counts.
#[cfg(feature = "flop-count")]
pub fn counted_force_loop<D: Dim, K: Kernel>(
    viscosity: &Viscosity,
    diffusion: &Diffusion,
    riemann: Option<&RiemannSolver>,
    kernel_correction: bool,
) -> Option<FluidForceLoop<D, K>> {
    use super::batched::fluid_forces_counted as counted;
    use super::VISC_LAMINAR;
    let visc = match viscosity {
        Viscosity::LaminarSps { .. } => return None,
        _ if kernel_correction => return None,
        Viscosity::Artificial { .. } => VISC_ARTIFICIAL,
        Viscosity::Laminar { .. } => VISC_LAMINAR,
    };
    Some(match (visc, riemann.is_some(), diffusion) {
        (VISC_LAMINAR, true, _) => counted::<D, K, VISC_LAMINAR, DIFF_RIEMANN>,
        (VISC_ARTIFICIAL, false, Diffusion::None) => counted::<D, K, VISC_ARTIFICIAL, DIFF_NONE>,
        (VISC_ARTIFICIAL, false, Diffusion::Molteni { .. }) => counted::<D, K, VISC_ARTIFICIAL, DIFF_MOLTENI>,
        (VISC_ARTIFICIAL, false, Diffusion::Fourtakas { .. }) => counted::<D, K, VISC_ARTIFICIAL, DIFF_FOURTAKAS>,
        (_, false, Diffusion::None) => counted::<D, K, VISC_LAMINAR, DIFF_NONE>,
        (_, false, Diffusion::Molteni { .. }) => counted::<D, K, VISC_LAMINAR, DIFF_MOLTENI>,
        (_, false, Diffusion::Fourtakas { .. }) => counted::<D, K, VISC_LAMINAR, DIFF_FOURTAKAS>,
        (_, true, _) => unreachable!("a validated scene has no artificial viscosity with riemann"),
    })
}

/// Continuity and momentum for fluid particles: the batched (SIMD) loop of `batched.rs` for the
/// artificial and laminar viscosity models, [`fluid_forces_scalar`] for the SPS closure.
pub fn fluid_forces<D: Dim, K: Kernel, const VISC: u8, const DIFF: u8>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: Fields<'_, D>,
    acc: &mut [D::V],
    drho: &mut [Real],
) -> StepLimits {
    if VISC == VISC_LAMINAR_SPS {
        // the tensile correction (`tensile.rs`), the kernel's constant first: a kernel without
        // the correction compiles no loop with it (the batched loop chooses the same way)
        if const { tensile::corrects(K::KIND) } && c.tensile.on {
            fluid_forces_scalar::<D, K, VISC, DIFF, true, false>(c, kernel, grid, f, acc, drho)
        } else {
            fluid_forces_scalar::<D, K, VISC, DIFF, false, false>(c, kernel, grid, f, acc, drho)
        }
    } else {
        super::batched::fluid_forces_batched::<D, K, VISC, DIFF>(c, kernel, grid, f, acc, drho)
    }
}

/// Continuity (and momentum) for fluid particles, one pair at a time: writes `acc` and `drho` for the fluid range
/// (both slices start at the first fluid particle) and returns the time-step limits.
///
/// Momentum (Monaghan 1992): `dv_a/dt = -sum_b m (P_a/rho_a^2 + P_b/rho_b^2 + Pi_ab) grad_a W_ab + g`
/// plus, for laminar viscosity, Lo & Shao (2002):
/// `sum_b m 4 nu r_ab.grad_a W_ab / ((rho_a + rho_b)(r_ab^2 + eta^2)) v_ab`, and for SPS
/// (Dalrymple & Rogers 2006) `sum_b m (tau_a/rho_a^2 + tau_b/rho_b^2).grad_a W_ab`.
/// Continuity: `drho_a/dt = sum_b m v_ab.grad_a W_ab + D_a` with density diffusion
/// `D_a = delta h c0 sum_b 2 (rho_b - rho_a - rho^H_ba) (r_ba.grad_a W_ab)/(r_ab^2 + eta^2) m/rho_b`
/// over fluid neighbours (Molteni & Colagrossi 2009 Eq. 8; the hydrostatic part
/// `rho^H_ba = rho0 ((1 + rho0 g z_ab / B)^(1/gamma) - 1)` is removed for Fourtakas et al. 2019,
/// as DualSPHysics' DDT2 does).
/// With Monaghan's (2000) tensile correction (`TENS`: [`fluid_forces`] sets it where the scene
/// has it) the pressure term gains `(R_a + R_b) f_ab^4` (`tensile.rs`).
/// With `KGC` the pressure part `(P_a/rho_a^2 + P_b/rho_b^2) grad_a W_ab` becomes the corrected
/// gradient of the pressure difference, `(P_b - P_a)/(rho_a rho_b) L_a grad_a W_ab` (`kgc.rs`).
/// With `DIFF = DIFF_RIEMANN` each pair's pressure and continuity terms are the Riemann
/// solver's (`riemann.rs`) instead, and the viscous terms are added as here.
pub fn fluid_forces_scalar<D: Dim, K: Kernel, const VISC: u8, const DIFF: u8, const TENS: bool, const KGC: bool>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: Fields<'_, D>,
    acc: &mut [D::V],
    drho: &mut [Real],
) -> StepLimits {
    let tens = TensilePair::<Real>::new(&c.tensile);
    let mut g = D::V::ZERO;
    g.set(D::DIM - 1, -c.gravity);
    let support2 = c.support * c.support;
    acc.par_iter_mut()
        .zip(drho.par_iter_mut())
        .enumerate()
        .with_max_len(NEIGHBOUR_TASK)
        .map(|(i, (acc_a, drho_a))| {
            let a = f.fluid_start + i;
            if f.kind[a] == KIND_EXCLUDED {
                *acc_a = D::V::ZERO;
                *drho_a = 0.0;
                return StepLimits::NONE;
            }
            let (pa, va, rhoa) = (f.pos[a], f.vel[a], f.rho[a]);
            let pa_p = pressure(c, rhoa);
            let pa_rho2 = pa_p / (rhoa * rhoa);
            let tens_a = if TENS { tens.stress(pa_p, pa_rho2) } else { 0.0 };
            let ca = sound_speed(c, rhoa);
            let tau_a = if VISC == VISC_LAMINAR_SPS { f.tau[i] } else { D::Sym::default() };
            let own = OwnState { rho: rhoa, p: pa_p, z: rhoa * ca };
            // a zero matrix marks a particle that keeps the plain symmetric form (`kgc.rs`)
            let (l_a, inv_rhoa) = if KGC { (f.kgc[i], 1.0 / rhoa) } else { (D::Sym::default(), 0.0) };
            let corrected = KGC && D::sym_trace_and_norm2(&l_a).1 > 0.0;
            let mut sum_acc = D::V::ZERO;
            let mut sum_drho = 0.0;
            let mut sum_diff = 0.0;
            let mut max_visc = 0.0f64;
            for group in 0..GROUPS {
                let is_fluid = group == GROUP_FLUID;
                let (alpha, nu) = c.viscous_coefficients(!is_fluid);
                for_each_pair(grid, support2, group, f.pos, pa, |b, r, r2, dist| {
                    let rhob = f.rho[b];
                    if DIFF == DIFF_RIEMANN {
                        // the Riemann solver's pair (`riemann.rs`): its P* and its whole
                        // continuity term, then the viscous terms as below
                        let vab = va - f.vel[b];
                        let vr = vab.dot(r);
                        let (pb, cb) = (pressure(c, rhob), sound_speed(c, rhob));
                        let t = riemann::pair_terms(c.riemann_limiter, c.rho0_g, own, rhob, pb, cb, vr, dist, r2 + c.eta2, r.vertical(), is_fluid);
                        let fk = if K::NEEDS_INV_R { kernel.grad_factor_inv_r(dist, t.inv_dist) } else { kernel.grad_factor(dist) };
                        let gw = r * fk;
                        max_visc = max_visc.max((c.h * vr * t.inv_r2e).abs());
                        sum_drho += t.drho_over_f * fk;
                        sum_acc -= gw * t.p_term;
                        sum_acc += vab * (4.0 * nu * r.dot(gw) * t.inv_r2e * t.inv_sum_rho);
                        if VISC == VISC_LAMINAR_SPS && is_fluid {
                            let tb = &f.tau[b - f.fluid_start];
                            sum_acc += D::sym_dot(&tau_a, gw) + D::sym_dot(tb, gw);
                        }
                        return;
                    }
                    // One division gives the pair's four reciprocals: 1/(r^2 + eta^2),
                    // 1/(rho_a + rho_b), 1/rho_b and (for kernels that need it) 1/r. Divisions
                    // and square roots share one slow unit and bounded this loop.
                    let r2e = r2 + c.eta2;
                    let sum_rho = rhoa + rhob;
                    let rr = if K::NEEDS_INV_R { dist } else { 1.0 };
                    let inv_all = 1.0 / (rr * r2e * rhob * sum_rho);
                    let inv_r2_eta2 = rr * rhob * sum_rho * inv_all;
                    let inv_sum_rho = rr * r2e * rhob * inv_all;
                    let fk = if K::NEEDS_INV_R {
                        kernel.grad_factor_inv_r(dist, r2e * rhob * sum_rho * inv_all)
                    } else {
                        kernel.grad_factor(dist)
                    };
                    let gw = r * fk;
                    let vab = va - f.vel[b];
                    sum_drho += vab.dot(gw);

                    let vr = vab.dot(r);
                    let visc_rate = c.h * vr * inv_r2_eta2;
                    max_visc = max_visc.max(visc_rate.abs());
                    // P_b / rho_b^2 from the pair's reciprocal of rho_b (pressure is not stored)
                    let inv_rhob = rr * r2e * sum_rho * inv_all;
                    let pb = pressure(c, rhob);
                    let pb_rho2 = pb * inv_rhob * inv_rhob;
                    let p_pair = pa_rho2 + pb_rho2;
                    let mut p_term = p_pair;
                    if TENS {
                        p_term += tens.term(dist, tens_a, tens.stress(pb, pb_rho2));
                    }
                    if VISC == VISC_ARTIFICIAL {
                        // Pi_ab acts on approaching pairs only (v_ab.r_ab < 0); min() instead of
                        // a branch: the sign is unpredictable, and for v_ab.r_ab >= 0 the term
                        // is -0.0, which leaves p_term unchanged.
                        // cbar / rhobar = (c_a + c_b) / (rho_a + rho_b)
                        let cbar_rhobar = (ca + sound_speed(c, rhob)) * inv_sum_rho;
                        p_term += -alpha * cbar_rhobar * (c.h * vr.min(0.0) * inv_r2_eta2);
                    }
                    if corrected {
                        // the corrected gradient of the pressure difference,
                        // (P_b - P_a) / (rho_a rho_b) L_a grad_a W_ab; the other terms (artificial
                        // viscosity) on the plain gradient
                        let p_diff = (pb - pa_p) * inv_rhoa * inv_rhob;
                        sum_acc -= gw * (p_term - p_pair) + D::sym_dot(&l_a, gw) * p_diff;
                    } else {
                        sum_acc -= gw * p_term;
                    }
                    if VISC != VISC_ARTIFICIAL {
                        let lam = 4.0 * nu * r.dot(gw) * inv_r2_eta2 * inv_sum_rho;
                        sum_acc += vab * lam;
                    }
                    if VISC == VISC_LAMINAR_SPS && is_fluid {
                        let tb = &f.tau[b - f.fluid_start];
                        sum_acc += D::sym_dot(&tau_a, gw) + D::sym_dot(tb, gw);
                    }
                    if DIFF != DIFF_NONE && is_fluid {
                        let drho_ba = if DIFF == DIFF_FOURTAKAS {
                            hydrostatic_free_difference(c, pb - pa_p, r.vertical())
                        } else {
                            rhob - rhoa
                        };
                        debug_assert!(DIFF == DIFF_MOLTENI || DIFF == DIFF_FOURTAKAS);
                        // r_ba . grad_a W_ab = -r_ab . grad_a W_ab = -r2 F > 0
                        sum_diff += 2.0 * drho_ba * (-r2 * fk) * inv_r2_eta2 * inv_rhob;
                    }
                });
            }
            // every particle has the same mass: it is factored out of the sums (with the Riemann
            // solver sum_drho is its whole continuity term and delta_h_c0 is 0)
            let a_total = sum_acc * c.mass + g;
            *acc_a = a_total;
            *drho_a = c.mass * (sum_drho + c.delta_h_c0 * sum_diff);
            StepLimits { max_acc: a_total.length(), min_dt_cv: c.h / (ca + max_visc), acc_slot: a, cv_slot: a }
        })
        .reduce(|| StepLimits::NONE, StepLimits::merge)
}

/// The density difference `rho_b - rho_a` of a pair without its hydrostatic part, taken in
/// pressure: `(p_b - p_a - rho0 g z_ab) / c0^2`. Fourtakas et al. (2019) subtract the hydrostatic
/// density difference about the free-surface state (Eq. 13);
/// with Tait's curved equation of state that is exact only for pairs at the surface, and its
/// even part in `z_ab` does not cancel between `ab` and `ba`: every pair adds density, and still
/// water expands (docs/wave-flume.md, "The mean water level"). In pressure the hydrostatic
/// field is exactly linear (`p = rho0 g depth` is how the water starts), so the difference is
/// zero for every hydrostatic pair and odd in `ab`; its first-order term is Eq. 13's.
#[inline(always)]
pub(crate) fn hydrostatic_free_difference<F: PairFloat>(c: &Constants, p_ba: F, z_ab: F) -> F {
    (p_ba - F::of(c.rho0_g) * z_ab) * F::of(c.inv_c0_2)
}

/// SPS sub-particle stress `tau / rho^2` for each fluid particle (Dalrymple & Rogers 2006 Eq. 11,
/// in DualSPHysics' form): strain rate `S = sym(grad v)` from fluid neighbours,
/// `nu_t = (Cs dp)^2 |S|`, `|S| = sqrt(2 S:S)`,
/// `tau/rho = 2 nu_t S - 2/3 (nu_t div v + C_I dp^2 |S|^2) I`.
pub fn sps_stress<D: Dim, K: Kernel>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: Fields<'_, D>,
    tau: &mut [D::Sym],
) {
    let support2 = c.support * c.support;
    tau.par_iter_mut().enumerate().with_max_len(NEIGHBOUR_TASK).for_each(|(i, tau_a)| {
        let a = f.fluid_start + i;
        let (pa, va) = (f.pos[a], f.vel[a]);
        let mut strain = D::Sym::default();
        for_each_pair(grid, support2, GROUP_FLUID, f.pos, pa, |b, r, _, dist| {
            let gw = r * kernel.grad_factor(dist);
            // grad v_a = sum_b V_b (v_b - v_a) (x) grad_a W_ab
            D::sym_add_outer(&mut strain, va - f.vel[b], gw, -c.mass / f.rho[b]);
        });
        let (div, s2) = D::sym_trace_and_norm2(&strain);
        let s_norm2 = 2.0 * s2;
        let nu_t = c.sps_smag * s_norm2.sqrt();
        let inv_rho = 1.0 / f.rho[a];
        let diag = -(2.0 / 3.0 * nu_t * div + c.sps_blin * s_norm2);
        *tau_a = D::sym_scale_add_diag(&strain, 2.0 * nu_t * inv_rho, diag * inv_rho);
    });
}

/// Particle-shifting fields of each fluid particle (see [`crate::scene::Shifting`]): the
/// concentration gradient `grad C_a = sum_b V_b grad_a W_ab` (Lind et al. 2012, Eq. 23) and the
/// particle divergence `div r_a = -sum_b V_b r_ab . grad_a W_ab` (Lee et al. 2008), over wall
/// and fluid neighbours in a fixed order (walls, paddle, fluid). Excluded particles get zeros.
pub fn shifting_fields<D: Dim, K: Kernel>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: Fields<'_, D>,
    grad: &mut [D::V],
    div: &mut [Real],
) {
    let support2 = c.support * c.support;
    grad.par_iter_mut().zip(div.par_iter_mut()).enumerate().with_max_len(NEIGHBOUR_TASK).for_each(|(i, (grad_a, div_a))| {
        let a = f.fluid_start + i;
        let (mut g, mut d) = (D::V::ZERO, 0.0);
        if f.kind[a] != KIND_EXCLUDED {
            let pa = f.pos[a];
            for group in 0..GROUPS {
                for_each_pair(grid, support2, group, f.pos, pa, |b, r, r2, dist| {
                    let vf = c.mass / f.rho[b] * kernel.grad_factor(dist);
                    g += r * vf;
                    d -= r2 * vf;
                });
            }
        }
        *grad_a = g;
        *div_a = d;
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    #[test]
    fn hydrostatic_free_difference_is_odd_and_zero_for_still_water() {
        let s = Scene::from_json(
            r#"{"dim": 2, "dp": 0.01, "coefsound": 10, "tank": {"min": [0, 0], "max": [1, 1]}, "fluid": [{"min": [0, 0], "max": [1, 0.5]}]}"#,
        )
        .expect("scene");
        let c = Constants::new(&s);
        let p_at = |depth: Real| super::super::eos::pressure(&c, super::super::eos::density_at_pressure(&c, c.rho0_g * depth));
        for (za, zb) in [(0.45, 0.43), (0.1, 0.13), (0.02, 0.0)] {
            let (pa, pb) = (p_at(0.5 - za), p_at(0.5 - zb));
            let ab = hydrostatic_free_difference(&c, pb - pa, za - zb);
            let ba = hydrostatic_free_difference(&c, pa - pb, zb - za);
            assert!(ab.abs() < 1e-9 && ab == -ba, "{za} {zb}: {ab} {ba}");
        }
        // a pair off hydrostatics: its density difference (first order, as Fourtakas' Eq. 13)
        let (pa, pb) = (p_at(0.1), p_at(0.1) + 50.0);
        let d = hydrostatic_free_difference(&c, pb - pa, 0.0);
        assert!((d - 50.0 / (c.c0 * c.c0)).abs() < 1e-12, "{d}");
    }
}
