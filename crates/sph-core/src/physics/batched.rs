//! The fluid force loop in batches: vectorisable form of [`super::forces::fluid_forces_scalar`].
//!
//! Per fluid particle `a`, the neighbours of each group are collected in the grid's order into a
//! small stack batch (index, `r_ab`, `r_ab^2`), their fields are gathered into arrays, the pair
//! terms are computed element-wise over the batch (a loop without calls or branches, which the
//! compiler turns into SIMD: 4 pairs per instruction with AVX2), and the terms are summed into
//! `LANES` partial sums (pair `k` into lane `k % LANES`), added up in a fixed order at the end.
//! The batch boundaries and the lane of every pair depend only on the particle data, so the sums
//! are the same for any thread count; they differ from the scalar loop's in the last bits only
//! (another summation order).
//!
//! With single-precision pair terms the scan itself runs in f32 on the positions split for it
//! (`split_positions.rs`: eight candidates per AVX2 instruction, no shuffles), and `r_ab` comes
//! from it in f32; with double precision it runs on the f64 positions, four at a time. Against
//! the f64 scan with its offsets rounded afterwards, the f32 scan took 14 % off the 3D dam
//! break's step, 9 % off the 2D one's and 5 % off the piston's (docs/benchmarks.md, "The
//! single-precision scan").
//!
//! A batch is padded to a whole number of lanes with dummy pairs whose kernel gradient is masked
//! to zero (the particle itself, placed at the support radius so every term stays finite).
//!
//! On x86-64 the per-particle function is compiled a second time with AVX2 enabled and chosen at
//! run time (`is_x86_feature_detected!`), so one binary runs everywhere and uses the wide units
//! where they exist. Both variants do the same operations in the same order (Rust never fuses
//! a multiply and an add on its own), so they give the same bits.

use super::eos::{pressure, seventh_power, sound_speed, TaitPair};
use super::forces::{hydrostatic_free_difference, Fields, StepLimits};
use super::tensile::{self, TensilePair};
use super::riemann::{self, OwnState};
use super::split_positions::SplitPositions;
use super::{Constants, DIFF_FOURTAKAS, DIFF_NONE, DIFF_RIEMANN, VISC_ARTIFICIAL, VISC_LAMINAR_SPS};
use crate::kernel::Kernel;
use crate::math::{Dim, PairFloat, Real, Vector};
use crate::neighbours::{CellGrid, StencilRows, GROUPS, GROUP_FIXED, GROUP_FLUID, GROUP_MOVING};
use crate::particles::KIND_EXCLUDED;
use crate::threads::{for_each_chunk, Chunks};

/// Pairs per batch: large enough to amortise the loop set-up, small enough for L1. A multiple
/// of every [`PairFloat::LANES`].
const BATCH: usize = 64;
/// The most partial sums per particle (f32 in an AVX2 register).
const MAX_LANES: usize = 8;
/// Room for the candidate scan's wide stores, which may write up to seven entries past the
/// batch's last pair (eight f32 candidates at a time; four f64).
const SCAN_ROOM: usize = BATCH + 8;

/// Per-chunk working arrays: the neighbours collected for one particle and one group, not yet
/// summed, their gathered fields and their pair terms in the pair float type `F`. Created once
/// per chunk of particles (on the stack); only the first `n` (padded) entries are ever read.
struct Scratch<F: PairFloat> {
    n: usize,
    idx: [u32; SCAN_ROOM],
    /// `r_ab` by component (x, y, z; z unused in 2D), in f64 as the scan forms it.
    r: [[Real; SCAN_ROOM]; 3],
    r2: [Real; SCAN_ROOM],
    /// `r_ab` and `r_ab^2` in f32 as the single-precision scan forms them from the split
    /// positions (`split_positions.rs`).
    rs: [[f32; SCAN_ROOM]; 3],
    r2s: [f32; SCAN_ROOM],
    vb: [[F; BATCH]; 3],
    rhob: [F; BATCH],
    /// `rho_b / rho0 - 1`, formed in f64 (single precision only).
    relb: [F; BATCH],
    /// Pressure of each neighbour.
    pb: [F; BATCH],
    cb: [F; BATCH],
    out_acc: [[F; BATCH]; 3],
    out_drho: [F; BATCH],
    out_diff: [F; BATCH],
    out_visc: [F; BATCH],
    rows: StencilRows,
}

impl<F: PairFloat> Scratch<F> {
    fn new() -> Self {
        let z = [F::default(); BATCH];
        let room = [0.0; SCAN_ROOM];
        let room32 = [0.0; SCAN_ROOM];
        Self {
            n: 0,
            idx: [0; SCAN_ROOM],
            r: [room; 3],
            r2: room,
            rs: [room32; 3],
            r2s: room32,
            vb: [z; 3],
            rhob: z,
            relb: z,
            pb: z,
            cb: z,
            out_acc: [z; 3],
            out_drho: z,
            out_diff: z,
            out_visc: z,
            rows: StencilRows::default(),
        }
    }
}

/// The fields of particle `a` that every pair uses, in the pair float type.
#[derive(Clone, Copy)]
struct Own<F: PairFloat> {
    slot: usize,
    vel: [F; 3],
    rho: F,
    /// `rho_a / rho0 - 1`, formed in f64.
    rel: F,
    /// Pressure.
    p: F,
    p_rho2: F,
    sound_speed: F,
    /// Tensile correction: `R_a = eps |P_a| / rho_a^2` (0 without it).
    tens: F,
}

/// Partial sums of particle `a`, one per lane (the first `F::LANES` are used).
#[derive(Default)]
struct Sums<F: PairFloat> {
    acc: [[F; MAX_LANES]; 3],
    drho: [F; MAX_LANES],
    diff: [F; MAX_LANES],
    /// Largest `|h v_ab.r_ab / (r_ab^2 + eta^2)|`.
    visc: [F; MAX_LANES],
}

/// Sums the pair terms of the collected pairs into `sums` and empties the batch. `G`: the group
/// of the neighbours (density diffusion acts between fluid particles only).
#[inline(always)]
fn sum_batch<F: PairFloat, D: Dim, K: Kernel, const VISC: u8, const DIFF: u8, const T7: bool, const TENS: bool, const G: usize>(
    c: &Constants,
    kernel: &K,
    f: &Fields<'_, D>,
    own: &Own<F>,
    s: &mut Scratch<F>,
    sums: &mut Sums<F>,
) {
    let fluid = G == GROUP_FLUID;
    let n = s.n;
    if n == 0 {
        return;
    }
    let n_pad = n.div_ceil(F::LANES) * F::LANES;
    // Lets the compiler drop the loops' bounds checks; with them it keeps a scalar epilogue of
    // a whole register of pairs, run on every batch.
    assert!(n_pad <= BATCH);
    #[cfg(feature = "flop-count")]
    super::flop_count::add_lanes(n_pad);
    // Padding: the particle itself at r = 0, masked in the arithmetic loop.
    for k in n..n_pad {
        s.idx[k] = own.slot as u32;
        for d in 0..3 {
            if F::SINGLE {
                s.rs[d][k] = 0.0;
            } else {
                s.r[d][k] = 0.0;
            }
        }
        if F::SINGLE {
            s.r2s[k] = 0.0;
        } else {
            s.r2[k] = 0.0;
        }
    }
    // Gather: the only indexed loads. With gamma = 7 (T7) pressure and sound speed are
    // computed in the arithmetic loop, vectorised; another gamma needs powf, done here so that
    // it does not keep that loop from vectorising.
    debug_assert!(s.idx[..n_pad].iter().all(|&b| (b as usize) < f.vel.len().min(f.rho.len())));
    for k in 0..n_pad {
        let b = s.idx[k] as usize;
        // SAFETY: every index comes from the candidate scan over the grid's slots (or is the
        // particle itself), and `fluid_forces_variant` asserted once per call that the grid's
        // slots lie within the position array and that the field arrays are as long as it.
        let (v, rhob) = unsafe { (*f.vel.get_unchecked(b), *f.rho.get_unchecked(b)) };
        for d in 0..D::DIM {
            s.vb[d][k] = F::of(v.get(d));
        }
        s.rhob[k] = F::of(rhob);
        if F::SINGLE {
            s.relb[k] = F::of(rhob * c.inv_rho0 - 1.0);
        }
        if !T7 {
            s.pb[k] = F::of(pressure(c, rhob));
            if VISC == VISC_ARTIFICIAL || DIFF == DIFF_RIEMANN {
                s.cb[k] = F::of(sound_speed(c, rhob));
            }
        }
    }

    // Element-wise pair terms (the comments of fluid_forces_scalar explain each formula), with
    // the constants in F formed once per batch.
    let (zero, one) = (F::of(0.0), F::of(1.0));
    let support2 = F::of(c.support * c.support);
    let tait = TaitPair::<F>::new(c);
    let (eta2, h) = (F::of(c.eta2), F::of(c.h));
    let (alpha, nu) = c.viscous_coefficients(!fluid);
    let (alpha, lam_coef, rho0) = (F::of(alpha), F::of(4.0 * nu), F::of(c.rho0));
    let tens = TensilePair::<F>::new(&c.tensile);
    let (riemann_eta, rho0_g) = (F::of(c.riemann_limiter), F::of(c.rho0_g));
    let three = D::DIM == 3;
    for k in 0..n_pad {
        let (rx, ry, rz, r2) = if F::SINGLE {
            // the scan's f32 offsets, read as they are
            let rz = if three { F::of_f32(s.rs[2][k]) } else { zero };
            (F::of_f32(s.rs[0][k]), F::of_f32(s.rs[1][k]), rz, F::of_f32(s.r2s[k]))
        } else {
            (F::of(s.r[0][k]), F::of(s.r[1][k]), if three { F::of(s.r[2][k]) } else { zero }, F::of(s.r2[k]))
        };
        // Pairs at r = 0 (the particle itself, padding, or a coincident particle) carry no
        // force: masked, and moved to the support radius so that no term divides by zero.
        let at_zero = r2 == zero;
        let mask = if at_zero { zero } else { one };
        let r2 = if at_zero { support2 } else { r2 };
        let rhob = s.rhob[k];
        let (pb, cb) = if T7 {
            if F::SINGLE {
                tait.seventh_of_relative(s.relb[k])
            } else {
                tait.seventh_of_density(rhob)
            }
        } else {
            (s.pb[k], s.cb[k])
        };
        let dist = r2.sqrt();
        let r2e = r2 + eta2;
        if DIFF == DIFF_RIEMANN {
            // the Riemann solver's pair (`riemann.rs`), with laminar viscosity (the scene's
            // check leaves no other model with it)
            let (vx, vy) = (own.vel[0] - s.vb[0][k], own.vel[1] - s.vb[1][k]);
            let vz = if three { own.vel[2] - s.vb[2][k] } else { zero };
            let vr = vx * rx + vy * ry + vz * rz;
            let z_ab = if three { rz } else { ry };
            let a = OwnState { rho: own.rho, p: own.p, z: own.rho * own.sound_speed };
            let t = riemann::pair_terms(riemann_eta, rho0_g, a, rhob, pb, cb, vr, dist, r2e, z_ab, fluid);
            let fk = if K::NEEDS_INV_R {
                kernel.grad_factor_inv_r_in(dist, t.inv_dist)
            } else {
                kernel.grad_factor_in(dist)
            } * mask;
            let (gx, gy, gz) = (rx * fk, ry * fk, rz * fk);
            s.out_drho[k] = t.drho_over_f * fk;
            s.out_visc[k] = (h * vr * t.inv_r2e).abs();
            let lam = lam_coef * (rx * gx + ry * gy + rz * gz) * t.inv_r2e * t.inv_sum_rho;
            s.out_acc[0][k] = -gx * t.p_term + vx * lam;
            s.out_acc[1][k] = -gy * t.p_term + vy * lam;
            s.out_acc[2][k] = -gz * t.p_term + vz * lam;
            continue;
        }
        let sum_rho = own.rho + rhob;
        let rr = if K::NEEDS_INV_R { dist } else { one };
        let inv_all = one / (rr * r2e * rhob * sum_rho);
        let inv_r2_eta2 = rr * rhob * sum_rho * inv_all;
        let inv_sum_rho = rr * r2e * rhob * inv_all;
        let fk = if K::NEEDS_INV_R {
            kernel.grad_factor_inv_r_in(dist, r2e * rhob * sum_rho * inv_all)
        } else {
            kernel.grad_factor_in(dist)
        } * mask;
        let (gx, gy, gz) = (rx * fk, ry * fk, rz * fk);
        let (vx, vy) = (own.vel[0] - s.vb[0][k], own.vel[1] - s.vb[1][k]);
        let vz = if three { own.vel[2] - s.vb[2][k] } else { zero };
        s.out_drho[k] = vx * gx + vy * gy + vz * gz;
        let vr = vx * rx + vy * ry + vz * rz;
        s.out_visc[k] = (h * vr * inv_r2_eta2).abs();
        let inv_rhob = rr * r2e * sum_rho * inv_all;
        let pb_rho2 = pb * inv_rhob * inv_rhob;
        let mut p_term = own.p_rho2 + pb_rho2;
        if TENS {
            p_term += tens.term(dist, own.tens, tens.stress(pb, pb_rho2));
        }
        if VISC == VISC_ARTIFICIAL {
            let cbar_rhobar = (own.sound_speed + cb) * inv_sum_rho;
            // `vr < 0 ? vr : 0` is `vr.min(0.0)` for every input (NaN gives 0 both ways),
            // without the NaN blend
            let approaching = if vr < zero { vr } else { zero };
            p_term += -alpha * cbar_rhobar * (h * approaching * inv_r2_eta2);
        }
        let (mut ax, mut ay, mut az) = (-gx * p_term, -gy * p_term, -gz * p_term);
        if VISC != VISC_ARTIFICIAL {
            let lam = lam_coef * (rx * gx + ry * gy + rz * gz) * inv_r2_eta2 * inv_sum_rho;
            ax += vx * lam;
            ay += vy * lam;
            az += vz * lam;
        }
        s.out_acc[0][k] = ax;
        s.out_acc[1][k] = ay;
        s.out_acc[2][k] = az;
        if DIFF != DIFF_NONE && fluid {
            let drho_ba = if DIFF == DIFF_FOURTAKAS {
                hydrostatic_free_difference(c, pb - own.p, if three { rz } else { ry })
            } else if F::SINGLE {
                // rho0 (e_b - e_a): two densities near rho0 would cancel in f32
                rho0 * (s.relb[k] - own.rel)
            } else {
                rhob - own.rho
            };
            s.out_diff[k] = F::of(2.0) * drho_ba * (-r2 * fk) * inv_r2_eta2 * inv_rhob;
        }
    }

    // Lane sums: pair k goes to lane k % LANES (one array at a time, each a vector add).
    lane_add(&mut sums.drho, &s.out_drho[..n_pad]);
    for d in 0..D::DIM {
        lane_add(&mut sums.acc[d], &s.out_acc[d][..n_pad]);
    }
    if DIFF != DIFF_NONE && fluid {
        lane_add(&mut sums.diff, &s.out_diff[..n_pad]);
    }
    lane_max(&mut sums.visc, &s.out_visc[..n_pad]);
    s.n = 0;
}

/// `max(lanes[k % LANES], terms[k])` into lane `k % LANES`. Written as a comparison, not
/// `f64::max`: the same result for every input (the lanes start at 0 and a NaN term never
/// wins), but one `vmaxpd` instead of a max and a NaN blend per register of terms.
#[inline(always)]
fn lane_max<F: PairFloat>(lanes: &mut [F; MAX_LANES], terms: &[F]) {
    for chunk in terms.chunks_exact(F::LANES) {
        for l in 0..F::LANES {
            if chunk[l] > lanes[l] {
                lanes[l] = chunk[l];
            }
        }
    }
}

/// Adds `terms[k]` to lane `k % LANES` (`terms.len()` is a multiple of `LANES`).
#[inline(always)]
fn lane_add<F: PairFloat>(lanes: &mut [F; MAX_LANES], terms: &[F]) {
    for chunk in terms.chunks_exact(F::LANES) {
        for l in 0..F::LANES {
            lanes[l] += chunk[l];
        }
    }
}

/// The lanes added in a fixed tree order, in f64: `(s0 + s1) + (s2 + s3)` for four lanes, and
/// the two halves of eight added likewise.
#[inline(always)]
fn lane_sum<F: PairFloat>(s: &[F; MAX_LANES]) -> Real {
    let v = |i: usize| s[i].to_real();
    let quad = |i: usize| (v(i) + v(i + 1)) + (v(i + 2) + v(i + 3));
    if F::LANES == 4 {
        quad(0)
    } else {
        quad(0) + quad(4)
    }
}

/// Collects the neighbours of `own` in group `G` and sums their terms. Plain loops, no
/// closures around the scan or the arithmetic: a closure would be compiled without the
/// caller's target features. (The one closure, forming a row's f64 offsets for the
/// single-precision scan, holds no vector code; a `&mut` update in its place measured 10 %
/// slower on the f64 piston flume.)
#[inline(always)]
fn gather_group<F: PairFloat, D: Dim, K: Kernel, const VISC: u8, const DIFF: u8, const T7: bool, const TENS: bool, const G: usize, const AVX2: bool>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: &Fields<'_, D>,
    own: &Own<F>,
    s: &mut Scratch<F>,
    sums: &mut Sums<F>,
) {
    if !grid.has_group(G) {
        return;
    }
    let support2 = c.support * c.support;
    let pa = f.pos[own.slot];
    // single precision: the scan on the split positions, with particle a's split height and
    // its offsets across the rows (formed per row)
    let split = if F::SINGLE {
        let Some(split) = f.split else { unreachable!("forces_in splits the positions for single precision") };
        Some(SplitRow::of(grid, split, pa, own.slot, support2))
    } else {
        None
    };
    for row in 0..s.rows.n {
        let split_row = split.map(|r| r.across(grid, s.rows.across[row]));
        let (begin, end) = grid.row_slots(G, &s.rows, row);
        let (mut j, end) = (begin as usize, end as usize);
        // Pieces that fit the batch, so the scan loop itself never flushes (no call in it: its
        // values stay in registers). The particle itself (r = 0) is let through here and
        // masked in `sum_batch`, one test fewer per candidate.
        // Measured and dropped (docs/benchmarks.md): testing the candidates four at a time with
        // a bit mask, and a separate vectorised distance pass per row; both slower than this
        // branch, which the particle lattice makes predictable.
        while j < end {
            if s.n == BATCH {
                sum_batch::<F, D, K, VISC, DIFF, T7, TENS, G>(c, kernel, f, own, s, sums);
            }
            let m = (end - j).min(BATCH - s.n);
            s.n = match split_row {
                Some(r) if F::SINGLE => scan_split::<F, D, AVX2>(&r, j, m, s),
                _ => scan_f64::<F, D, AVX2>(pa, f.pos, support2, j, m, s),
            };
            j += m;
        }
    }
    sum_batch::<F, D, K, VISC, DIFF, T7, TENS, G>(c, kernel, f, own, s, sums);
}

/// Appends the candidates at slots `j..j + m` within the support of `pa` to the batch, with
/// `r_ab` and `r_ab^2` in f64; returns the batch's new length. AVX2: four at a time, without
/// branches; otherwise one by one.
#[inline(always)]
fn scan_f64<F: PairFloat, D: Dim, const AVX2: bool>(pa: D::V, pos: &[D::V], support2: Real, j: usize, m: usize, s: &mut Scratch<F>) -> usize {
    let mut k = s.n;
    let mut done = 0;
    #[cfg(target_arch = "x86_64")]
    if AVX2 {
        let flat: &[Real] = bytemuck::cast_slice(pos);
        let mut a = [0.0; 3];
        for (d, x) in a.iter_mut().enumerate().take(D::DIM) {
            *x = pa.get(d);
        }
        // SAFETY: AVX2 is true only in `chunk_forces_avx2`, which runs where AVX2 was
        // detected; `m <= BATCH - s.n` keeps the stores within SCAN_ROOM.
        (k, done) = unsafe { x86::scan_quads(D::DIM, a, flat, j, m, support2, s, k) };
    }
    for (l, &pb) in pos[j + done..j + m].iter().enumerate() {
        let r = pa - pb;
        let r2 = r.length_squared();
        if r2 < support2 {
            s.idx[k] = (j + done + l) as u32;
            for d in 0..D::DIM {
                s.r[d][k] = r.get(d);
            }
            s.r2[k] = r2;
            k += 1;
        }
    }
    k
}

/// What the single-precision scan of one stencil row needs of particle a
/// (`split_positions.rs`): its split height, its offsets from the row's cell faces across the
/// rows, and `fl32(support^2)`. The pairs are those with `r_ab^2 < fl32(support^2)` in f32.
#[derive(Clone, Copy)]
struct SplitRow<'a> {
    split: &'a SplitPositions,
    a_hi: f32,
    a_lo: f32,
    /// Along grid axes 1 and 2, from the grid's origin (f64), then from the row's faces (f32).
    along: [Real; 2],
    a_off: [f32; 2],
    support2: f32,
}

impl<'a> SplitRow<'a> {
    #[inline(always)]
    fn of<D: Dim>(grid: &CellGrid<D>, split: &'a SplitPositions, pa: D::V, a: usize, support2: Real) -> Self {
        // the scan's grid axes 0, 1, 2 are the physical axes z, y, x (3D) or y, x (2D)
        debug_assert!((0..D::DIM).all(|k| CellGrid::<D>::physical_axis(k) == D::DIM - 1 - k));
        let along = [grid.along(pa, 1), if D::DIM == 3 { grid.along(pa, 2) } else { 0.0 }];
        Self { split, a_hi: split.hi[a], a_lo: split.lo[a], along, a_off: [0.0; 2], support2: support2 as f32 }
    }

    /// For the row at cell coordinates `across` (grid axes 1 and 2): particle a's offsets from
    /// its faces, formed in f64 and rounded once.
    #[inline(always)]
    fn across<D: Dim>(mut self, grid: &CellGrid<D>, across: [u32; 2]) -> Self {
        for k in 1..D::DIM {
            self.a_off[k - 1] = (self.along[k - 1] - grid.face(across[k - 1])) as f32;
        }
        self
    }
}

/// [`scan_f64`] on the split positions in f32, eight at a time with AVX2, `r_ab` and `r_ab^2`
/// kept in f32 for the pair terms.
#[inline(always)]
fn scan_split<F: PairFloat, D: Dim, const AVX2: bool>(r: &SplitRow<'_>, j: usize, m: usize, s: &mut Scratch<F>) -> usize {
    let (split, three) = (r.split, D::DIM == 3);
    let mut k = s.n;
    let mut done = 0;
    #[cfg(target_arch = "x86_64")]
    if AVX2 {
        // SAFETY: AVX2 is true only in `chunk_forces_avx2`, which runs where AVX2 was
        // detected; `m <= BATCH - s.n` keeps the stores within SCAN_ROOM, and the split
        // arrays hold PAD slots past every slot of the grid (asserted in `forces_in`).
        k = unsafe { x86::scan_octets(D::DIM, r.a_hi, r.a_lo, r.a_off, split, j, m, r.support2, s, k) };
        done = m;
    }
    for b in j + done..j + m {
        // the same operations in the same order as `scan_octets`
        let r0 = (r.a_hi - split.hi[b]) + (r.a_lo - split.lo[b]);
        let r1 = r.a_off[0] - split.offset[0][b];
        let (rx, ry, rz) = if three { (r.a_off[1] - split.offset[1][b], r1, r0) } else { (r1, r0, 0.0) };
        let mut r2 = rx * rx + ry * ry;
        if three {
            r2 += rz * rz;
        }
        if r2 < r.support2 {
            s.idx[k] = b as u32;
            s.rs[0][k] = rx;
            s.rs[1][k] = ry;
            s.rs[2][k] = rz;
            s.r2s[k] = r2;
            k += 1;
        }
    }
    k
}

/// Acceleration, density rate and step limits of fluid particle `a` (storage slot).
#[inline(always)]
fn particle_forces<F: PairFloat, D: Dim, K: Kernel, const VISC: u8, const DIFF: u8, const T7: bool, const TENS: bool, const AVX2: bool>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: &Fields<'_, D>,
    a: usize,
    s: &mut Scratch<F>,
) -> (D::V, Real, StepLimits) {
    let va = f.vel[a];
    let mut vel = [F::of(0.0); 3];
    for (d, v) in vel.iter_mut().enumerate().take(D::DIM) {
        *v = F::of(va.get(d));
    }
    let rho = f.rho[a];
    let p = pressure(c, rho);
    let cs = sound_speed(c, rho);
    let p_rho2 = p / (rho * rho);
    let own = Own {
        slot: a,
        vel,
        rho: F::of(rho),
        rel: F::of(rho * c.inv_rho0 - 1.0),
        p: F::of(p),
        p_rho2: F::of(p_rho2),
        sound_speed: F::of(cs),
        tens: if TENS { F::of(TensilePair::<Real>::new(&c.tensile).stress(p, p_rho2)) } else { F::of(0.0) },
    };
    let mut sums = Sums::<F>::default();
    grid.stencil_rows(f.pos[a], &mut s.rows);
    debug_assert_eq!(GROUPS, 3);
    gather_group::<F, D, K, VISC, DIFF, T7, TENS, GROUP_FIXED, AVX2>(c, kernel, grid, f, &own, s, &mut sums);
    gather_group::<F, D, K, VISC, DIFF, T7, TENS, GROUP_MOVING, AVX2>(c, kernel, grid, f, &own, s, &mut sums);
    gather_group::<F, D, K, VISC, DIFF, T7, TENS, GROUP_FLUID, AVX2>(c, kernel, grid, f, &own, s, &mut sums);

    let mut acc = D::V::ZERO;
    for d in 0..D::DIM {
        acc.set(d, lane_sum(&sums.acc[d]) * c.mass);
    }
    let vertical = D::DIM - 1;
    acc.set(vertical, acc.get(vertical) - c.gravity);
    let drho = c.mass * (lane_sum(&sums.drho) + c.delta_h_c0 * lane_sum(&sums.diff));
    let max_visc = sums.visc[..F::LANES].iter().fold(0.0 as Real, |m, &v| m.max(v.to_real()));
    let limits = StepLimits { max_acc: acc.length(), min_dt_cv: c.h / (cs + max_visc), acc_slot: a, cv_slot: a };
    (acc, drho, limits)
}

/// Forces on the fluid particles `first..first + acc.len()` (indices into the fluid range).
#[inline(always)]
fn chunk_forces<F: PairFloat, D: Dim, K: Kernel, const VISC: u8, const DIFF: u8, const T7: bool, const TENS: bool, const AVX2: bool>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: &Fields<'_, D>,
    first: usize,
    acc: &mut [D::V],
    drho: &mut [Real],
) -> StepLimits {
    let mut s = Scratch::<F>::new();
    let mut limits = StepLimits::NONE;
    for (i, (acc_a, drho_a)) in acc.iter_mut().zip(drho.iter_mut()).enumerate() {
        let a = f.fluid_start + first + i;
        if f.kind[a] == KIND_EXCLUDED {
            *acc_a = D::V::ZERO;
            *drho_a = 0.0;
            continue;
        }
        let (acc_v, drho_v, lim) = particle_forces::<F, D, K, VISC, DIFF, T7, TENS, AVX2>(c, kernel, grid, f, a, &mut s);
        *acc_a = acc_v;
        *drho_a = drho_v;
        limits = limits.merge(lim);
    }
    limits
}

/// [`chunk_forces`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2 (checked by [`fluid_forces_batched`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[allow(clippy::too_many_arguments)]
unsafe fn chunk_forces_avx2<F: PairFloat, D: Dim, K: Kernel, const VISC: u8, const DIFF: u8, const T7: bool, const TENS: bool>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: &Fields<'_, D>,
    first: usize,
    acc: &mut [D::V],
    drho: &mut [Real],
) -> StepLimits {
    chunk_forces::<F, D, K, VISC, DIFF, T7, TENS, true>(c, kernel, grid, f, first, acc, drho)
}

/// Whether the batched loop runs its AVX2 variant on this CPU.
pub fn uses_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Fluid particles per parallel task (one scratch each). The last chunks decide how long one
/// thread waits for the other at the loop's end: 128 gave the 2D dam break 1.91 times one
/// thread's speed on two against 1.88 with 256, and 64 slowed one thread (measured in ef0b49f).
const CHUNK: usize = 128;

/// Batched [`super::forces::fluid_forces_scalar`] for the artificial and laminar viscosity
/// models (the SPS closure stays on the scalar loop). Same contract: writes `acc` and `drho` of
/// the fluid range and returns the step limits. Reached from outside the crate through
/// [`super::forces::fluid_forces`] only.
///
/// # Panics
/// If the grid's slots or the fluid range do not lie within `f.pos`, or a field array is
/// shorter than `f.pos` (checked once per call: the gather reads without bounds checks).
pub(crate) fn fluid_forces_batched<D: Dim, K: Kernel, const VISC: u8, const DIFF: u8>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: Fields<'_, D>,
    acc: &mut [D::V],
    drho: &mut [Real],
) -> StepLimits {
    fluid_forces_variant::<D, K, VISC, DIFF>(c, kernel, grid, f, acc, drho, uses_avx2())
}

/// [`fluid_forces_batched`] with the variant chosen by the caller: `avx2` must be false where
/// [`uses_avx2`] is (tests compare the two variants' bits).
pub(crate) fn fluid_forces_variant<D: Dim, K: Kernel, const VISC: u8, const DIFF: u8>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: Fields<'_, D>,
    acc: &mut [D::V],
    drho: &mut [Real],
    avx2: bool,
) -> StepLimits {
    forces_in::<f32, f64, D, K, VISC, DIFF>(c, kernel, grid, f, acc, drho, avx2)
}

/// [`fluid_forces_variant`] with `S` and `W` for the single- and double-precision pair float
/// types (f32 and f64; the counting types of `flop_count.rs` for the roofline).
#[allow(clippy::too_many_arguments)]
fn forces_in<S: PairFloat, W: PairFloat, D: Dim, K: Kernel, const VISC: u8, const DIFF: u8>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: Fields<'_, D>,
    acc: &mut [D::V],
    drho: &mut [Real],
    avx2: bool,
) -> StepLimits {
    assert!(VISC != VISC_LAMINAR_SPS, "the SPS closure uses fluid_forces_scalar");
    assert!(!avx2 || uses_avx2(), "the AVX2 variant needs a CPU with AVX2");
    // What the unchecked gather and the AVX2 scan's loads rely on, checked here once per call
    // instead of once per pair: every slot the grid hands out indexes the position array, the
    // fields are as long as it, and the fluid range lies within it.
    let n = f.pos.len();
    assert!(
        grid.slot_end() <= n && f.vel.len() >= n && f.rho.len() >= n && f.kind.len() >= n,
        "fluid forces: the grid's {} slots and the fields ({} velocities, {} densities, {} kinds) must cover the {n} positions",
        grid.slot_end(),
        f.vel.len(),
        f.rho.len(),
        f.kind.len()
    );
    assert!(
        acc.len() == drho.len() && f.fluid_start + acc.len() <= n,
        "fluid forces: {} accelerations and {} density rates from slot {} must lie within the {n} positions",
        acc.len(),
        drho.len(),
        f.fluid_start
    );
    // The single-precision scan reads the split positions: the caller's, or its own.
    let own_split;
    let mut f = f;
    if c.pair_f32 && DIFF != DIFF_RIEMANN {
        if f.split.is_none() {
            let mut split = SplitPositions::default();
            split.update(grid, f.pos);
            own_split = split;
            f.split = Some(&own_split);
        }
        let covered = f.split.is_some_and(|s| s.covers(D::DIM, n));
        assert!(covered, "fluid forces: the split positions must cover the {n} positions");
    }
    macro_rules! for_precision {
        ($tens:expr) => {
            match (c.pair_f32, seventh_power(c)) {
                (false, true) => forces_for_gamma::<W, D, K, VISC, DIFF, true, { $tens }>(c, kernel, grid, f, acc, drho, avx2),
                (false, false) => forces_for_gamma::<W, D, K, VISC, DIFF, false, { $tens }>(c, kernel, grid, f, acc, drho, avx2),
                (true, true) => forces_for_gamma::<S, D, K, VISC, DIFF, true, { $tens }>(c, kernel, grid, f, acc, drho, avx2),
                (true, false) => forces_for_gamma::<S, D, K, VISC, DIFF, false, { $tens }>(c, kernel, grid, f, acc, drho, avx2),
            }
        };
    }
    // The Riemann solver: f64 pair terms and no tensile correction (the scene's check refuses
    // both), so it compiles two loops per kernel, not eight.
    if const { DIFF == DIFF_RIEMANN } {
        return if seventh_power(c) {
            forces_for_gamma::<W, D, K, VISC, DIFF, true, false>(c, kernel, grid, f, acc, drho, avx2)
        } else {
            forces_for_gamma::<W, D, K, VISC, DIFF, false, false>(c, kernel, grid, f, acc, drho, avx2)
        };
    }
    // The tensile correction (`tensile.rs`), the kernel's constant first: a kernel without the
    // correction compiles no loop with it.
    if const { tensile::corrects(K::KIND) } && c.tensile.on {
        for_precision!(true)
    } else {
        for_precision!(false)
    }
}

/// [`fluid_forces_batched`] with pair floats that count their operations (`flop_count.rs`):
/// the same pairs, batches, padding and arithmetic as the loop a scene runs. The portable
/// variant; the AVX2 one does the same operations in the same order.
#[cfg(feature = "flop-count")]
pub(crate) fn fluid_forces_counted<D: Dim, K: Kernel, const VISC: u8, const DIFF: u8>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: Fields<'_, D>,
    acc: &mut [D::V],
    drho: &mut [Real],
) -> StepLimits {
    use super::flop_count::Counted;
    forces_in::<Counted<f32>, Counted<f64>, D, K, VISC, DIFF>(c, kernel, grid, f, acc, drho, false)
}

/// [`fluid_forces_variant`] with the pair float type `F`, `T7` = "gamma is 7" and the tensile
/// correction `TENS` fixed at compile time.
fn forces_for_gamma<F: PairFloat, D: Dim, K: Kernel, const VISC: u8, const DIFF: u8, const T7: bool, const TENS: bool>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: Fields<'_, D>,
    acc: &mut [D::V],
    drho: &mut [Real],
    avx2: bool,
) -> StepLimits {
    // each thread keeps about the same fluid slots from step to step (see for_each_chunk)
    let (acc, drho) = (Chunks::new(acc, CHUNK), Chunks::new(drho, CHUNK));
    for_each_chunk(
        acc.count(),
        || StepLimits::NONE,
        |ci| {
            // SAFETY: for_each_chunk hands each chunk index to one task
            let (acc_c, drho_c) = unsafe { (acc.get(ci), drho.get(ci)) };
            let first = ci * CHUNK;
            #[cfg(target_arch = "x86_64")]
            if avx2 {
                // SAFETY: `avx2` is true only where AVX2 was detected (asserted above).
                return unsafe { chunk_forces_avx2::<F, D, K, VISC, DIFF, T7, TENS>(c, kernel, grid, &f, first, acc_c, drho_c) };
            }
            let _ = avx2;
            chunk_forces::<F, D, K, VISC, DIFF, T7, TENS, false>(c, kernel, grid, &f, first, acc_c, drho_c)
        },
        StepLimits::merge,
    )
}

/// The candidate scan with AVX2 intrinsics.
#[cfg(target_arch = "x86_64")]
mod x86 {
    use std::arch::x86_64::*;

    use super::{PairFloat, Real, Scratch};
    use crate::physics::split_positions::SplitPositions;

    /// Compress table of the f32 scan: for each 8-bit mask of candidates inside the support,
    /// their lanes (which are their offsets from the octet's first slot) in order, and their
    /// count. A static, not a const: one 8 KB copy for every loop that uses it.
    struct Octets {
        lanes: [[i32; 8]; 256],
        counts: [u8; 256],
    }

    const fn octet_tables() -> Octets {
        let mut t = Octets { lanes: [[0; 8]; 256], counts: [0; 256] };
        let mut bits = 0;
        while bits < 256 {
            let (mut n, mut lane) = (0, 0);
            while lane < 8 {
                if bits & (1 << lane) != 0 {
                    t.lanes[bits][n] = lane;
                    n += 1;
                }
                lane += 1;
            }
            t.counts[bits] = n as u8;
            bits += 1;
        }
        t
    }

    static OCTETS: Octets = octet_tables();

    /// `(a_hi - hi[slot..slot + 8]) + (a_lo - lo[slot..slot + 8])`. A function, not a closure:
    /// closures do not inherit target features.
    ///
    /// # Safety
    /// AVX2; `slot + 8 <= hi.len().min(lo.len())`.
    #[target_feature(enable = "avx2")]
    #[inline]
    unsafe fn height_difference(a_hi: f32, a_lo: f32, hi: &[f32], lo: &[f32], slot: usize) -> __m256 {
        // SAFETY: by the contract
        let (hb, lb) = unsafe { (_mm256_loadu_ps(hi.as_ptr().add(slot)), _mm256_loadu_ps(lo.as_ptr().add(slot))) };
        _mm256_add_ps(_mm256_sub_ps(_mm256_set1_ps(a_hi), hb), _mm256_sub_ps(_mm256_set1_ps(a_lo), lb))
    }

    /// `a_off - offset[slot..slot + 8]`.
    ///
    /// # Safety
    /// AVX2; `slot + 8 <= offset.len()`.
    #[target_feature(enable = "avx2")]
    #[inline]
    unsafe fn offset_difference(a_off: f32, offset: &[f32], slot: usize) -> __m256 {
        // SAFETY: by the contract
        _mm256_sub_ps(_mm256_set1_ps(a_off), unsafe { _mm256_loadu_ps(offset.as_ptr().add(slot)) })
    }

    /// Tests the candidates at slots `first..first + m` eight at a time on the split positions
    /// and appends those inside the support to the batch at `k`, in candidate order, with the
    /// portable scan's operations in its order (see `gather_group_split`; `r^2 = (x^2 + y^2) +
    /// z^2` without fused multiply-add, `<`): the same pairs and the same bits. A last,
    /// partial octet is read whole (the arrays hold PAD slots past the last particle) and
    /// masked. Returns the new batch length. `dim`: 2 or 3, a constant after inlining.
    ///
    /// # Safety
    /// The CPU must support AVX2; `k + m + 7` must not exceed the scratch arrays' SCAN_ROOM;
    /// the split arrays must hold `first + m + 7` slots.
    #[target_feature(enable = "avx2")]
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub(super) unsafe fn scan_octets<F: PairFloat>(
        dim: usize,
        a_hi: f32,
        a_lo: f32,
        a_off: [f32; 2],
        split: &SplitPositions,
        first: usize,
        m: usize,
        support2: f32,
        s: &mut Scratch<F>,
        mut k: usize,
    ) -> usize {
        let limit = _mm256_set1_ps(support2);
        debug_assert!(split.hi.len() >= first + m.div_ceil(8) * 8);
        for o in 0..m.div_ceil(8) {
            let slot = first + 8 * o;
            // SAFETY (the differences): within the split arrays by the caller's contract
            let r0 = unsafe { height_difference(a_hi, a_lo, &split.hi, &split.lo, slot) };
            let r1 = unsafe { offset_difference(a_off[0], &split.offset[0], slot) };
            let (rx, ry, rz) = if dim == 3 {
                (unsafe { offset_difference(a_off[1], &split.offset[1], slot) }, r1, r0)
            } else {
                (r1, r0, _mm256_setzero_ps())
            };
            let mut r2 = _mm256_add_ps(_mm256_mul_ps(rx, rx), _mm256_mul_ps(ry, ry));
            if dim == 3 {
                r2 = _mm256_add_ps(r2, _mm256_mul_ps(rz, rz));
            }
            let left = m - 8 * o;
            let valid = if left >= 8 { 0xff } else { (1 << left) - 1 };
            let bits = (_mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LT_OQ>(r2, limit)) & valid) as usize;
            // SAFETY: the stores stay within SCAN_ROOM by the caller's contract
            unsafe {
                let lanes = _mm256_loadu_si256(OCTETS.lanes[bits].as_ptr().cast());
                _mm256_storeu_ps(s.rs[0].as_mut_ptr().add(k), _mm256_permutevar8x32_ps(rx, lanes));
                _mm256_storeu_ps(s.rs[1].as_mut_ptr().add(k), _mm256_permutevar8x32_ps(ry, lanes));
                if dim == 3 {
                    _mm256_storeu_ps(s.rs[2].as_mut_ptr().add(k), _mm256_permutevar8x32_ps(rz, lanes));
                }
                _mm256_storeu_ps(s.r2s.as_mut_ptr().add(k), _mm256_permutevar8x32_ps(r2, lanes));
                let idx = _mm256_add_epi32(_mm256_set1_epi32(slot as i32), lanes);
                _mm256_storeu_si256(s.idx.as_mut_ptr().add(k).cast(), idx);
            }
            k += OCTETS.counts[bits] as usize;
        }
        k
    }

    /// Compress tables for one lane order: for each 4-bit mask of lanes inside the support, the
    /// 32-bit source indices that move the passing lanes' f64 values to the front in candidate
    /// order, the candidates' offsets (for the neighbour indices) and their count; and, for
    /// 0..=4 valid candidates, the mask of their lanes.
    struct Tables {
        lanes: [[i32; 8]; 16],
        offsets: [[i32; 4]; 16],
        counts: [usize; 16],
        valid: [i32; 5],
    }

    /// `lane_of[c]`: the lane that holds candidate `c` after the loads and shuffles.
    const fn tables(lane_of: [usize; 4]) -> Tables {
        let mut t = Tables { lanes: [[0; 8]; 16], offsets: [[0; 4]; 16], counts: [0; 16], valid: [0; 5] };
        let mut bits = 0;
        while bits < 16 {
            let mut n = 0;
            let mut c = 0;
            while c < 4 {
                let lane = lane_of[c];
                if bits & (1 << lane) != 0 {
                    t.lanes[bits][2 * n] = 2 * lane as i32;
                    t.lanes[bits][2 * n + 1] = 2 * lane as i32 + 1;
                    t.offsets[bits][n] = c as i32;
                    n += 1;
                }
                c += 1;
            }
            t.counts[bits] = n;
            bits += 1;
        }
        let mut v = 1;
        while v <= 4 {
            t.valid[v] = t.valid[v - 1] | (1 << lane_of[v - 1]);
            v += 1;
        }
        t
    }
    /// 2D: `unpacklo/unpackhi` of `[x0 y0 | x1 y1]` and `[x2 y2 | x3 y3]` hold the candidates in
    /// the lane order 0, 2, 1, 3. 3D: the shuffles keep the natural order.
    const TABLES_2D: Tables = tables([0, 2, 1, 3]);
    const TABLES_3D: Tables = tables([0, 1, 2, 3]);

    /// Moves the f64 lanes of `v` as `perm` (pairs of 32-bit indices) says. A function, not a
    /// closure: closures do not inherit target features.
    #[target_feature(enable = "avx2")]
    #[inline]
    fn compress(v: __m256d, perm: __m256i) -> __m256d {
        _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(v), perm))
    }

    /// Tests the candidates at slots `first..first + m` four at a time against the support and
    /// appends those inside to the batch at `k`, in candidate order, exactly as the scalar scan
    /// does (the same `r = pa - pb`, the same `(x^2 + y^2) + z^2` without fused multiply-add,
    /// the same `<`): the same pairs and the same bits. A last, partial quad reads the
    /// positions that follow (when the array has them) and masks them off. Returns the new batch
    /// length and the number of candidates scanned; the caller scans the rest one by one.
    /// `pos` is the flat position array (`dim` values per particle, 2 or 3: a constant after
    /// inlining).
    ///
    /// # Safety
    /// The CPU must support AVX2; `k + m + 3` must not exceed the scratch arrays' SCAN_ROOM
    /// (the stores write four entries at a time).
    #[target_feature(enable = "avx2")]
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub(super) unsafe fn scan_quads<F: PairFloat>(
        dim: usize,
        pa: [Real; 3],
        pos: &[Real],
        first: usize,
        m: usize,
        support2: Real,
        s: &mut Scratch<F>,
        mut k: usize,
    ) -> (usize, usize) {
        let t = if dim == 2 { &TABLES_2D } else { &TABLES_3D };
        let n_slots = pos.len() / dim;
        // quads that may be read whole: a partial last one needs the slots after the row
        let quads = if first + m.div_ceil(4) * 4 <= n_slots { m.div_ceil(4) } else { m / 4 };
        debug_assert!(k + 4 * quads <= s.idx.len());
        let (ax, ay, az) = (_mm256_set1_pd(pa[0]), _mm256_set1_pd(pa[1]), _mm256_set1_pd(pa[2]));
        let limit = _mm256_set1_pd(support2);
        for q in 0..quads {
            let slot = first + 4 * q;
            // SAFETY (every pointer access): slot + 4 <= n_slots as checked above, and the
            // stores stay within SCAN_ROOM by the caller's contract.
            unsafe {
                let p = pos.as_ptr().add(dim * slot);
                let (rx, ry, rz) = if dim == 2 {
                    let a = _mm256_loadu_pd(p); // x0 y0 | x1 y1
                    let b = _mm256_loadu_pd(p.add(4)); // x2 y2 | x3 y3
                    // lanes: candidates 0 2 | 1 3
                    (_mm256_sub_pd(ax, _mm256_unpacklo_pd(a, b)), _mm256_sub_pd(ay, _mm256_unpackhi_pd(a, b)), az)
                } else {
                    // x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3, reloaded as 128-bit halves:
                    let xy02 = _mm256_loadu2_m128d(p.add(6), p); // x0 y0 | x2 y2
                    let zx = _mm256_loadu2_m128d(p.add(8), p.add(2)); // z0 x1 | z2 x3
                    let yz = _mm256_loadu2_m128d(p.add(10), p.add(4)); // y1 z1 | y3 z3
                    let x = _mm256_shuffle_pd::<0b1010>(xy02, zx);
                    let y = _mm256_shuffle_pd::<0b0101>(xy02, yz);
                    let z = _mm256_shuffle_pd::<0b1010>(zx, yz);
                    (_mm256_sub_pd(ax, x), _mm256_sub_pd(ay, y), _mm256_sub_pd(az, z))
                };
                let mut r2 = _mm256_add_pd(_mm256_mul_pd(rx, rx), _mm256_mul_pd(ry, ry));
                if dim == 3 {
                    r2 = _mm256_add_pd(r2, _mm256_mul_pd(rz, rz));
                }
                let inside = _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(r2, limit));
                let bits = (inside & t.valid[(m - 4 * q).min(4)]) as usize;
                let perm = _mm256_loadu_si256(t.lanes[bits].as_ptr().cast());
                _mm256_storeu_pd(s.r[0].as_mut_ptr().add(k), compress(rx, perm));
                _mm256_storeu_pd(s.r[1].as_mut_ptr().add(k), compress(ry, perm));
                if dim == 3 {
                    _mm256_storeu_pd(s.r[2].as_mut_ptr().add(k), compress(rz, perm));
                }
                _mm256_storeu_pd(s.r2.as_mut_ptr().add(k), compress(r2, perm));
                let idx = _mm_add_epi32(_mm_set1_epi32(slot as i32), _mm_loadu_si128(t.offsets[bits].as_ptr().cast()));
                _mm_storeu_si128(s.idx.as_mut_ptr().add(k).cast(), idx);
                k += t.counts[bits];
            }
        }
        (k, (4 * quads).min(m))
    }
}
