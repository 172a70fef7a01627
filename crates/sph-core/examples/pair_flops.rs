//! The fluid force loop against the core's floating-point peak (docs/benchmarks.md, "Distance
//! to the floor"):
//!
//! `RAYON_NUM_THREADS=1 taskset -c 0 cargo run --release --features flop-count --example
//! pair_flops -- SCENE.json [WARMUP] [REPEATS] [OPS_PER_CYCLE]`
//!
//! Steps the scene WARMUP steps (default 20), counts the floating-point operations of one fluid
//! force evaluation on that state (`physics::flop_count`: the pair terms, every SIMD lane
//! executed), times REPEATS (default 20) evaluations of the real loop on the same state, and
//! measures the core's clock with a chain of dependent integer additions (one per cycle). The
//! peak is OPS_PER_CYCLE (default 4: two additions and two multiplications per cycle, AMD Zen
//! 2-4 without fused multiply-add, which the loop does not use; 2 on Intel cores whose two FMA
//! ports do either) times the lanes of an AVX2 register of the pair float (8 in f32, 4 in f64).
//! `scripts/roofline.sh` runs it on the DualSPHysics benchmark cases.

use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().expect("usage: pair_flops SCENE.json [WARMUP] [REPEATS] [OPS_PER_CYCLE]");
    let warmup: u64 = args.next().map(|s| s.parse().expect("WARMUP: an integer")).unwrap_or(20);
    let repeats: u32 = args.next().map(|s| s.parse().expect("REPEATS: an integer")).unwrap_or(20);
    let ops_per_cycle: f64 = args.next().map(|s| s.parse().expect("OPS_PER_CYCLE: a number")).unwrap_or(4.0);
    let text = std::fs::read_to_string(&path).expect("read the scene file");
    let mut sim = sph_core::build_from_json(&text).unwrap_or_else(|e| panic!("{e}"));
    sim.step(warmup).unwrap_or_else(|e| panic!("{e}"));
    let Some(r) = sim.pair_flops(repeats) else {
        eprintln!("{path}: this scene runs the pair-at-a-time loop (SPS or kernel correction); nothing to count");
        std::process::exit(2);
    };
    if !r.same_bits {
        eprintln!("{path}: the counted evaluation differs from the real loop: the counts are not the loop's");
        std::process::exit(1);
    }
    let mut t = r.loop_seconds.clone();
    t.sort_by(f64::total_cmp);
    let median = t[t.len() / 2];
    let ghz = clock_ghz();
    let single = sim.params().force_precision == "f32";
    let lanes = if single { 8.0 } else { 4.0 };
    let peak = ghz * ops_per_cycle * lanes;
    let (o, pairs) = (r.ops, r.pairs as f64);
    let flops = o.flops() as f64;
    let gflops = flops / median / 1e9;
    println!("{path}: {} fluid particles, {} pairs in the support, {} lanes executed ({:.1} % padding and self-pairs)", sim.n_fluid(), r.pairs, o.lanes, 100.0 * (o.lanes as f64 / pairs - 1.0));
    println!(
        "per pair: {:.1} flop ({:.1} add, {:.1} mul, {:.2} div, {:.2} sqrt; {:.1} comparisons), {:.1} flop per lane",
        flops / pairs,
        o.add as f64 / pairs,
        o.mul as f64 / pairs,
        o.div as f64 / pairs,
        o.sqrt as f64 / pairs,
        o.cmp as f64 / pairs,
        flops / o.lanes as f64
    );
    let best = t[0];
    println!(
        "fluid loop: median {:.3} ms of {repeats}, best {:.3}, worst {:.3}; {:.2} ns and {:.1} cycles per pair at {ghz:.2} GHz (median; best {:.2} ns, {:.1} cycles)",
        1e3 * median,
        1e3 * best,
        1e3 * t[t.len() - 1],
        1e9 * median / pairs,
        ghz * 1e9 * median / pairs,
        1e9 * best / pairs,
        ghz * 1e9 * best / pairs
    );
    let gflops_best = flops / best / 1e9;
    println!(
        "{gflops:.2} GFLOP/s = {:.1} % of the {} peak {peak:.1} GFLOP/s ({ops_per_cycle} ops x {lanes} lanes per cycle); best {gflops_best:.2} GFLOP/s = {:.1} %",
        100.0 * gflops / peak,
        if single { "f32" } else { "f64" },
        100.0 * gflops_best / peak
    );
}

/// The core's clock [GHz]: four dependent additions per loop iteration take four cycles
/// (the counter's decrement and branch run beside them); the best of five runs of 0.1 s.
#[cfg(target_arch = "x86_64")]
fn clock_ghz() -> f64 {
    let n: u64 = 100_000_000;
    (0..5)
        .map(|_| {
            let t0 = Instant::now();
            // SAFETY: register arithmetic only.
            unsafe {
                std::arch::asm!(
                    "2:",
                    "add {x}, 1",
                    "add {x}, 1",
                    "add {x}, 1",
                    "add {x}, 1",
                    "dec {n}",
                    "jnz 2b",
                    x = inout(reg) 0u64 => _,
                    n = inout(reg) n => _,
                    options(nomem, nostack),
                );
            }
            4.0 * n as f64 / t0.elapsed().as_secs_f64() / 1e9
        })
        .fold(0.0, f64::max)
}

#[cfg(not(target_arch = "x86_64"))]
fn clock_ghz() -> f64 {
    panic!("the clock measurement is written for x86-64");
}
