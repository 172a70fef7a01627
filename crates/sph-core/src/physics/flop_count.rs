//! Floating-point operations of the batched force loop, counted (feature `flop-count`): the
//! roofline figures of docs/benchmarks.md ("Distance to the floor").
//!
//! [`Counted`] is a pair float type whose every add, multiply, division, square root and
//! comparison bumps a global counter; the batched loop run with it (`batched::fluid_forces_counted`)
//! does exactly the arithmetic of the real loop on the same pairs, batches and padding, so the
//! counts per evaluation are the real loop's. Neither the type nor the counters are compiled
//! into a build without the feature.
//!
//! Counted: the pair terms in the pair float type (`sum_batch`'s arithmetic loop and its lane
//! sums, every lane of a batch, the padding lanes included, as the SIMD units execute them).
//! Not counted: the gather's f64 set-up per lane (`rho_b / rho0 - 1`, two operations; the
//! pressure for gamma other than 7), the candidate scan's distances (f64, 5 operations per
//! candidate in 3D) and the per-particle set-up and totals.

use std::cmp::Ordering as CmpOrdering;
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::math::{PairFloat, Real};

static ADD: AtomicU64 = AtomicU64::new(0);
static MUL: AtomicU64 = AtomicU64::new(0);
static DIV: AtomicU64 = AtomicU64::new(0);
static SQRT: AtomicU64 = AtomicU64::new(0);
static CMP: AtomicU64 = AtomicU64::new(0);
static LANES: AtomicU64 = AtomicU64::new(0);

#[inline(always)]
fn bump(counter: &AtomicU64) {
    counter.fetch_add(1, Ordering::Relaxed);
}

/// Lanes of pair arithmetic a batch executes (its pairs and its padding).
pub(crate) fn add_lanes(n: usize) {
    LANES.fetch_add(n as u64, Ordering::Relaxed);
}

/// Operation counts of one or more force evaluations.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PairOps {
    /// Lanes of pair arithmetic executed (pairs, the particle itself and padding).
    pub lanes: u64,
    /// Additions and subtractions.
    pub add: u64,
    pub mul: u64,
    pub div: u64,
    pub sqrt: u64,
    /// Comparisons (selects and maxima; not floating-point operations of the roofline).
    pub cmp: u64,
}

impl PairOps {
    /// Floating-point operations: additions, multiplications, divisions and square roots,
    /// one each.
    pub fn flops(&self) -> u64 {
        self.add + self.mul + self.div + self.sqrt
    }
}

/// Sets every counter to zero.
pub(crate) fn reset() {
    for c in [&ADD, &MUL, &DIV, &SQRT, &CMP, &LANES] {
        c.store(0, Ordering::Relaxed);
    }
}

/// The counts since the last [`reset`].
pub(crate) fn read() -> PairOps {
    let r = |c: &AtomicU64| c.load(Ordering::Relaxed);
    PairOps { lanes: r(&LANES), add: r(&ADD), mul: r(&MUL), div: r(&DIV), sqrt: r(&SQRT), cmp: r(&CMP) }
}

/// A pair float that counts its operations.
#[derive(Clone, Copy, Debug, Default)]
pub struct Counted<T>(T);

macro_rules! counted {
    ($t:ty, $lanes:expr, $single:expr) => {
        impl Add for Counted<$t> {
            type Output = Self;
            #[inline(always)]
            fn add(self, o: Self) -> Self {
                bump(&ADD);
                Counted(self.0 + o.0)
            }
        }
        impl Sub for Counted<$t> {
            type Output = Self;
            #[inline(always)]
            fn sub(self, o: Self) -> Self {
                bump(&ADD);
                Counted(self.0 - o.0)
            }
        }
        impl Mul for Counted<$t> {
            type Output = Self;
            #[inline(always)]
            fn mul(self, o: Self) -> Self {
                bump(&MUL);
                Counted(self.0 * o.0)
            }
        }
        impl Div for Counted<$t> {
            type Output = Self;
            #[inline(always)]
            fn div(self, o: Self) -> Self {
                bump(&DIV);
                Counted(self.0 / o.0)
            }
        }
        /// A sign flip (an exclusive or of the sign bit in SIMD): not counted.
        impl Neg for Counted<$t> {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                Counted(-self.0)
            }
        }
        impl AddAssign for Counted<$t> {
            #[inline(always)]
            fn add_assign(&mut self, o: Self) {
                bump(&ADD);
                self.0 += o.0;
            }
        }
        impl PartialEq for Counted<$t> {
            #[inline(always)]
            fn eq(&self, o: &Self) -> bool {
                bump(&CMP);
                self.0 == o.0
            }
        }
        impl PartialOrd for Counted<$t> {
            #[inline(always)]
            fn partial_cmp(&self, o: &Self) -> Option<CmpOrdering> {
                bump(&CMP);
                self.0.partial_cmp(&o.0)
            }
        }
        impl PairFloat for Counted<$t> {
            const LANES: usize = $lanes;
            const SINGLE: bool = $single;
            #[inline(always)]
            fn of(x: Real) -> Self {
                Counted(x as $t)
            }
            #[inline(always)]
            fn of_f32(x: f32) -> Self {
                Counted(x as $t)
            }
            #[inline(always)]
            fn to_real(self) -> Real {
                self.0 as Real
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                bump(&SQRT);
                Counted(self.0.sqrt())
            }
            /// A mask of the sign bit in SIMD: not counted.
            #[inline(always)]
            fn abs(self) -> Self {
                Counted(self.0.abs())
            }
        }
    };
}
counted!(f64, <f64 as PairFloat>::LANES, false);
counted!(f32, <f32 as PairFloat>::LANES, true);
