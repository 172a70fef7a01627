//! Running work on a given number of threads, for timing one thread count against another in
//! one process (`watersim bench --compare-threads`): on a shared host single runs scatter by
//! 10-30 % from one minute to the next, and two thread counts timed in alternation, each run
//! next to the other, drift together. Results do not depend on the thread count, so one
//! simulation can alternate between pools and follow the same trajectory.
//!
//! Also the split of the per-particle loops among a pool's threads ([`for_each_chunk`]) that
//! keeps each thread on the same slots from one loop to the next.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use rayon::ThreadPool;

use crate::error::{Error, Result};

/// Pools built so far, one per thread count, kept for the process's life: building one starts
/// its threads, which a timed run should not pay for.
static POOLS: Mutex<Vec<(usize, Arc<ThreadPool>)>> = Mutex::new(Vec::new());

/// Runs `op` on a rayon pool of `threads` threads (built on first use, then reused); every
/// parallel loop inside runs on that pool.
pub fn on_threads<R: Send>(threads: usize, op: impl FnOnce() -> R + Send) -> Result<R> {
    if threads == 0 {
        return Err(Error::InvalidScene { field: "threads".into(), reason: "must be at least 1".into() });
    }
    let pool = {
        let mut pools = POOLS.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        match pools.iter().find(|(t, _)| *t == threads) {
            Some((_, pool)) => Arc::clone(pool),
            None => {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().map_err(|e| {
                    Error::InvalidScene { field: "threads".into(), reason: format!("cannot start {threads} threads: {e}") }
                })?;
                let pool = Arc::new(pool);
                pools.push((threads, Arc::clone(&pool)));
                pool
            }
        }
    };
    Ok(pool.install(op))
}

/// Most segments [`for_each_chunk`] splits a loop into; threads beyond them only take chunks
/// from the others' segments.
const MAX_SEGMENTS: usize = 64;

/// A segment's chunks not yet taken, `front..back`, packed in one word so that a claim is one
/// compare-and-swap.
fn pack(front: usize, back: usize) -> u64 {
    ((front as u64) << 32) | back as u64
}

fn unpack(word: u64) -> (usize, usize) {
    ((word >> 32) as usize, (word & 0xffff_ffff) as usize)
}

/// Takes one chunk of `segment`: its first if `from_front`, else its last; `None` when empty.
fn claim(segment: &AtomicU64, from_front: bool) -> Option<usize> {
    let mut word = segment.load(Ordering::Acquire);
    loop {
        let (front, back) = unpack(word);
        if front >= back {
            return None;
        }
        let (next, chunk) = if from_front { (pack(front + 1, back), front) } else { (pack(front, back - 1), back - 1) };
        match segment.compare_exchange_weak(word, next, Ordering::AcqRel, Ordering::Acquire) {
            Ok(_) => return Some(chunk),
            Err(now) => word = now,
        }
    }
}

/// Runs `op(c)` once for each chunk index `c` in `0..n` on the pool's threads and folds the
/// results with `merge`, which must be associative and commutative (the order of the calls
/// varies; what a call computes must not depend on it).
///
/// Why not rayon's split: rayon hands a loop's pieces to whichever thread asks first, so the
/// slots one thread wrote in a loop are, in the next, as likely processed on the other core,
/// which must fetch them from the first core's L2 cache. A 2D dam break's integrator sweep
/// took twice as long per slot on two threads as on one (phase timers, see [`crate::phases`]).
/// Here `0..n` is cut into one contiguous segment per thread in thread order, and each thread
/// works through its own: even threads from the segment's front, odd ones from its back, so
/// that two neighbouring segments are worked from their outer ends towards each other. A
/// thread whose segment is empty takes chunks from the segment with most left, at the end its
/// owner reaches last. Loops over the same slots thus give each thread about the same
/// slots, and the load still balances.
pub fn for_each_chunk<R: Send>(
    n: usize,
    identity: impl Fn() -> R + Sync,
    op: impl Fn(usize) -> R + Sync,
    merge: impl Fn(R, R) -> R + Sync,
) -> R {
    chunks_of::<R>(n, &identity, &op, &merge)
}

/// [`for_each_chunk`] compiled once per result type rather than once per caller: the callers
/// are many (the force loop in each of its variants), and the scheduling and rayon's `join`
/// machinery was compiled again around each of them (docs/benchmarks.md, "The release build").
/// The price is one indirect call per chunk.
fn chunks_of<R: Send>(
    n: usize,
    identity: &(dyn Fn() -> R + Sync),
    op: &(dyn Fn(usize) -> R + Sync),
    merge: &(dyn Fn(R, R) -> R + Sync),
) -> R {
    let threads = rayon::current_num_threads();
    if threads == 1 || n <= 1 || n > u32::MAX as usize {
        return (0..n).fold(identity(), |acc, c| merge(acc, op(c)));
    }
    let segments = threads.min(MAX_SEGMENTS).min(n);
    let state: [AtomicU64; MAX_SEGMENTS] = std::array::from_fn(|s| {
        let (front, back) = if s < segments { (s * n / segments, (s + 1) * n / segments) } else { (0, 0) };
        AtomicU64::new(pack(front, back))
    });
    let state = &state[..segments];
    let work = || {
        let own = rayon::current_thread_index().unwrap_or(0);
        let mut acc = identity();
        if own < segments {
            while let Some(c) = claim(&state[own], own.is_multiple_of(2)) {
                acc = merge(acc, op(c));
            }
        }
        loop {
            // the segment with most chunks left (the lowest on ties)
            let left = |s: usize| {
                let (front, back) = unpack(state[s].load(Ordering::Acquire));
                back.saturating_sub(front)
            };
            let (most, std::cmp::Reverse(s)) = (0..segments).map(|s| (left(s), std::cmp::Reverse(s))).max().expect("one segment at least");
            if most == 0 {
                break;
            }
            if let Some(c) = claim(&state[s], !s.is_multiple_of(2)) {
                acc = merge(acc, op(c));
            }
        }
        acc
    };
    workers(threads, &work, &merge)
}

/// Runs `count` copies of `work` under nested `rayon::join`s, so that each idle thread can take
/// one, and merges their results.
fn workers<R: Send>(count: usize, work: &(impl Fn() -> R + Sync), merge: &(impl Fn(R, R) -> R + Sync)) -> R {
    if count == 1 {
        return work();
    }
    let half = count / 2;
    let (a, b) = rayon::join(|| workers(half, work, merge), || workers(count - half, work, merge));
    merge(a, b)
}

/// Runs `op` while the pool's other threads poll for the work of its parallel loops instead of
/// going to sleep between them; they go back to rayon's usual idling when `op` returns.
///
/// Why: a rayon thread that finds no work yields to the OS some 32 times and then sleeps, and
/// waking it takes a futex call and, in a virtual machine, an interrupt to a halted virtual
/// CPU. A simulation step is a handful of parallel loops with short serial parts between
/// them, long enough for the second thread to fall asleep: it then started the next loop 15-60
/// us late, a few per cent of a 2D step on two threads (phase timers). OpenMP
/// runtimes spin before sleeping for the same reason (GOMP_SPINCOUNT, OMP_WAIT_POLICY).
pub fn with_workers_polling<R: Send>(op: impl FnOnce() -> R + Send) -> R {
    let pollers = rayon::current_num_threads().saturating_sub(1);
    if pollers == 0 || rayon::current_thread_index().is_none() {
        return op();
    }
    let done = AtomicBool::new(false);
    /// Sets `done` however `op` ends: a panic must not leave the pollers spinning.
    struct Finish<'a>(&'a AtomicBool);
    impl Drop for Finish<'_> {
        fn drop(&mut self) {
            self.0.store(true, Ordering::Release);
        }
    }
    let run = || {
        let _finish = Finish(&done);
        op()
    };
    rayon::join(run, || workers(pollers, &|| poll_until(&done), &|(), ()| ())).0
}

/// Runs pending rayon work until `done`.
fn poll_until(done: &AtomicBool) {
    let mut idle = 0u32;
    while !done.load(Ordering::Acquire) {
        if rayon::yield_now() == Some(rayon::Yield::Executed) {
            idle = 0;
            continue;
        }
        idle = idle.wrapping_add(1);
        // let the OS run something else now and then: on a busy host a poller holds a core
        if idle.is_multiple_of(256) {
            std::thread::yield_now();
        } else {
            std::hint::spin_loop();
        }
    }
}

/// Mutable chunks of a slice handed out by index to the tasks of [`for_each_chunk`], which gives
/// each index to one task only.
pub struct Chunks<'a, T> {
    ptr: *mut T,
    len: usize,
    chunk: usize,
    _slice: std::marker::PhantomData<&'a mut [T]>,
}

// SAFETY: a `Chunks` hands out disjoint `&mut` chunks, one per index, to the threads that claim
// them; it is as sendable as `&mut [T]`.
unsafe impl<T: Send> Sync for Chunks<'_, T> {}
unsafe impl<T: Send> Send for Chunks<'_, T> {}

impl<'a, T> Chunks<'a, T> {
    pub fn new(slice: &'a mut [T], chunk: usize) -> Self {
        assert!(chunk > 0, "chunk length must be positive");
        Chunks { ptr: slice.as_mut_ptr(), len: slice.len(), chunk, _slice: std::marker::PhantomData }
    }

    /// Number of chunks (the last may be shorter).
    pub fn count(&self) -> usize {
        self.len.div_ceil(self.chunk)
    }

    /// Chunk `c`.
    ///
    /// # Safety
    /// No other reference to chunk `c` may be live: call it once per index handed out by
    /// [`for_each_chunk`].
    #[allow(clippy::mut_from_ref)]
    pub unsafe fn get(&self, c: usize) -> &'a mut [T] {
        let start = c * self.chunk;
        assert!(start < self.len || (start == 0 && self.len == 0), "chunk {c} out of range");
        let len = self.chunk.min(self.len - start);
        // SAFETY: in bounds (asserted); disjoint from every other chunk handed out (caller).
        unsafe { std::slice::from_raw_parts_mut(self.ptr.add(start), len) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_on_a_pool_of_the_given_size_and_refuses_zero() {
        for threads in [1, 3, 1] {
            assert_eq!(on_threads(threads, rayon::current_num_threads).expect("pool"), threads);
        }
        match on_threads(0, || ()) {
            Err(Error::InvalidScene { field, .. }) => assert_eq!(field, "threads"),
            other => panic!("{other:?}"),
        }
    }

    /// Each chunk index of `0..n` is handed out exactly once, for any pool size (more threads
    /// than segments and than chunks included), and the results all reach the merge.
    #[test]
    fn every_chunk_runs_once_on_any_pool() {
        for threads in [1, 2, 3, 5, 70] {
            for n in [0, 1, 2, 3, 7, 64, 65, 1000] {
                let seen: Vec<AtomicU64> = (0..n).map(|_| AtomicU64::new(0)).collect();
                let (count, sum) = on_threads(threads, || {
                    for_each_chunk(
                        n,
                        || (0usize, 0usize),
                        |c| {
                            seen[c].fetch_add(1, Ordering::Relaxed);
                            (1, c)
                        },
                        |a, b| (a.0 + b.0, a.1 + b.1),
                    )
                })
                .expect("pool");
                assert!(seen.iter().all(|s| s.load(Ordering::Relaxed) == 1), "{threads} threads, {n} chunks");
                assert_eq!((count, sum), (n, n * n.saturating_sub(1) / 2), "{threads} threads, {n} chunks");
            }
        }
    }

    /// On two threads each thread's chunks form one contiguous run (the segments are worked
    /// from their outer ends towards each other), whoever finishes first.
    #[test]
    fn two_threads_split_the_chunks_into_two_runs() {
        let n = 200;
        let owner: Vec<AtomicU64> = (0..n).map(|_| AtomicU64::new(u64::MAX)).collect();
        on_threads(2, || {
            for_each_chunk(
                n,
                || (),
                |c| {
                    let t = rayon::current_thread_index().expect("on the pool");
                    owner[c].store(t as u64, Ordering::Relaxed);
                    // uneven work, so that stealing happens
                    std::hint::black_box((0..(c % 7) * 2000).sum::<usize>());
                },
                |_, _| (),
            )
        })
        .expect("pool");
        let owner: Vec<u64> = owner.iter().map(|o| o.load(Ordering::Relaxed)).collect();
        let switches = owner.windows(2).filter(|w| w[0] != w[1]).count();
        assert!(switches <= 1, "owners {owner:?}");
    }

    #[test]
    fn chunks_cover_the_slice_with_a_short_last_one() {
        let mut data: Vec<u32> = (0..10).collect();
        let chunks = Chunks::new(&mut data, 4);
        assert_eq!(chunks.count(), 3);
        // SAFETY: each index once
        let (a, b, c) = unsafe { (chunks.get(0), chunks.get(1), chunks.get(2)) };
        assert_eq!((a.len(), b.len(), c.len()), (4, 4, 2));
        c[1] = 99;
        assert_eq!(data[9], 99);
        assert_eq!(Chunks::new(&mut Vec::<u32>::new(), 4).count(), 0);
    }

    /// The result comes back on any pool size with loops inside running on every thread, and a
    /// panic in `op` reaches the caller instead of leaving the pollers spinning.
    #[test]
    fn polling_workers_run_the_loops_and_let_a_panic_through() {
        for threads in [1, 2, 3] {
            let sum = on_threads(threads, || {
                with_workers_polling(|| (0..50).map(|_| for_each_chunk(100, || 0, |c| c, |a, b| a + b)).sum::<usize>())
            })
            .expect("pool");
            assert_eq!(sum, 50 * 4950, "{threads} threads");
            let caught = std::panic::catch_unwind(|| on_threads(threads, || with_workers_polling(|| panic!("in op"))));
            assert!(caught.is_err(), "{threads} threads");
        }
    }
}
