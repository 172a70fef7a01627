#!/usr/bin/env bash
# Instructions and mispredicted branches per time step of a step_scene binary (cachegrind,
# one thread): the difference between 6 and 1 timed steps, divided by 5, so set-up and the
# three warm-up steps cancel. Deterministic, unlike timings on a shared machine.
#   scripts/perf_cachegrind.sh SCENE.json BIN
set -euo pipefail
scene=$1; bin=$2
for n in 1 6; do
  RAYON_NUM_THREADS=1 valgrind --tool=cachegrind --cache-sim=no --branch-sim=yes \
    --cachegrind-out-file=/dev/null "$bin" "$scene" "$n" 2>&1 | tr -d ',' |
    awk -v n="$n" '/I +refs/{i=$4} /Mispredicts/{m=$3} END{print n, i, m}'
done | python3 -c "
import sys
(_, i1, m1), (_, i6, m6) = [l.split() for l in sys.stdin]
print('instructions/step %.4g  mispredicted/step %.4g' % ((int(i6) - int(i1)) / 5, (int(m6) - int(m1)) / 5))
"
