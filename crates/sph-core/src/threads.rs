//! Running work on a given number of threads, for timing one thread count against another in
//! one process (`watersim bench --compare-threads`): on a shared host single runs scatter by
//! 10-30 % from one minute to the next, and two thread counts timed in alternation, each run
//! next to the other, drift together. Results do not depend on the thread count, so one
//! simulation can alternate between pools and follow the same trajectory.

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
}
