//! Steps a scene given as a JSON file: a target for profilers (`perf record`, callgrind).
//!
//! `cargo run --release --example step_scene -- scene.json STEPS [WARMUP]` (WARMUP untimed
//! steps first, 3 by default: a developed flow sorts and moves more than the first steps do);
//! with `--features phase-timers` it also prints the wall time per phase of a step.
//! (`watersim bench --case dsph-dambreak3d` prints the same case's figure from Python; write a
//! case's scene with `python3 -c "import json, watersim.bench_cases as b;
//! print(json.dumps(b.dsph_scene('dsph-dambreak3d')))" > scene.json`.)

use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().expect("usage: step_scene SCENE.json [STEPS] [WARMUP]");
    let steps: u64 = args.next().map(|s| s.parse().expect("STEPS: an integer")).unwrap_or(20);
    let warmup: u64 = args.next().map(|s| s.parse().expect("WARMUP: an integer")).unwrap_or(3);
    let text = std::fs::read_to_string(&path).expect("read the scene file");
    let mut sim = sph_core::build_from_json(&text).unwrap_or_else(|e| panic!("{e}"));
    sim.step(warmup).unwrap_or_else(|e| panic!("{e}"));
    sph_core::phases::reset();
    let t0 = Instant::now();
    let cpu0 = process_cpu_seconds();
    sim.step(steps).unwrap_or_else(|e| panic!("{e}"));
    let wall = t0.elapsed().as_secs_f64();
    let cpu = process_cpu_seconds() - cpu0;
    let n = sim.n_particles() as f64;
    println!(
        "{} particles, {steps} steps, {:.3} s: {:.3} us per particle-step (cpu {:.3} us); state {:016x}",
        sim.n_particles(),
        wall,
        1e6 * wall / (n * steps as f64),
        1e6 * cpu / (n * steps as f64),
        state_digest(sim.as_ref())
    );
    if let Some(table) = sph_core::phases::report(steps) {
        println!("{table}");
    }
}

/// FNV-1a of positions, velocities and densities in particle-id order: equal exactly when the
/// states are bit-identical (a quick check that an optimisation changed no arithmetic).
fn state_digest(sim: &dyn sph_core::Simulation) -> u64 {
    let dim = sim.dim();
    let mut order: Vec<usize> = (0..sim.n_particles()).collect();
    order.sort_by_key(|&i| sim.ids()[i]);
    let mut hash = 0xcbf2_9ce4_8422_2325u64;
    let mut eat = |x: f64| {
        for byte in x.to_le_bytes() {
            hash = (hash ^ byte as u64).wrapping_mul(0x100_0000_01b3);
        }
    };
    for &i in &order {
        for k in 0..dim {
            eat(sim.positions()[i * dim + k]);
            eat(sim.velocities()[i * dim + k]);
        }
        eat(sim.densities()[i]);
    }
    hash
}

/// CPU time of this process (all threads, user + system) from /proc/self/stat [s]: on a shared
/// machine it moves far less than the wall time when other jobs compete for the cores.
fn process_cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // fields after the command name's closing parenthesis; utime and stime are fields 14, 15
    let rest = stat.rsplit_once(')').map(|(_, r)| r).unwrap_or("");
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| f.get(i).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.0);
    (ticks(11) + ticks(12)) / 100.0
}
