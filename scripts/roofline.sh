#!/usr/bin/env bash
# The fluid force loop against the core's floating-point peak on the DualSPHysics benchmark
# cases (docs/benchmarks.md, "Distance to the floor"): each case's scene written from
# watersim.bench_cases, then examples/pair_flops.rs (counted operations of one force
# evaluation, the real loop timed on the same state, the clock measured) on one pinned thread.
#   scripts/roofline.sh [CORE] [CASE ...]     (default core 0; default cases: the three dsph-*)
# Needs the watersim package importable (PYTHONPATH=python with its built extension, or
# installed) for the scenes.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
core=${1:-0}
shift || true
cases=${*:-dsph-dambreak3d dsph-dambreak2d dsph-piston2d}
cargo build -q --release --features flop-count -p sph-core --example pair_flops
bin=target/release/examples/pair_flops
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for case in $cases; do
  python3 -c "import json, sys, watersim.bench_cases as b; json.dump(b.dsph_scene(sys.argv[1]), sys.stdout)" \
    "$case" > "$dir/$case.json"
  echo "== $case"
  RAYON_NUM_THREADS=1 taskset -c "$core" "$bin" "$dir/$case.json" 20 20
done
