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

/// Marks in `moved` (one flag per [`PERMUTE_BLOCK`] slots of `perm`) the blocks where `perm`
/// (new slot - `start` -> old absolute index) moves a particle; returns how many. The cell sort
/// of a flow that moved for one step is nearly the identity (the piston bench case after 2,000
/// steps: 31-59 of 89 blocks of 256 slots change in a step of two sorts; at the start of a run
/// none), so [`permute`] copies only those: less memory traffic, and fewer cache lines handed
/// between cores.
///
/// Serial: a compare per slot (4 bytes read), which one core does in less time than a
/// fork-join of two threads takes. 2D dam break, 21,000 fluid particles: 2.4-2.8 us per sort
/// on one or two threads; the parallel loop it replaces took 11-12 us on one and 25-28 us on
/// two (docs/benchmarks.md, Session 11).
pub fn mark_moved_blocks(perm: &[u32], start: usize, moved: &mut [bool]) -> usize {
    let moved = &mut moved[..perm.len().div_ceil(PERMUTE_BLOCK)];
    let mut count = 0;
    for (b, (m, block)) in moved.iter_mut().zip(perm.chunks(PERMUTE_BLOCK)).enumerate() {
        let first = (start + b * PERMUTE_BLOCK) as u32;
        // a fold without early exit, so that the compare vectorises
        *m = block.iter().zip(first..).fold(false, |any, (&old, slot)| any | (old != slot));
        count += *m as usize;
    }
    count
}

/// `buf[s] = value(perm[s])` for the slots `s` of the blocks `moved` marks.
fn gather_moved<B: Send>(buf: &mut [B], perm: &[u32], moved: &[bool], value: impl Fn(usize) -> B + Sync) {
    use rayon::prelude::*;
    buf.par_chunks_mut(PERMUTE_BLOCK).zip(perm.par_chunks(PERMUTE_BLOCK)).zip(moved.par_iter()).for_each(
        |((dst, block), &m)| {
            if m {
                for (d, &old) in dst.iter_mut().zip(block) {
                    *d = value(old as usize);
                }
            }
        },
    );
}

/// `put(&mut data[s], buf[s])` for the slots `s` of the blocks `moved` marks.
fn put_moved<T: Send, B: Copy + Sync>(data: &mut [T], buf: &[B], moved: &[bool], put: impl Fn(&mut T, B) + Sync) {
    use rayon::prelude::*;
    data.par_chunks_mut(PERMUTE_BLOCK).zip(buf.par_chunks(PERMUTE_BLOCK)).zip(moved.par_iter()).for_each(
        |((dst, b), &m)| {
            if m {
                for (d, &x) in dst.iter_mut().zip(b) {
                    put(d, x);
                }
            }
        },
    );
}

/// Applies `perm` (new slot -> old absolute index) to `data[range]` in the blocks `moved`
/// marks ([`mark_moved_blocks`]; the others are the identity), gathering through `scratch`:
/// one 8-byte-per-particle buffer serves every array (reinterpreted as `T`), so sorting costs
/// 8 bytes per particle rather than one vector per type. `T` must be at most 8 bytes wide;
/// vectors go through [`permute_vectors`].
pub fn permute<T: bytemuck::Pod + Send + Sync>(
    data: &mut [T],
    range: std::ops::Range<usize>,
    perm: &[u32],
    moved: &[bool],
    scratch: &mut [u64],
) {
    let n = range.len();
    let buf = &mut bytemuck::cast_slice_mut::<u64, T>(scratch)[..n];
    let src = &*data;
    gather_moved(buf, &perm[..n], moved, |old| src[old]);
    put_moved(&mut data[range], buf, moved, |d, x| *d = x);
}

/// [`permute`] for vectors: whole vectors where `scratch` holds `dim` words per slot of
/// `range`, else one component at a time through 8 bytes per slot.
pub fn permute_vectors<V: Vector>(
    data: &mut [V],
    range: std::ops::Range<usize>,
    perm: &[u32],
    moved: &[bool],
    scratch: &mut [u64],
) {
    let n = range.len();
    let dim = std::mem::size_of::<V>() / std::mem::size_of::<Real>();
    if scratch.len() >= n * dim {
        // The whole vector per pass where the buffer holds it (the fluid's accelerations, which
        // the fluid sort lends): `dim` times fewer fork-joins and passes over the vectors.
        return permute(data, range, perm, moved, &mut scratch[..n * dim]);
    }
    let buf = &mut bytemuck::cast_slice_mut::<u64, Real>(scratch)[..n];
    for k in 0..dim {
        let src = &*data;
        gather_moved(buf, &perm[..n], moved, |old| src[old].get(k));
        put_moved(&mut data[range.clone()], buf, moved, |v, x| v.set(k, x));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vectors_permute_alike_through_a_small_and_a_large_buffer() {
        use glam::DVec3;
        let (start, n) = (5usize, 2 * PERMUTE_BLOCK + 17);
        let data: Vec<DVec3> = (0..start + n).map(|i| DVec3::new(i as f64, -(i as f64), 0.5 * i as f64)).collect();
        // reverse the first block, swap two slots of the last: the middle block stays
        let mut perm: Vec<u32> = (start..start + n).map(|i| i as u32).collect();
        perm[..PERMUTE_BLOCK].reverse();
        perm.swap(n - 1, n - 3);
        let mut moved = vec![false; n.div_ceil(PERMUTE_BLOCK)];
        assert_eq!(mark_moved_blocks(&perm, start, &mut moved), 2);
        let expect: Vec<DVec3> = (0..start).map(|i| data[i]).chain(perm.iter().map(|&old| data[old as usize])).collect();
        for words in [n, 3 * n] {
            let mut permuted = data.clone();
            permute_vectors(&mut permuted, start..start + n, &perm, &moved, &mut vec![0u64; words]);
            assert_eq!(permuted, expect, "{words} words of scratch");
        }
    }

    #[test]
    fn marks_exactly_the_blocks_a_permutation_changes() {
        let (start, n) = (7usize, 3 * PERMUTE_BLOCK + 5);
        let identity: Vec<u32> = (start..start + n).map(|i| i as u32).collect();
        let mut moved = vec![true; n.div_ceil(PERMUTE_BLOCK)];
        assert_eq!(mark_moved_blocks(&identity, start, &mut moved), 0);
        assert!(moved.iter().all(|&m| !m));
        // two slots swapped inside block 1, and the last slot of the partial block 3 changed
        let mut perm = identity.clone();
        perm.swap(PERMUTE_BLOCK + 3, PERMUTE_BLOCK + 90);
        perm.swap(n - 1, 0);
        assert_eq!(mark_moved_blocks(&perm, start, &mut moved), 3);
        assert_eq!(moved, vec![true, true, false, true]);
    }
}
