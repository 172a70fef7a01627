#!/usr/bin/env bash
# What the host gives two busy cores, against what two threads get: alternating REPS times,
#   lone: one thread on core 0, the other core idle;
#   pair: two one-thread runs at once, one per core (the same work, no sharing of the step);
#   two:  one run on two threads.
# Prints the medians of the wall time per particle-step and three ratios: lone / two (the
# speed-up the issue measures), lone / pair (what the host itself loses when both cores are
# busy: shared cache, memory, clock), and pair / two (the speed-up the solver gets out of the
# two cores it is given: 2.0 is perfect parallel scaling on this host).
#   scripts/perf_host_share.sh SCENE.json STEPS WARMUP REPS BIN
set -euo pipefail
scene=$1; steps=$2; warm=$3; reps=$4; bin=$5
us() { sed -E 's/.*: ([0-9.]+) us per.*/\1/'; }
for r in $(seq "$reps"); do
  echo "lone $(RAYON_NUM_THREADS=1 taskset -c 0 "$bin" "$scene" "$steps" "$warm" | us)"
  a=$(mktemp); b=$(mktemp)
  RAYON_NUM_THREADS=1 taskset -c 0 "$bin" "$scene" "$steps" "$warm" > "$a" &
  RAYON_NUM_THREADS=1 taskset -c 1 "$bin" "$scene" "$steps" "$warm" > "$b" &
  wait
  echo "pair $(us < "$a")"; echo "pair $(us < "$b")"; rm -f "$a" "$b"
  echo "two $(RAYON_NUM_THREADS=2 "$bin" "$scene" "$steps" "$warm" | us)"
done | python3 -c "
import collections, statistics as st, sys
runs = collections.defaultdict(list)
for line in sys.stdin:
    kind, value = line.split()
    runs[kind].append(float(value))
m = {k: st.median(v) for k, v in runs.items()}
for k in ('lone', 'pair', 'two'):
    print(f'{k}: median {m[k]:.3f} us per particle-step {runs[k]}')
print(f'lone / two {m[\"lone\"] / m[\"two\"]:.2f}; lone / pair {m[\"lone\"] / m[\"pair\"]:.2f}; '
      f'pair / two {m[\"pair\"] / m[\"two\"]:.2f}')
"
