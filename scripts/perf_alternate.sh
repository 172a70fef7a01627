#!/usr/bin/env bash
# Timing of step_scene binaries on one core when the other is busy: the binaries run one after
# the other on core 0, alternating, REPS times; prints each binary's median CPU time per
# particle-step. (scripts/perf_pair.sh needs both cores.)
#   scripts/perf_alternate.sh SCENE.json STEPS REPS BIN...
set -euo pipefail
scene=$1; steps=$2; reps=$3; shift 3
for r in $(seq "$reps"); do
  for b in "$@"; do
    echo "$b $(RAYON_NUM_THREADS=1 taskset -c 0 "$b" "$scene" "$steps" | sed -E 's/.*cpu ([0-9.]+) us.*/\1/')"
  done
done | python3 -c "
import collections, statistics as st, sys
runs = collections.defaultdict(list)
for line in sys.stdin:
    b, v = line.split()
    runs[b].append(float(v))
for b, v in runs.items():
    print(b, 'median', st.median(v), v)
"
