//! Criterion benchmarks of the hot loops on dam-break scenes: the neighbour search (cell sort and
//! stencil walk) and one force evaluation (sort, EOS, forces). Run with
//! `cargo bench -p sph-core --bench hot_loops`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use sph_core::math::{Dim, Dim2, Dim3, Vector};
use sph_core::neighbours::{CellGrid, GROUP_FLUID};
use sph_core::{Scene, Solver, WendlandC2};

/// DualSPHysics' CaseDambreakVal2D geometry (column 1 x 2 m in a 4 m tank) and a 3D analogue.
fn dambreak(dim: usize, dp: f64) -> Scene {
    let json = if dim == 2 {
        format!(
            r#"{{"dim": 2, "dp": {dp}, "tank": {{"min": [0, 0], "max": [4, 2.4]}},
                "fluid": [{{"min": [0, 0], "max": [1, 2]}}], "viscosity": {{"model": "artificial", "alpha": 0.02}}}}"#
        )
    } else {
        format!(
            r#"{{"dim": 3, "dp": {dp}, "tank": {{"min": [0, 0, 0], "max": [1.6, 0.67, 0.4]}},
                "fluid": [{{"min": [0, 0, 0], "max": [0.4, 0.67, 0.3]}}], "viscosity": {{"model": "artificial", "alpha": 0.1}}}}"#
        )
    };
    Scene::from_json(&json).expect("valid bench scene")
}

fn neighbour_search<D: Dim>(c: &mut Criterion, name: &str, scene: Scene) {
    let solver = Solver::<D, WendlandC2>::new(scene).expect("solver");
    let p = solver.particles();
    let pos: Vec<D::V> = p.pos.clone();
    let n = pos.len();
    let support = solver.constants().support;
    let (mut lo, mut hi) = (pos[0], pos[0]);
    for &x in &pos {
        lo = lo.min(x);
        hi = hi.max(x);
    }
    let mut grid = CellGrid::<D>::new(lo, hi, support, 2);
    let mut keys = vec![0u32; n];
    let mut perm = vec![0u32; n];
    let mut group = c.benchmark_group(format!("neighbours/{name}"));
    group.throughput(Throughput::Elements(n as u64));
    group.bench_function(BenchmarkId::new("sort", n), |b| {
        b.iter(|| grid.sort_group(GROUP_FLUID, 0..n, &pos, &mut perm, &mut keys));
    });
    let sorted: Vec<D::V> = perm.iter().map(|&i| pos[i as usize]).collect();
    grid.sort_group(GROUP_FLUID, 0..n, &sorted, &mut perm, &mut keys);
    group.bench_function(BenchmarkId::new("count_pairs", n), |b| {
        b.iter(|| {
            use rayon::prelude::*;
            let s2 = support * support;
            sorted
                .par_iter()
                .map(|&x| {
                    let mut k = 0usize;
                    grid.for_each_near(GROUP_FLUID, x, |j| k += ((x - sorted[j]).length_squared() < s2) as usize);
                    k
                })
                .sum::<usize>()
        });
    });
    group.finish();
}

fn force_loop<D: Dim>(c: &mut Criterion, name: &str, scene: Scene) {
    let mut solver = Solver::<D, WendlandC2>::new(scene).expect("solver");
    let n = solver.particles().len();
    let mut group = c.benchmark_group(format!("forces/{name}"));
    group.throughput(Throughput::Elements(n as u64));
    group.bench_function(BenchmarkId::new("artificial_fourtakas", n), |b| b.iter(|| solver.compute_forces()));
    group.finish();
}

fn benches(c: &mut Criterion) {
    neighbour_search::<Dim2>(c, "dambreak2d", dambreak(2, 0.01));
    neighbour_search::<Dim3>(c, "dambreak3d", dambreak(3, 0.01));
    force_loop::<Dim2>(c, "dambreak2d", dambreak(2, 0.01));
    force_loop::<Dim3>(c, "dambreak3d", dambreak(3, 0.01));
}

criterion_group! {
    name = hot_loops;
    config = Criterion::default().sample_size(20);
    targets = benches
}
criterion_main!(hot_loops);
