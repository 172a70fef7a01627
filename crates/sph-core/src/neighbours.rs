//! Cell-linked list built by a stable counting sort, or, when few particles changed cell since
//! the last sort, by merging those few into the rest (the same order). Cells have side
//! `support / reach` and a particle's neighbours lie within `reach` cells along each axis:
//! `reach = 1` is the classic
//! `2h` cell with a 3^dim stencil; `reach = 2` (the solver's choice) checks `(5/6)^dim` as many
//! candidates (42 % fewer in 3D) for 25 rows instead of 9.
//!
//! Particles live in three contiguous groups (fixed boundary, moving boundary, fluid). Within a
//! group they are sorted by cell with the vertical fastest and x slowest (see [`axis`]), so the
//! cells of a stencil row, a vertical run, are one contiguous range. Below, "grid axis 0" is the
//! fast one. `starts[g][c]` is the first index of cell `c` in group `g` (absolute index into the
//! particle arrays). Neighbours of a point are visited row by row (slow axis, then middle axis
//! ascending, then up the row), and within a cell in storage order: a fixed order, so sums do
//! not depend on threads.
//!
//! Positions outside the grid are clamped to the edge cells. Clamping is monotone and moves a
//! coordinate by at most the distance it exceeds the edge, so two points within the support stay
//! within `reach` cells: the search stays exact, it only gets slower for particles far outside.

use crate::math::{Dim, Real, Vector};
use crate::threads::{for_each_chunk, Chunks};

pub const GROUPS: usize = 3;
pub const GROUP_FIXED: usize = 0;
pub const GROUP_MOVING: usize = 1;
pub const GROUP_FLUID: usize = 2;

/// Particles per task of the sort's key pass: 4096 left the 2D dam break's 20,000 fluid
/// particles five tasks, split two and three between two threads (phase timers).
const KEY_CHUNK: usize = 1024;

/// [`CellGrid::sort_group`] sorts only the particles that changed cell while they are at most
/// one in this many.
const MOVER_SHARE: usize = 8;

/// The physical axis of grid axis `k`: the vertical is the fast axis, x the slow one (y in
/// between in 3D).
///
/// Why: a particle that changes cell shifts by one slot every particle stored between its old
/// and its new cell, and the sort then moves every block of slots that shifted (see
/// [`crate::particles::permute_carried`]). Flumes and dam breaks are wider than deep: with x
/// fastest, a particle that crossed a cell boundary vertically shifted a whole row of the
/// water's length, with the vertical fastest it shifts at most a column of the water's depth.
/// In the 2D dam break's developed flow (steps 3,000-3,300) the moved blocks per step fell from
/// 61 to 35 of 164 and the sort from 98 to 69 us per step on one thread and from 168 to 62 on
/// two, where it had been the one phase slower on two threads than on one (phase timers,
/// see [`crate::phases`]). The force loop's cost does not depend on the order.
#[inline(always)]
fn axis<D: Dim>(k: usize) -> usize {
    D::DIM - 1 - k
}

/// Largest stencil reach the grid accepts.
pub const MAX_REACH: usize = 3;

/// Cells of a stencil row out of reach below and above the particle's cell, for reach `r`:
/// `near2` (see [`CellGrid::stencil_rows`]) holds the squared distances along grid axis 0, `d2` the row's
/// distance across. Inlined, so a constant `r` unrolls the loop.
#[inline(always)]
fn out_of_reach(d2: Real, near2: &[Real; 2 * MAX_REACH + 1], limit: Real, r: usize) -> (usize, usize) {
    let (mut below, mut above) = (0, 0);
    for o in 1..=r {
        below += (d2 + near2[r - o] >= limit) as usize;
        above += (d2 + near2[r + o] >= limit) as usize;
    }
    (below, above)
}

/// The rows of one stencil: `(first, end)` cell ranges, `n` of them, and each row's cell
/// coordinates along grid axes 1 and 2 (0 along axis 2 in 2D).
pub struct StencilRows {
    pub n: usize,
    pub cells: [(u32, u32); (2 * MAX_REACH + 1) * (2 * MAX_REACH + 1)],
    pub across: [[u32; 2]; (2 * MAX_REACH + 1) * (2 * MAX_REACH + 1)],
}

impl Default for StencilRows {
    fn default() -> Self {
        const ROWS: usize = (2 * MAX_REACH + 1) * (2 * MAX_REACH + 1);
        Self { n: 0, cells: [(0, 0); ROWS], across: [[0; 2]; ROWS] }
    }
}

#[derive(Debug, Clone)]
pub struct CellGrid<D: Dim> {
    origin: D::V,
    inv_cell: Real,
    cell_size: Real,
    /// Stencil half-width in cells.
    reach: usize,
    /// Cells along grid axes 0, 1, 2 (see [`axis`]; 1 along axis 2 in 2D).
    dims: [usize; 3],
    n_cells: usize,
    /// Per group, `n_cells + 1` entries; empty for a group the scene does not have
    /// ([`CellGrid::release_group`]), which then has no neighbours.
    starts: [Vec<u32>; GROUPS],
    /// Per group, the cells `lo..=hi` that held its particles at its last sort, and its slot
    /// range `first..end`: cells up to `lo` start at `first`, cells after `hi` at `end`, so the
    /// next sort rewrites only the cells between (see [`CellGrid::sort_group`]).
    bands: [Option<Band>; GROUPS],
    /// Per group, the cell of each slot (minus `first`) at its last sort, in slot order, so
    /// non-decreasing: the next sort finds the particles that changed cell by comparing keys.
    cells: [Vec<u32>; GROUPS],
    /// The particles that changed cell, as `(cell << 32) | slot`: where they left (old cell,
    /// slot order) and where they go (new cell). Scratch of [`CellGrid::resort_movers`],
    /// reserved once for an eighth of the largest group.
    departures: Vec<u64>,
    arrivals: Vec<u64>,
}

/// See [`CellGrid`]'s `bands`.
#[derive(Debug, Clone, Copy)]
struct Band {
    lo: usize,
    hi: usize,
    first: u32,
    end: u32,
}

impl<D: Dim> CellGrid<D> {
    /// A grid covering `[lo, hi]`, finding all pairs closer than `support` with cells of side
    /// `support / reach`.
    pub fn new(lo: D::V, hi: D::V, support: Real, reach: usize) -> Self {
        let reach = reach.clamp(1, MAX_REACH);
        let cell_size = support / reach as Real;
        let mut dims = [1usize; 3];
        for (k, d) in dims.iter_mut().enumerate().take(D::DIM) {
            let extent = (hi.get(axis::<D>(k)) - lo.get(axis::<D>(k))).max(0.0);
            *d = ((extent / cell_size).floor() as usize).max(1);
        }
        let n_cells = dims[0] * dims[1] * dims[2];
        // scenes are checked for this first (`Scene::validate`: fewer than u32::MAX cells)
        assert!(n_cells < u32::MAX as usize && dims.iter().all(|&d| d <= i32::MAX as usize), "{dims:?} cells: cell keys are 32-bit");
        let empty = || vec![0u32; n_cells + 1];
        Self {
            origin: lo,
            inv_cell: 1.0 / cell_size,
            cell_size,
            reach,
            dims,
            n_cells,
            starts: [empty(), empty(), empty()],
            bands: [None; GROUPS],
            cells: [Vec::new(), Vec::new(), Vec::new()],
            departures: Vec::new(),
            arrivals: Vec::new(),
        }
    }

    pub fn n_cells(&self) -> usize {
        self.n_cells
    }

    /// Bytes held by the grid.
    pub fn memory_bytes(&self) -> usize {
        let words: usize = self.starts.iter().chain(&self.cells).map(|s| s.capacity()).sum();
        words * std::mem::size_of::<u32>() + (self.departures.capacity() + self.arrivals.capacity()) * std::mem::size_of::<u64>()
    }

    /// Frees the cell starts of group `g`, which holds no particle (a scene without a paddle
    /// has no moving walls): 4 bytes per cell, about 5 bytes per particle in the 3D dam break.
    /// The group then has no neighbours; sorting particles into it allocates them again.
    pub fn release_group(&mut self, g: usize) {
        self.starts[g] = Vec::new();
        self.cells[g] = Vec::new();
        self.bands[g] = None;
    }

    /// Frees the cell of each slot that group `g` keeps for its next sort (4 bytes a particle),
    /// for a group that is not sorted again: the fixed walls. A later sort of it sorts every
    /// particle and keeps them again.
    pub fn forget_slot_cells(&mut self, g: usize) {
        self.cells[g] = Vec::new();
    }

    /// One past the highest slot any group's cells hold (the cell starts are non-decreasing,
    /// so each group's last start is its end).
    pub fn slot_end(&self) -> usize {
        self.starts.iter().filter_map(|s| s.last()).map(|&e| e as usize).max().unwrap_or(0)
    }

    /// Whether group `g` has cell starts (see [`CellGrid::release_group`]).
    #[inline(always)]
    pub fn has_group(&self, g: usize) -> bool {
        !self.starts[g].is_empty()
    }

    /// The physical axis of grid axis `k` (see [`axis`]).
    #[inline(always)]
    pub fn physical_axis(k: usize) -> usize {
        axis::<D>(k)
    }

    /// Where `p` lies along grid axis `k` from the grid's origin [m].
    #[inline(always)]
    pub fn along(&self, p: D::V, k: usize) -> Real {
        p.get(axis::<D>(k)) - self.origin.get(axis::<D>(k))
    }

    /// The lower face of the cells at coordinate `c` along any axis, from the grid's origin [m].
    #[inline(always)]
    pub fn face(&self, c: u32) -> Real {
        c as Real * self.cell_size
    }

    /// Where `p` lies along grid axis `k` from the lower face of its cell (the cell it is
    /// sorted into: clamped to the grid) [m].
    #[inline(always)]
    pub fn offset_in_cell(&self, p: D::V, k: usize) -> Real {
        self.along(p, k) - self.face(self.coord_u32(p, k))
    }

    #[inline(always)]
    fn coord(&self, p: D::V, k: usize) -> usize {
        self.coord_u32(p, k) as usize
    }

    /// Where `p` lies along grid axis `k`, in cells from the grid's origin (not clamped).
    #[inline(always)]
    fn cell_units(&self, p: D::V, k: usize) -> Real {
        (p.get(axis::<D>(k)) - self.origin.get(axis::<D>(k))) * self.inv_cell
    }

    /// The cell coordinate of `p` along grid axis `k`, clamped to the grid.
    #[inline(always)]
    fn coord_u32(&self, p: D::V, k: usize) -> u32 {
        let c = self.cell_units(p, k);
        // Truncation is the floor for c >= 0 (negative c clamps to 0 anyway) and, unlike
        // `floor()`, needs no libm call on x86-64 targets without SSE4.1 (it cost 2 % of a
        // step). NaN goes to 0 through `max`; the monitors report NaN separately. Clamped
        // before the conversion, so that it needs none of `as`'s saturation: then the sort's
        // key pass vectorises.
        let c = c.max(0.0).min((self.dims[k] - 1) as Real);
        // SAFETY: `c` is finite and within 0..=dims-1, which i32 holds (asserted in `new`).
        unsafe { c.to_int_unchecked::<i32>() as u32 }
    }

    /// The cell of `p` (grid axis 0 fastest), in 32-bit integers, which the sort's key pass vectorises.
    #[inline(always)]
    fn cell_key(&self, p: D::V) -> u32 {
        let mut key = 0;
        for k in (0..D::DIM).rev() {
            key = key * self.dims[k] as u32 + self.coord_u32(p, k);
        }
        key
    }

    #[inline(always)]
    fn coords(&self, p: D::V) -> [usize; 3] {
        let mut c = [0usize; 3];
        for (k, ck) in c.iter_mut().enumerate().take(D::DIM) {
            *ck = self.coord(p, k);
        }
        c
    }

    /// Sorts group `g`, occupying `range` of the particle arrays, by cell. Writes into `perm`
    /// (indexed by the new slot minus `range.start`) the old absolute index of each particle, and
    /// updates the group's cell starts. Stable: particles in one cell keep their relative order.
    /// `keys` (at least `range.len()` long) is scratch for the cell of each particle: the
    /// caller lends it (the solver, from its gather buffer).
    ///
    /// Between two steps few particles change cell (about 2 % in the 2D dam break): when at most
    /// an eighth did, only they are sorted and merged into the others ([`CellGrid::resort_movers`]),
    /// with the same result as the counting sort of all of them.
    pub fn sort_group(&mut self, g: usize, range: std::ops::Range<usize>, pos: &[D::V], perm: &mut [u32], keys: &mut [u32]) {
        let n = range.len();
        let keys = &mut keys[..n];
        let (first, end) = (range.start as u32, range.end as u32);
        let n_cells = self.n_cells;
        if self.starts[g].len() != n_cells + 1 {
            self.starts[g].resize(n_cells + 1, 0);
            self.bands[g] = None;
        }
        // the last sort's band and cells describe these slots only if it sorted the same range
        let last_band = self.bands[g].filter(|b| b.first == first && b.end == end);
        let same_slots = last_band.is_some() && self.cells[g].len() == n;
        let this = &*self;
        let last = &this.cells[g][..if same_slots { n } else { 0 }];
        let pos = &pos[range.clone()];
        let key_chunks = Chunks::new(&mut *keys, KEY_CHUNK);
        // each thread reads the positions it wrote in the last sweep (see for_each_chunk)
        let (k_lo, k_hi, movers) = for_each_chunk(
            key_chunks.count(),
            || (u32::MAX, 0, 0),
            |ci| {
                // SAFETY: for_each_chunk hands each chunk index to one task
                let keys = unsafe { key_chunks.get(ci) };
                let pos = &pos[ci * KEY_CHUNK..ci * KEY_CHUNK + keys.len()];
                let (mut lo, mut hi) = (u32::MAX, 0);
                for (k, &p) in keys.iter_mut().zip(pos) {
                    *k = this.cell_key(p);
                    lo = lo.min(*k);
                    hi = hi.max(*k);
                }
                let last = last.get(ci * KEY_CHUNK..ci * KEY_CHUNK + keys.len()).unwrap_or(&[]);
                let moved = keys.iter().zip(last).map(|(k, l)| (k != l) as usize).sum::<usize>();
                (lo, hi, moved)
            },
            |a, b| (a.0.min(b.0), a.1.max(b.1), a.2 + b.2),
        );
        if keys.is_empty() {
            self.starts[g].fill(first);
            self.bands[g] = None;
            self.cells[g].clear();
            return;
        }
        let (k_lo, k_hi) = (k_lo as usize, k_hi as usize);
        let band = Band { lo: k_lo, hi: k_hi, first, end };
        if same_slots && movers <= n / MOVER_SHARE {
            if movers == 0 {
                perm.iter_mut().zip(first..).for_each(|(p, i)| *p = i);
            } else {
                self.resort_movers(g, first, keys, perm);
            }
            self.bands[g] = Some(band);
            return;
        }

        // Only the cells between the lowest and the highest occupied cell, of this sort and the
        // last, are rewritten: below them every cell starts at `first`, above them at `end`, as
        // the last sort left them. Most of a flume's cells are air (the grid reaches a tank's
        // height above the tank): the moving paddle's few particles sorted through every cell
        // of the grid, twice per Symplectic step, before.
        let (lo, hi) = match last_band {
            Some(b) => (b.lo.min(k_lo), b.hi.max(k_hi)),
            None => (0, n_cells - 1),
        };
        let starts = &mut self.starts[g];
        starts[lo] = first;

        // Counting sort without a cursor array: the count of cell c goes to starts[c + 1],
        // which the exclusive prefix sum turns into the first slot of cell c; placing the
        // particles advances it to the cell's end, which is the start of cell c + 1.
        let band_starts = &mut starts[lo + 1..=hi + 1];
        band_starts.fill(0);
        for &k in keys.iter() {
            band_starts[k as usize - lo] += 1;
        }
        let mut running = first;
        for s in band_starts.iter_mut() {
            let count = *s;
            *s = running;
            running += count;
        }
        let cells = &mut self.cells[g];
        cells.resize(n, 0);
        for (i, &k) in keys.iter().enumerate() {
            let s = &mut band_starts[k as usize - lo];
            let slot = (*s - first) as usize;
            perm[slot] = first + i as u32;
            cells[slot] = k;
            *s += 1;
        }
        self.bands[g] = Some(band);
    }

    /// The sort of [`CellGrid::sort_group`] when only some particles changed cell since the last
    /// one (`keys` differ from `cells` there): the others are still in cell order, so the movers,
    /// sorted by (new cell, slot), are merged into them, and each cell's start moves by the
    /// movers that left and entered the cells below it. O(particles) in runs that copy, plus
    /// O(movers log movers), against the counting sort's particle-by-particle passes.
    fn resort_movers(&mut self, g: usize, first: u32, keys: &[u32], perm: &mut [u32]) {
        let n = keys.len();
        let (departures, arrivals) = (&mut self.departures, &mut self.arrivals);
        departures.clear();
        arrivals.clear();
        departures.reserve(n / MOVER_SHARE);
        arrivals.reserve(n / MOVER_SHARE);
        let cells = &mut self.cells[g];
        for (i, (&k, &l)) in keys.iter().zip(cells.iter()).enumerate() {
            if k != l {
                departures.push(((l as u64) << 32) | i as u64);
                arrivals.push(((k as u64) << 32) | i as u64);
            }
        }
        // by new cell, then slot: the counting sort's order (stable)
        arrivals.sort_unstable();
        let starts = &mut self.starts[g];

        // The particles that stayed in their cell, in slot order, are in (cell, slot) order. A
        // mover into cell k from slot s goes before the stayers of cells above k and of cell k
        // at slots above s: the slots of cell k at the last sort are starts[k]..starts[k + 1],
        // and s is not among them, so it goes right before slot starts[k] (s below them) or
        // starts[k + 1] (s above).
        let slot_of = |e: u64| (e & 0xffff_ffff) as usize;
        let cell_in = |e: u64| (e >> 32) as usize;
        let (mut out, mut next, mut left) = (0, 0, departures.iter().map(|&e| slot_of(e)).peekable());
        let mut copy_stayers = |upto: usize, out: &mut usize, perm: &mut [u32], cells: &mut [u32]| {
            while next < upto {
                // the stayers up to the next slot a mover left
                let stop = left.peek().map_or(upto, |&d| d.min(upto));
                let len = stop - next;
                perm[*out..*out + len].iter_mut().zip(first + next as u32..).for_each(|(p, i)| *p = i);
                cells[*out..*out + len].copy_from_slice(&keys[next..stop]);
                *out += len;
                next = stop;
                if left.peek() == Some(&next) {
                    left.next();
                    next += 1;
                }
            }
        };
        for &e in arrivals.iter() {
            let (k, s) = (cell_in(e), slot_of(e));
            let (a, b) = ((starts[k] - first) as usize, (starts[k + 1] - first) as usize);
            copy_stayers(if s < a { a } else { b }, &mut out, perm, cells);
            perm[out] = first + s as u32;
            cells[out] = k as u32;
            out += 1;
        }
        copy_stayers(n, &mut out, perm, cells);
        debug_assert_eq!(out, n);

        // A particle that left cell o no longer counts below the cells above o; one that entered
        // cell k now does. Between two such events every start moves by the same amount.
        // the cell of the next departure or arrival not yet counted (usize::MAX: none left)
        let next_event = |d: usize, a: usize| {
            let cell = |list: &[u64], i: usize| list.get(i).map_or(usize::MAX, |&e| cell_in(e));
            cell(departures, d).min(cell(arrivals, a))
        };
        let (mut d, mut a, mut shift) = (0, 0, 0i64);
        loop {
            let cell = next_event(d, a);
            if cell == usize::MAX {
                break;
            }
            while departures.get(d).is_some_and(|&e| cell_in(e) == cell) {
                shift -= 1;
                d += 1;
            }
            while arrivals.get(a).is_some_and(|&e| cell_in(e) == cell) {
                shift += 1;
                a += 1;
            }
            let upto = next_event(d, a);
            if shift != 0 {
                // all movers are counted once the last event is passed, so `upto` is finite here
                starts[cell + 1..=upto].iter_mut().for_each(|s| *s = (*s as i64 + shift) as u32);
            }
        }
    }

    /// The stencil rows around `p`, trimmed to the cells that reach within the support of `p`:
    /// a row is left out when its nearest point across it (grid axes 1 and 2) is a support or
    /// more away, and its range along grid axis 0 ends at the last cell whose nearest point is
    /// within the support (about a third
    /// fewer candidates in 3D with `reach = 2`). The rows keep the order of
    /// [`CellGrid::for_each_near`], so the pairs found (those within the support) and their
    /// order are the same. Cell ranges; [`CellGrid::row_slots`] turns them into particle slots.
    /// For loops that cannot take a closure: a closure is compiled without the target features
    /// of the function that calls it (the AVX2 force loop).
    #[inline(always)]
    pub fn stencil_rows(&self, p: D::V, rows: &mut StencilRows) {
        let c = self.coords(p);
        let r = self.reach;
        // Squared distance, in cell units, from p to the nearest point of the cell `o` cells
        // away along axis k (o in -r..=r, stored at o + r); the support is `r` cells. A point
        // outside the grid (clamped to an edge cell) is not trimmed: its fraction is unknown.
        let mut near2 = [[0.0 as Real; 2 * MAX_REACH + 1]; 3];
        let mut trim = true;
        for (k, nk) in near2.iter_mut().enumerate().take(D::DIM) {
            let u = self.cell_units(p, k) - c[k] as Real;
            trim &= (0.0..1.0).contains(&u);
            for o in 1..=r {
                let below = u + (o - 1) as Real;
                let above = o as Real - u;
                nk[r - o] = below * below;
                nk[r + o] = above * above;
            }
        }
        // A hair above r^2: rounding of the cell-unit distances must never drop a pair.
        let limit = if trim { (r * r) as Real * (1.0 + 1e-9) } else { Real::INFINITY };
        let span = |k: usize| (c[k].saturating_sub(r), (c[k] + r).min(self.dims[k] - 1));
        // x, y, z here are grid axes 0, 1, 2 (see `axis`): x along the rows
        let (x_lo, x_hi) = span(0);
        let (y_lo, y_hi) = span(1);
        let (z_lo, z_hi) = if D::DIM == 3 { span(2) } else { (0, 0) };
        rows.n = 0;
        for z in z_lo..=z_hi {
            let dz2 = if D::DIM == 3 { near2[2][z + r - c[2]] } else { 0.0 };
            // Without branches on the trimming (which cells a row keeps depends on where `p`
            // sits in its cell, so those branches went either way): the cells out of reach
            // on either side are counted, not searched for. They are the row's outer ends,
            // since `near2` grows away from `p`'s cell, so a count gives where the row starts
            // or ends. A row out of reach is written and not counted.
            for y in y_lo..=y_hi {
                let d2 = dz2 + near2[1][y + r - c[1]];
                // the solver's reach unrolled, any other counted in a loop
                let (below, above) = match r {
                    2 => out_of_reach(d2, &near2[0], limit, 2),
                    _ => out_of_reach(d2, &near2[0], limit, r),
                };
                // cells past the grid's edge count as trimmed too: the span cuts them anyway
                let (lo, hi) = ((c[0] + below).saturating_sub(r).max(x_lo), (c[0] + r - above).min(x_hi));
                let row = self.dims[0] * (y + self.dims[1] * z);
                rows.cells[rows.n] = ((row + lo) as u32, (row + hi + 1) as u32);
                rows.across[rows.n] = [y as u32, z as u32];
                rows.n += (d2 < limit) as usize;
            }
        }
    }

    /// Particle slots `(first, end)` of group `g` in row `i` of `rows`. The group must have its
    /// cell starts ([`CellGrid::has_group`]).
    #[inline(always)]
    pub fn row_slots(&self, g: usize, rows: &StencilRows, i: usize) -> (u32, u32) {
        let (lo, hi) = rows.cells[i];
        (self.starts[g][lo as usize], self.starts[g][hi as usize])
    }

    /// Calls `f(b)` for every particle `b` of group `g` in the cells around `p`, in a fixed order.
    #[inline(always)]
    pub fn for_each_near(&self, g: usize, p: D::V, mut f: impl FnMut(usize)) {
        let starts = &self.starts[g];
        if starts.is_empty() {
            return;
        }
        let c = self.coords(p);
        let r = self.reach;
        let span = |k: usize| (c[k].saturating_sub(r), (c[k] + r).min(self.dims[k] - 1));
        // x, y, z here are grid axes 0, 1, 2 (see `axis`): x along the rows
        let (x_lo, x_hi) = span(0);
        let (y_lo, y_hi) = span(1);
        let (z_lo, z_hi) = if D::DIM == 3 { span(2) } else { (0, 0) };
        for z in z_lo..=z_hi {
            for y in y_lo..=y_hi {
                let row = self.dims[0] * (y + self.dims[1] * z);
                let begin = starts[row + x_lo] as usize;
                let end = starts[row + x_hi + 1] as usize;
                for b in begin..end {
                    f(b);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Dim2, Dim3};
    use glam::{DVec2, DVec3};
    use proptest::prelude::*;

    /// Sorts one fluid group and checks the neighbour sets against brute force.
    fn check<D: Dim>(points: Vec<D::V>, lo: D::V, hi: D::V, radius: Real) {
        for reach in [1, 2, 3] {
            check_reach::<D>(&points, lo, hi, radius, reach);
        }
    }

    fn check_reach<D: Dim>(points: &[D::V], lo: D::V, hi: D::V, radius: Real, reach: usize) {
        let n = points.len();
        let mut grid = CellGrid::<D>::new(lo, hi, radius, reach);
        let mut perm = vec![0u32; n];
        grid.sort_group(GROUP_FLUID, 0..n, points, &mut perm, &mut vec![0; n]);
        let sorted: Vec<D::V> = perm.iter().map(|&i| points[i as usize]).collect();
        // empty groups: starts all zero, so iteration over them visits nothing
        for a in 0..n {
            let mut found = Vec::new();
            grid.for_each_near(GROUP_FLUID, sorted[a], |b| {
                if (sorted[a] - sorted[b]).length_squared() < radius * radius {
                    found.push(b)
                }
            });
            grid.for_each_near(GROUP_FIXED, sorted[a], |_| panic!("fixed group is empty"));
            let mut brute: Vec<usize> = (0..n)
                .filter(|&b| (sorted[a] - sorted[b]).length_squared() < radius * radius)
                .collect();
            // the trimmed rows find the same pairs in the same order
            let mut rows = StencilRows::default();
            grid.stencil_rows(sorted[a], &mut rows);
            let mut trimmed = Vec::new();
            for i in 0..rows.n {
                let (lo, hi) = grid.row_slots(GROUP_FLUID, &rows, i);
                trimmed.extend((lo as usize..hi as usize).filter(|&b| (sorted[a] - sorted[b]).length_squared() < radius * radius));
            }
            assert_eq!(trimmed, found, "trimmed stencil, particle {a}, reach {reach}");
            let mut f2 = found.clone();
            f2.sort();
            brute.sort();
            assert_eq!(f2, brute, "particle {a}, reach {reach}");
            assert_eq!(found.len(), f2.len(), "no particle visited twice");
        }
        let mut seen = perm.clone();
        seen.sort();
        assert!(seen.iter().enumerate().all(|(i, &v)| i as u32 == v), "perm is a permutation");
    }

    #[test]
    fn a_released_group_has_no_neighbours_until_sorted_again() {
        let pts = vec![DVec2::new(0.3, 0.3), DVec2::new(0.32, 0.3), DVec2::new(0.9, 0.1)];
        let mut grid = CellGrid::<Dim2>::new(DVec2::ZERO, DVec2::ONE, 0.1, 2);
        let bytes = grid.memory_bytes();
        grid.release_group(GROUP_MOVING);
        assert!(!grid.has_group(GROUP_MOVING) && grid.has_group(GROUP_FLUID));
        assert_eq!(grid.memory_bytes(), bytes * 2 / 3);
        grid.for_each_near(GROUP_MOVING, pts[0], |_| panic!("released group"));
        let (mut perm, mut keys) = (vec![0u32; 3], vec![0u32; 3]);
        grid.sort_group(GROUP_MOVING, 0..3, &pts, &mut perm, &mut keys);
        let mut near = Vec::new();
        grid.for_each_near(GROUP_MOVING, pts[0], |b| near.push(b));
        assert!(grid.has_group(GROUP_MOVING) && near.len() == 2, "{near:?}");
    }

    #[test]
    fn a_group_whose_slot_cells_were_forgotten_sorts_in_full() {
        let mut pts: Vec<DVec2> = (0..100).map(|i| DVec2::new(0.05 + 0.009 * i as f64, 0.3)).collect();
        let mut grid = CellGrid::<Dim2>::new(DVec2::ZERO, DVec2::ONE, 0.1, 2);
        let (mut perm, mut keys) = (vec![0u32; 100], vec![0u32; 100]);
        grid.sort_group(GROUP_FIXED, 0..100, &pts, &mut perm, &mut keys);
        let bytes = grid.memory_bytes();
        grid.forget_slot_cells(GROUP_FIXED);
        assert_eq!(grid.memory_bytes(), bytes - 100 * 4);
        pts[3].x += 0.3;
        grid.sort_group(GROUP_FIXED, 0..100, &pts, &mut perm, &mut keys);
        let mut fresh = CellGrid::<Dim2>::new(DVec2::ZERO, DVec2::ONE, 0.1, 2);
        let mut fresh_perm = vec![0u32; 100];
        fresh.sort_group(GROUP_FIXED, 0..100, &pts, &mut fresh_perm, &mut keys);
        assert_eq!(perm, fresh_perm);
        assert_eq!(grid.starts[GROUP_FIXED], fresh.starts[GROUP_FIXED]);
        assert_eq!(grid.cells[GROUP_FIXED], fresh.cells[GROUP_FIXED]);
    }

    #[test]
    fn one_particle() {
        check::<Dim2>(vec![DVec2::new(0.3, 0.3)], DVec2::ZERO, DVec2::ONE, 0.1);
    }

    #[test]
    fn all_in_one_cell() {
        let pts: Vec<DVec3> = (0..50).map(|i| DVec3::splat(0.5 + 1e-4 * i as f64)).collect();
        check::<Dim3>(pts, DVec3::ZERO, DVec3::ONE, 0.2);
    }

    #[test]
    fn on_cell_edges_and_outside_the_grid() {
        let mut pts = Vec::new();
        for i in 0..=10 {
            for j in 0..=10 {
                pts.push(DVec2::new(i as f64 * 0.1, j as f64 * 0.1));
            }
        }
        pts.push(DVec2::new(-0.35, 0.2));
        pts.push(DVec2::new(1.7, 1.25));
        pts.push(DVec2::new(1.75, 1.3));
        check::<Dim2>(pts, DVec2::ZERO, DVec2::ONE, 0.1);
    }

    #[test]
    fn empty_cells_in_a_large_grid() {
        let pts = vec![DVec3::new(0.05, 0.05, 0.05), DVec3::new(0.95, 0.95, 0.95), DVec3::new(0.9, 0.9, 0.9)];
        check::<Dim3>(pts, DVec3::ZERO, DVec3::ONE, 0.1);
    }

    /// A grid sorted again after its particles moved (its cell band shifted, grew or shrank)
    /// gives the perm and starts a fresh grid gives.
    fn resort_matches_fresh(first: &[DVec2], then: &[DVec2], offset: usize) {
        let n = first.len();
        let range = offset..offset + n;
        let padded = |pts: &[DVec2]| {
            let mut all = vec![DVec2::splat(0.5); offset];
            all.extend_from_slice(pts);
            all
        };
        let (a, b) = (padded(first), padded(then));
        let new_grid = || CellGrid::<Dim2>::new(DVec2::ZERO, DVec2::ONE, 0.1, 2);
        let (mut perm, mut keys) = (vec![0u32; n], vec![0u32; n]);
        let mut grid = new_grid();
        grid.sort_group(GROUP_MOVING, range.clone(), &a, &mut perm, &mut keys);
        grid.sort_group(GROUP_MOVING, range.clone(), &b, &mut perm, &mut keys);
        let mut fresh = new_grid();
        let mut fresh_perm = vec![0u32; n];
        fresh.sort_group(GROUP_MOVING, range, &b, &mut fresh_perm, &mut keys);
        assert_eq!(perm, fresh_perm);
        assert_eq!(grid.starts[GROUP_MOVING], fresh.starts[GROUP_MOVING]);
    }

    #[test]
    fn a_group_that_moved_resorts_as_a_fresh_grid_sorts_it() {
        let low: Vec<DVec2> = (0..40).map(|i| DVec2::new(0.02 * i as f64, 0.05)).collect();
        let high: Vec<DVec2> = (0..40).map(|i| DVec2::new(0.9 - 0.02 * i as f64, 0.95)).collect();
        let middle: Vec<DVec2> = (0..40).map(|i| DVec2::new(0.5, 0.4 + 0.005 * i as f64)).collect();
        for (a, b) in [(&low, &high), (&high, &low), (&low, &middle), (&middle, &low), (&middle, &high)] {
            resort_matches_fresh(a, b, 0);
            resort_matches_fresh(a, b, 7);
        }
    }

    /// Sorted again after each round of moves, with the perm applied between sorts as the
    /// solver does: the grid that merges the movers ([`CellGrid::resort_movers`]) gives the perm
    /// and starts of a fresh grid every round. `rounds` hold (particle, dx, dy).
    fn drift_matches_fresh(start: &[DVec2], rounds: &[Vec<(usize, f64, f64)>], offset: usize) {
        let n = start.len();
        let range = offset..offset + n;
        let mut pts = vec![DVec2::splat(0.5); offset];
        pts.extend_from_slice(start);
        let new_grid = || CellGrid::<Dim2>::new(DVec2::ZERO, DVec2::ONE, 0.1, 2);
        let (mut perm, mut keys) = (vec![0u32; n], vec![0u32; n]);
        let mut grid = new_grid();
        let mut merged = 0;
        for (round, moves) in std::iter::once(&Vec::new()).chain(rounds).enumerate() {
            for &(i, dx, dy) in moves {
                pts[offset + i % n] += DVec2::new(dx, dy);
            }
            let before: Vec<u32> = pts[range.clone()].iter().map(|&p| grid.cell_key(p)).collect();
            let movers = before.iter().zip(&grid.cells[GROUP_MOVING]).filter(|(&k, &l)| k != l).count();
            merged += (round > 0 && movers <= n / MOVER_SHARE) as usize;
            grid.sort_group(GROUP_MOVING, range.clone(), &pts, &mut perm, &mut keys);
            let mut fresh = new_grid();
            let mut fresh_perm = vec![0u32; n];
            fresh.sort_group(GROUP_MOVING, range.clone(), &pts, &mut fresh_perm, &mut keys);
            assert_eq!(perm, fresh_perm, "round {round}");
            assert_eq!(grid.starts[GROUP_MOVING], fresh.starts[GROUP_MOVING], "round {round}");
            assert_eq!(grid.cells[GROUP_MOVING], fresh.cells[GROUP_MOVING], "round {round}");
            let sorted: Vec<DVec2> = perm.iter().map(|&i| pts[i as usize]).collect();
            pts[range.clone()].copy_from_slice(&sorted);
        }
        assert_eq!(merged, rounds.len(), "every round after the first merges its few movers");
    }

    #[test]
    fn movers_merge_into_the_particles_that_stayed() {
        // a lattice of two particles per cell in 0.1..0.9
        let lattice: Vec<DVec2> = (0..32 * 32).map(|i| DVec2::new(0.1 + 0.025 * (i % 32) as f64, 0.1 + 0.025 * (i / 32) as f64)).collect();
        let rounds = vec![
            vec![(5, 0.03, 0.0)],                      // one cell up in x
            vec![(700, -0.2, -0.05)],                  // back by several cells
            vec![(3, 0.0, 0.95), (4, 0.0, 0.95)],      // above the band of occupied cells
            vec![(10, -0.5, -0.5), (900, 0.5, 0.5)],   // outside the grid (clamped to the edges)
            vec![(20, 0.025, 0.0), (21, -0.025, 0.0)], // two that swap cells
            vec![(30, 1e-3, 0.0)],                     // moves within its cell
            vec![],                                    // no move at all
        ];
        drift_matches_fresh(&lattice, &rounds, 0);
        drift_matches_fresh(&lattice, &rounds, 9);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn random_drift(
            coords in proptest::collection::vec((-0.2f64..1.2, -0.2f64..1.2), 40..300),
            rounds in proptest::collection::vec(proptest::collection::vec((0usize..300, -0.3f64..0.3, -0.3f64..0.3), 0..5), 1..4),
        ) {
            let pts: Vec<DVec2> = coords.into_iter().map(|(x, y)| DVec2::new(x, y)).collect();
            drift_matches_fresh(&pts, &rounds, 3);
        }
        #[test]
        fn random_2d(coords in proptest::collection::vec((-0.2f64..1.2, -0.2f64..1.2), 1..300), r in 0.02f64..0.5) {
            let pts = coords.into_iter().map(|(x, y)| DVec2::new(x, y)).collect();
            check::<Dim2>(pts, DVec2::ZERO, DVec2::ONE, r);
        }
        #[test]
        fn random_resort(moves in proptest::collection::vec(((0.0f64..1.0, 0.0f64..1.0), (-0.3f64..1.3, -0.3f64..1.3)), 1..200)) {
            let (a, b): (Vec<DVec2>, Vec<DVec2>) =
                moves.into_iter().map(|((x, y), (u, v))| (DVec2::new(x, y), DVec2::new(u, v))).unzip();
            resort_matches_fresh(&a, &b, 3);
        }
        #[test]
        fn random_3d(coords in proptest::collection::vec((-0.2f64..1.2, -0.2f64..1.2, 0.0f64..1.0), 1..300), r in 0.05f64..0.5) {
            let pts = coords.into_iter().map(|(x, y, z)| DVec3::new(x, y, z)).collect();
            check::<Dim3>(pts, DVec3::ZERO, DVec3::ONE, r);
        }
    }
}
