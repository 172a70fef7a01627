#!/usr/bin/env bash
# One and two threads of step_scene binaries, alternating: each binary runs on one thread
# (pinned to core 0) and on two, REPS times in turn; prints the medians of the wall time per
# particle-step, their ratio, and the state digests (one digest when every binary computes the
# same state, as an optimisation that changes no arithmetic must).
#   scripts/perf_threads.sh SCENE.json STEPS WARMUP REPS BIN...
# WARMUP untimed steps first (a developed flow sorts and moves more than the first steps).
set -euo pipefail
scene=$1; steps=$2; warm=$3; reps=$4; shift 4
for r in $(seq "$reps"); do
  for b in "$@"; do
    echo "$b 1 $(RAYON_NUM_THREADS=1 taskset -c 0 "$b" "$scene" "$steps" "$warm")"
    echo "$b 2 $(RAYON_NUM_THREADS=2 "$b" "$scene" "$steps" "$warm")"
  done
done | python3 -c "
import collections, re, statistics as st, sys
runs, states = collections.defaultdict(list), set()
for line in sys.stdin:
    b, t, rest = line.split(' ', 2)
    runs[(b, t)].append(float(re.search(r': ([0-9.]+) us per', rest).group(1)))
    states.add(re.search(r'state (\w+)', rest).group(1))
for b in dict.fromkeys(k[0] for k in runs):
    one, two = runs[(b, '1')], runs[(b, '2')]
    print(f'{b}: 1 thread {st.median(one):.3f} us {one}; 2 threads {st.median(two):.3f} us {two}; '
          f'ratio {st.median(one) / st.median(two):.2f}')
print('state digests:', ' '.join(sorted(states)))
"
