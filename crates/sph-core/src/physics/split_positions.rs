//! Positions in single precision for the candidate scan of the single-precision force loop
//! (`force_precision = "f32"`, [`super::batched`]), 4 bytes per particle and axis more (16 in
//! 3D, 12 in 2D).
//!
//! Across the stencil's rows (grid axes 1 and 2, [`CellGrid`]), a particle is held as its
//! offset from the lower face of its cell, `fl32(x - face)`: within a row that face is the
//! row's, so `r = fl32(x_a - face) - fl32(x_b - face)` with `x_a - face` formed in f64 once per
//! row, within the f32 rounding of a few cells' width (2e-7 of the support; the f64 offset
//! rounded to f32 is within half a unit in its own last place). Along the rows (grid axis 0,
//! the vertical) the candidates lie in several cells, so the height above the grid's origin is
//! held as two f32, `hi = fl32(z)` and `lo = fl32(z - hi)`, and `r = (hi_a - hi_b) + (lo_a -
//! lo_b)`: the first difference is exact for two nearby heights away from zero (Sterbenz), the
//! second carries what f32 dropped. Plain f32 arrays let the AVX2 scan test eight candidates
//! per instruction without the shuffles that interleaved f64 positions need, and hand the
//! pair arithmetic its `r` in the type it computes in.
//!
//! Rebuilt from the positions before every force evaluation of a single-precision scene, after
//! the cell sort (the offsets are taken from the cells the particles are sorted into); a
//! double-precision scene never fills it.

use rayon::prelude::*;

use crate::math::{Dim, Real};
use crate::neighbours::CellGrid;

/// Slots past the last particle that each array holds (zeros): the AVX2 scan reads a last,
/// partial octet of candidates whole and masks off what lies beyond the row.
pub const PAD: usize = 8;

/// See the module's documentation. Empty until the first [`SplitPositions::update`].
#[derive(Debug, Clone, Default)]
pub struct SplitPositions {
    /// Grid axis 0: the height above the grid's origin as `hi + lo`, `n + PAD` values each.
    pub hi: Vec<f32>,
    pub lo: Vec<f32>,
    /// Grid axes 1 and 2: the offset from the lower face of the particle's cell (axis 2 empty
    /// in 2D).
    pub offset: [Vec<f32>; 2],
}

impl SplitPositions {
    /// Fills the arrays from `pos` (all slots), sorted into `grid`'s cells. Allocates only
    /// when the particle count grows.
    pub fn update<D: Dim>(&mut self, grid: &CellGrid<D>, pos: &[D::V]) {
        let n = pos.len();
        let [off1, off2] = &mut self.offset;
        let arrays: [&mut Vec<f32>; 4] = [&mut self.hi, &mut self.lo, off1, off2];
        for v in arrays.into_iter().take(D::DIM + 1) {
            if v.len() != n + PAD {
                v.clear();
                v.resize(n + PAD, 0.0);
            }
        }
        self.hi[..n].par_iter_mut().zip(self.lo[..n].par_iter_mut()).zip(pos.par_iter()).with_min_len(4096).for_each(|((h, l), &p)| {
            (*h, *l) = split(grid.along(p, 0));
        });
        for k in 1..D::DIM {
            self.offset[k - 1][..n].par_iter_mut().zip(pos.par_iter()).with_min_len(4096).for_each(|(o, &p)| {
                *o = grid.offset_in_cell(p, k) as f32;
            });
        }
    }

    /// Whether the arrays hold `n` slots and the PAD after them.
    pub fn covers(&self, dim: usize, n: usize) -> bool {
        let len = |v: &Vec<f32>| v.len() >= n + PAD;
        len(&self.hi) && len(&self.lo) && self.offset[..dim - 1].iter().all(len)
    }

    /// Bytes held.
    pub fn memory_bytes(&self) -> usize {
        [&self.hi, &self.lo, &self.offset[0], &self.offset[1]].iter().map(|v| v.capacity() * std::mem::size_of::<f32>()).sum()
    }
}

/// `(fl32(x), fl32(x - fl32(x)))`.
#[inline(always)]
pub fn split(x: Real) -> (f32, f32) {
    let hi = x as f32;
    (hi, (x - hi as Real) as f32)
}

/// The f32 difference `a - b` of two split heights, as the scan forms it.
#[inline(always)]
pub fn difference(a: (f32, f32), b: (f32, f32)) -> f32 {
    (a.0 - b.0) + (a.1 - b.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Within 2.5 units in the last place of the rounded f64 difference, for coordinates near
    /// zero, around 1 m and 20 m apart by up to a support.
    #[test]
    fn the_difference_keeps_single_precision() {
        let mut worst: f64 = 0.0;
        for &base in &[0.0, 1e-3, 0.7, 1.3, 19.9, 20.0, -4.2] {
            for i in 0..2000 {
                let a = base + (i as Real) * 3.7e-4;
                let b = a + ((i * 7919) % 613) as Real * 1.1e-4 - 0.03;
                let exact = a - b;
                let r = difference(split(a), split(b)) as Real;
                let ulp = (exact as f32).abs().max(f32::MIN_POSITIVE);
                let ulp = (f32::from_bits(ulp.to_bits() + 1) - ulp) as Real;
                worst = worst.max((r - exact).abs() / ulp);
            }
        }
        assert!(worst <= 2.5, "worst error {worst} ulp");
    }

    /// The offsets the scan forms from a filled split, across the rows (from the row's cell
    /// faces) and along them (the split height), against the f64 offsets, 19 m from the origin
    /// of a 3D grid 20 m long: every component within the f32 rounding of a few cells' width.
    #[test]
    fn the_scan_offsets_match_the_f64_offsets() {
        use crate::math::{Dim3, Vector};
        type V = <Dim3 as Dim>::V;
        let support = 0.03;
        let grid = CellGrid::<Dim3>::new(V::new(-0.1, -0.2, -0.05), V::new(20.0, 0.6, 1.2), support, 2);
        // a linear congruential sequence: uniform enough, and reproducible
        let mut state: u64 = 12345;
        let mut uniform = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as Real / (1u64 << 53) as Real
        };
        let pos: Vec<V> = (0..4000).map(|_| V::new(19.3 + uniform() * 0.3, uniform() * 0.3 - 0.1, uniform() * 0.3)).collect();
        let mut pairs = 0;
        let mut split = SplitPositions::default();
        split.update::<Dim3>(&grid, &pos);
        assert!(split.covers(3, pos.len()));
        let mut worst: Real = 0.0;
        for a in 0..pos.len() {
            for b in (0..pos.len()).step_by(7) {
                let exact = pos[a] - pos[b];
                if exact.length() > 1.5 * support {
                    continue;
                }
                // grid axis 0 is the vertical (physical z), 1 is y, 2 is x
                let r0 = difference((split.hi[a], split.lo[a]), (split.hi[b], split.lo[b]));
                let across = |k: usize| {
                    let face_b = grid.along(pos[b], k) - grid.offset_in_cell(pos[b], k);
                    ((grid.along(pos[a], k) - face_b) as f32) - split.offset[k - 1][b]
                };
                let r = [across(2), across(1), r0];
                pairs += usize::from(a != b);
                for (d, &rd) in r.iter().enumerate() {
                    worst = worst.max((rd as Real - exact.get(d)).abs() / support);
                }
            }
        }
        assert!(pairs > 1000, "{pairs} pairs");
        // the bound: half a unit in the last place of each offset (up to 1.5 supports across,
        // one cell within) and of their difference, 1.6e-7 of the support; measured 1.4e-7
        assert!(worst < 2e-7, "worst error {worst:e} of the support");
    }
}
