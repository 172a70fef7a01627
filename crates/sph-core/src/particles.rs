//! Structure-of-arrays particle state.
//!
//! Storage order: fixed boundary `[0, n_fixed)`, moving boundary `[n_fixed, fluid_start)`, fluid
//! `[fluid_start, n)`. Groups never mix; within a group particles are sorted by cell (see
//! `neighbours.rs`), so `id` maps a storage slot back to the particle's creation order.
//! Arrays are allocated once per run and never reallocated: Python reads them as NumPy views.

use crate::math::{Dim, Real, Vector};

/// Particle kind codes, as exposed to Python.
pub const KIND_FLUID: u8 = 0;
pub const KIND_FIXED: u8 = 1;
pub const KIND_MOVING: u8 = 2;
/// A fluid particle that left the domain: frozen and left out of the physics.
pub const KIND_EXCLUDED: u8 = 3;

#[derive(Debug, Clone)]
pub struct Particles<D: Dim> {
    pub pos: Vec<D::V>,
    pub vel: Vec<D::V>,
    /// Density; pressure is not stored (16 bytes per particle saved with `P / rho^2`): the
    /// force loops compute it from `rho` where they read it.
    pub rho: Vec<Real>,
    /// Creation order of the particle in each storage slot.
    pub id: Vec<u32>,
    /// Kind of each slot (fluid slots turn `KIND_EXCLUDED` when their particle leaves the domain).
    pub kind: Vec<u8>,
    /// Acceleration of fluid particles (indexed from `fluid_start`).
    pub acc: Vec<D::V>,
    /// Density rate of every particle.
    pub drho: Vec<Real>,
    pub n_fixed: usize,
    pub n_moving: usize,
}

impl<D: Dim> Particles<D> {
    pub fn len(&self) -> usize {
        self.pos.len()
    }
    pub fn is_empty(&self) -> bool {
        self.pos.is_empty()
    }
    pub fn fluid_start(&self) -> usize {
        self.n_fixed + self.n_moving
    }
    pub fn n_fluid(&self) -> usize {
        self.len() - self.fluid_start()
    }

    /// Bytes held by the arrays (capacity based).
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        let v = size_of::<D::V>();
        (self.pos.capacity() + self.vel.capacity() + self.acc.capacity()) * v
            + (self.rho.capacity() + self.drho.capacity()) * size_of::<Real>()
            + self.id.capacity() * size_of::<u32>()
            + self.kind.capacity()
    }
}

/// Slots per block of a permutation's dirty map ([`mark_moved_blocks`]): small enough that
/// a particle crossing into the next cell dirties little, large enough for a memcpy.
pub const PERMUTE_BLOCK: usize = 128;

/// A block's entry in the rank map of [`mark_moved_blocks`] when the permutation leaves it alone.
pub const NOT_MOVED: u32 = u32::MAX;

/// Ranks in `ranks` (one entry per [`PERMUTE_BLOCK`] slots of `perm`) the blocks where `perm`
/// (new slot - `start` -> old absolute index) moves a particle, in slot order, and lists them in
/// `moved` (cleared first); the other blocks get [`NOT_MOVED`]. Returns how many moved. The
/// cell sort of a flow that moved for one step is nearly the identity (the piston bench case
/// after 2,000 steps: 31-59 of 89 blocks of 256 slots change in a step of two sorts; at the
/// start of a run none), so [`permute_carried`] copies only those: less memory traffic, and
/// fewer cache lines handed between cores.
///
/// Serial: a compare per slot (4 bytes read), which one core does in less time than a
/// fork-join of two threads takes. 2D dam break, 21,000 fluid particles: 2.4-2.8 us per sort
/// on one or two threads; the parallel loop it replaces took 11-12 us on one and 25-28 us on
/// two (phase timers, see [`crate::phases`]).
pub fn mark_moved_blocks(perm: &[u32], start: usize, ranks: &mut [u32], moved: &mut Vec<u32>) -> usize {
    let ranks = &mut ranks[..perm.len().div_ceil(PERMUTE_BLOCK)];
    moved.clear();
    for (b, (r, block)) in ranks.iter_mut().zip(perm.chunks(PERMUTE_BLOCK)).enumerate() {
        let first = (start + b * PERMUTE_BLOCK) as u32;
        // a fold without early exit, so that the compare vectorises
        let changed = block.iter().zip(first..).fold(false, |any, (&old, slot)| any | (old != slot));
        *r = if changed { moved.len() as u32 } else { NOT_MOVED };
        if changed {
            moved.push(b as u32);
        }
    }
    moved.len()
}

/// `buf[s] = value(perm[s])` for the slots `s` of the blocks `ranks` marks.
fn gather_moved<B: Send>(buf: &mut [B], perm: &[u32], ranks: &[u32], value: impl Fn(usize) -> B + Sync) {
    use rayon::prelude::*;
    buf.par_chunks_mut(PERMUTE_BLOCK).zip(perm.par_chunks(PERMUTE_BLOCK)).zip(ranks.par_iter()).for_each(
        |((dst, block), &rank)| {
            if rank != NOT_MOVED {
                for (d, &old) in dst.iter_mut().zip(block) {
                    *d = value(old as usize);
                }
            }
        },
    );
}

/// `put(&mut data[s], buf[s])` for the slots `s` of the blocks `ranks` marks.
fn put_moved<T: Send, B: Copy + Sync>(data: &mut [T], buf: &[B], ranks: &[u32], put: impl Fn(&mut T, B) + Sync) {
    use rayon::prelude::*;
    data.par_chunks_mut(PERMUTE_BLOCK).zip(buf.par_chunks(PERMUTE_BLOCK)).zip(ranks.par_iter()).for_each(
        |((dst, b), &rank)| {
            if rank != NOT_MOVED {
                for (d, &x) in dst.iter_mut().zip(b) {
                    put(d, x);
                }
            }
        },
    );
}

/// Applies `perm` (new slot -> old absolute index) to `data[range]` in the blocks `ranks`
/// marks ([`mark_moved_blocks`]; the others are the identity), gathering through `scratch`:
/// one 8-byte-per-particle buffer serves every array (reinterpreted as `T`), so sorting costs
/// 8 bytes per particle rather than one vector per type. `T` must be at most 8 bytes wide;
/// vectors go through [`permute_vectors`].
fn permute<T: bytemuck::Pod + Send + Sync>(
    data: &mut [T],
    range: std::ops::Range<usize>,
    perm: &[u32],
    ranks: &[u32],
    scratch: &mut [u64],
) {
    let n = range.len();
    let buf = &mut bytemuck::cast_slice_mut::<u64, T>(scratch)[..n];
    let src = &*data;
    gather_moved(buf, &perm[..n], ranks, |old| src[old]);
    put_moved(&mut data[range], buf, ranks, |d, x| *d = x);
}

/// [`permute`] for vectors: whole vectors where `scratch` holds `dim` words per slot of
/// `range`, else one component at a time through 8 bytes per slot.
fn permute_vectors<V: Vector>(
    data: &mut [V],
    range: std::ops::Range<usize>,
    perm: &[u32],
    ranks: &[u32],
    scratch: &mut [u64],
) {
    let n = range.len();
    let dim = std::mem::size_of::<V>() / std::mem::size_of::<Real>();
    if scratch.len() >= n * dim {
        // The whole vector per pass where the buffer holds it (the fluid's accelerations, which
        // the fluid sort lends): `dim` times fewer fork-joins and passes over the vectors.
        return permute(data, range, perm, ranks, &mut scratch[..n * dim]);
    }
    let buf = &mut bytemuck::cast_slice_mut::<u64, Real>(scratch)[..n];
    for k in 0..dim {
        let src = &*data;
        gather_moved(buf, &perm[..n], ranks, |old| src[old].get(k));
        put_moved(&mut data[range.clone()], buf, ranks, |v, x| v.set(k, x));
    }
}

/// `dst[s] = src[olds[s]]`: one block's slots of one array, gathered into its record.
fn gather_block<T: Copy>(dst: &mut [T], olds: &[u32], src: &[T]) {
    dst.iter_mut().zip(olds).for_each(|(d, &old)| *d = src[old as usize]);
}

/// Every per-particle array a cell sort carries along, for [`permute_carried`]: position,
/// velocity and the integrator's history velocity; density and history density; id; kind.
pub struct Carried<'a, V> {
    pub vectors: [&'a mut [V]; 3],
    pub reals: [&'a mut [Real]; 2],
    pub id: &'a mut [u32],
    pub kind: &'a mut [u8],
}

/// Where one moved block's slots of each carried array lie in its record of `u64` words in
/// [`permute_carried`]'s buffer: the three vector arrays, the two real arrays, the ids, the
/// kinds. `PERMUTE_BLOCK` is a multiple of 8, so every section starts on a word.
struct Record {
    real: usize,
    id: usize,
    kind: usize,
    words: usize,
}

impl Record {
    fn new(dim: usize) -> Self {
        let b = PERMUTE_BLOCK;
        // the vectors from word 0
        let real = 3 * b * dim;
        let id = real + 2 * b;
        let kind = id + b / 2;
        Record { real, id, kind, words: kind + b / 8 }
    }
}

/// Applies `perm` (new slot -> old absolute index) to all carried arrays in `range`, in the
/// blocks `ranks` marks (`moved` lists them; see [`mark_moved_blocks`]), in two parallel loops:
/// one gathers each moved block's slots of all seven arrays into its record in `scratch`, the
/// other copies the records back. Array by array ([`permute`]) that is fourteen fork-joins,
/// each a wake-up of the other threads for a loop of a few microseconds: in the 2D dam break
/// on two threads the permutation took longer than on one (phase timers).
/// Where `scratch` cannot hold every moved block's record (many particles changed cell, e.g.
/// at a first sort), it permutes array by array through `scratch` instead.
pub fn permute_carried<V: Vector>(
    arrays: Carried<'_, V>,
    range: std::ops::Range<usize>,
    perm: &[u32],
    ranks: &[u32],
    moved: &[u32],
    scratch: &mut [u64],
) {
    use rayon::prelude::*;
    let Carried { vectors: [pos, vel, hist_v], reals: [rho, hist_r], id, kind } = arrays;
    let dim = std::mem::size_of::<V>() / std::mem::size_of::<Real>();
    let rec = Record::new(dim);
    if scratch.len() < moved.len() * rec.words {
        for v in [pos, vel, hist_v] {
            permute_vectors(v, range.clone(), perm, ranks, scratch);
        }
        for r in [rho, hist_r] {
            permute(r, range.clone(), perm, ranks, scratch);
        }
        permute(id, range.clone(), perm, ranks, scratch);
        permute(kind, range, perm, ranks, scratch);
        return;
    }
    let b = PERMUTE_BLOCK;
    let perm = &perm[..range.len()];
    let (vectors, reals) = ([&*pos, &*vel, &*hist_v], [&*rho, &*hist_r]);
    let records = &mut scratch[..moved.len() * rec.words];
    records.par_chunks_mut(rec.words).zip(moved.par_iter()).for_each(|(words, &block)| {
        let olds = &perm[block as usize * b..((block as usize + 1) * b).min(perm.len())];
        let (vs, rest) = words.split_at_mut(rec.real);
        let (rs, rest) = rest.split_at_mut(rec.id - rec.real);
        let (is, ks) = rest.split_at_mut(rec.kind - rec.id);
        let vs = bytemuck::cast_slice_mut::<u64, V>(vs);
        let rs = bytemuck::cast_slice_mut::<u64, Real>(rs);
        vs.chunks_mut(b).zip(vectors).for_each(|(dst, src)| gather_block(dst, olds, src));
        rs.chunks_mut(b).zip(reals).for_each(|(dst, src)| gather_block(dst, olds, src));
        gather_block(bytemuck::cast_slice_mut(is), olds, id);
        gather_block(bytemuck::cast_slice_mut(ks), olds, kind);
    });
    let records = &*records;
    (
        pos[range.clone()].par_chunks_mut(b),
        vel[range.clone()].par_chunks_mut(b),
        hist_v[range.clone()].par_chunks_mut(b),
        rho[range.clone()].par_chunks_mut(b),
        hist_r[range.clone()].par_chunks_mut(b),
        id[range.clone()].par_chunks_mut(b),
        kind[range].par_chunks_mut(b),
        ranks.par_iter(),
    )
        .into_par_iter()
        .for_each(|(x, v, hv, rho, hr, id, kind, &rank)| {
            if rank == NOT_MOVED {
                return;
            }
            let words = &records[rank as usize * rec.words..(rank as usize + 1) * rec.words];
            let n = x.len();
            let vs = bytemuck::cast_slice::<u64, V>(&words[..rec.real]);
            let rs = bytemuck::cast_slice::<u64, Real>(&words[rec.real..rec.id]);
            for (k, dst) in [x, v, hv].into_iter().enumerate() {
                dst.copy_from_slice(&vs[k * b..k * b + n]);
            }
            for (k, dst) in [rho, hr].into_iter().enumerate() {
                dst.copy_from_slice(&rs[k * b..k * b + n]);
            }
            id.copy_from_slice(&bytemuck::cast_slice::<u64, u32>(&words[rec.id..rec.kind])[..n]);
            kind.copy_from_slice(&bytemuck::cast_slice::<u64, u8>(&words[rec.kind..])[..n]);
        });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `perm` over `start..start + n` with block 0 reversed and two slots of the last (partial)
    /// block swapped; the blocks between stay.
    fn two_blocks_changed(start: usize, n: usize) -> Vec<u32> {
        let mut perm: Vec<u32> = (start..start + n).map(|i| i as u32).collect();
        perm[..PERMUTE_BLOCK].reverse();
        perm.swap(n - 1, n - 3);
        perm
    }

    fn permuted<T: Copy>(data: &[T], start: usize, perm: &[u32]) -> Vec<T> {
        data[..start].iter().copied().chain(perm.iter().map(|&old| data[old as usize])).collect()
    }

    #[test]
    fn vectors_permute_alike_through_a_small_and_a_large_buffer() {
        use glam::DVec3;
        let (start, n) = (5usize, 2 * PERMUTE_BLOCK + 17);
        let data: Vec<DVec3> = (0..start + n).map(|i| DVec3::new(i as f64, -(i as f64), 0.5 * i as f64)).collect();
        let perm = two_blocks_changed(start, n);
        let (mut ranks, mut moved) = (vec![0; n.div_ceil(PERMUTE_BLOCK)], Vec::new());
        assert_eq!(mark_moved_blocks(&perm, start, &mut ranks, &mut moved), 2);
        let expect = permuted(&data, start, &perm);
        for words in [n, 3 * n] {
            let mut permuted = data.clone();
            permute_vectors(&mut permuted, start..start + n, &perm, &ranks, &mut vec![0u64; words]);
            assert_eq!(permuted, expect, "{words} words of scratch");
        }
    }

    #[test]
    fn carried_arrays_permute_together_as_each_alone() {
        use glam::DVec2;
        let (start, n) = (9usize, 3 * PERMUTE_BLOCK + 40);
        let all = start + n;
        let vector = |k: f64| (0..all).map(|i| DVec2::new(i as f64 + k, k - i as f64)).collect::<Vec<_>>();
        let real = |k: f64| (0..all).map(|i| k * 1e3 + i as f64).collect::<Vec<_>>();
        let id: Vec<u32> = (0..all as u32).map(|i| i * 7 + 1).collect();
        let kind: Vec<u8> = (0..all).map(|i| (i % 251) as u8).collect();
        let perm = two_blocks_changed(start, n);
        let (mut ranks, mut moved) = (vec![0; n.div_ceil(PERMUTE_BLOCK)], Vec::new());
        assert_eq!(mark_moved_blocks(&perm, start, &mut ranks, &mut moved), 2);
        let record = Record::new(2).words;
        // too small for two records: array by array; then exactly two records: all at once
        for words in [n, 2 * record] {
            let (mut v, mut r) = ([vector(0.0), vector(0.25), vector(0.5)], [real(1.0), real(2.0)]);
            let (mut i, mut k) = (id.clone(), kind.clone());
            let [v0, v1, v2] = &mut v;
            let [r0, r1] = &mut r;
            let arrays = Carried { vectors: [v0, v1, v2], reals: [r0, r1], id: &mut i, kind: &mut k };
            permute_carried(arrays, start..all, &perm, &ranks, &moved, &mut vec![0u64; words]);
            for (got, k) in v.iter().zip([0.0, 0.25, 0.5]) {
                assert_eq!(*got, permuted(&vector(k), start, &perm), "vectors, {words} words");
            }
            for (got, k) in r.iter().zip([1.0, 2.0]) {
                assert_eq!(*got, permuted(&real(k), start, &perm), "reals, {words} words");
            }
            assert_eq!(i, permuted(&id, start, &perm), "ids, {words} words");
            assert_eq!(k, permuted(&kind, start, &perm), "kinds, {words} words");
        }
    }

    #[test]
    fn marks_exactly_the_blocks_a_permutation_changes() {
        let (start, n) = (7usize, 3 * PERMUTE_BLOCK + 5);
        let identity: Vec<u32> = (start..start + n).map(|i| i as u32).collect();
        let (mut ranks, mut moved) = (vec![0; n.div_ceil(PERMUTE_BLOCK)], vec![9]);
        assert_eq!(mark_moved_blocks(&identity, start, &mut ranks, &mut moved), 0);
        assert!(ranks.iter().all(|&r| r == NOT_MOVED) && moved.is_empty());
        // two slots swapped inside block 1, and the last slot of the partial block 3 changed
        let mut perm = identity.clone();
        perm.swap(PERMUTE_BLOCK + 3, PERMUTE_BLOCK + 90);
        perm.swap(n - 1, 0);
        assert_eq!(mark_moved_blocks(&perm, start, &mut ranks, &mut moved), 3);
        assert_eq!(ranks, vec![0, 1, NOT_MOVED, 2]);
        assert_eq!(moved, vec![0, 1, 3]);
    }
}
