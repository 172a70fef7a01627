#!/usr/bin/env bash
# Paired timing of two step_scene binaries on a noisy 2-core machine: A and B run at the same
# time, one pinned to each core, swapped each repetition; prints the medians of the CPU time per
# particle-step and their ratio.
#   scripts/perf_pair.sh SCENE.json STEPS REPS BIN_A BIN_B
# Build a binary with `cargo build --release --example step_scene` and copy
# target/release/examples/step_scene aside; write a scene with
#   python3 -c "import json, watersim.bench_cases as b; print(json.dumps(b.dsph_scene('dsph-piston2d')))" > piston.json
set -euo pipefail
scene=$1; steps=$2; reps=$3; A=$4; B=$5
out=$(mktemp -d)
for r in $(seq "$reps"); do
  RAYON_NUM_THREADS=1 taskset -c 0 "$A" "$scene" "$steps" > "$out/a.$r" &
  RAYON_NUM_THREADS=1 taskset -c 1 "$B" "$scene" "$steps" > "$out/b.$r" &
  wait
  RAYON_NUM_THREADS=1 taskset -c 1 "$A" "$scene" "$steps" > "$out/a2.$r" &
  RAYON_NUM_THREADS=1 taskset -c 0 "$B" "$scene" "$steps" > "$out/b2.$r" &
  wait
done
python3 - "$out" "$A" "$B" <<'PY'
import glob, re, statistics as st, sys
out, a_name, b_name = sys.argv[1:]
def cpu(prefix):
    return [float(re.search(r"cpu ([0-9.]+) us", open(f).read()).group(1)) for f in sorted(glob.glob(f"{out}/{prefix}*"))]
a, b = cpu("a"), cpu("b")
print(f"{a_name}: median {st.median(a):.3f} us  {b_name}: median {st.median(b):.3f} us  "
      f"ratio B/A {st.median(b) / st.median(a):.3f}  A {a}  B {b}")
PY
rm -rf "$out"
