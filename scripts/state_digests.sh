#!/usr/bin/env bash
# The state digests a refactor must keep bit for bit: step_scene (release) on the four scenes of
# crates/sph-core/examples/scenes/ at one and two threads, compared with digests.txt there.
#   scripts/state_digests.sh           check (exit 1 on any difference)
#   scripts/state_digests.sh --write   record the current digests as the expected ones
# The scenes are the core's JSON, committed, so the check does not depend on the Python side.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
dir=crates/sph-core/examples/scenes
cargo build -q --release --example step_scene
bin=target/release/examples/step_scene
# scene  steps  warm-up
cases="dambreak2d 300 3000
piston2d_dbc 100 1000
piston2d_adami 100 1000
dambreak3d 10 20"
got=""
while read -r name steps warmup; do
  for threads in 1 2; do
    line=$(RAYON_NUM_THREADS=$threads "$bin" "$dir/$name.json" "$steps" "$warmup" | head -n 1)
    digest=${line##*state }
    echo "$name threads=$threads $digest"
    got+="$name $threads $digest"$'\n'
  done
done <<< "$cases"
if [ "${1:-}" = "--write" ]; then
  printf '%s' "$got" > "$dir/digests.txt"
  echo "written: $dir/digests.txt"
elif diff <(printf '%s' "$got") "$dir/digests.txt"; then
  echo "state digests unchanged"
else
  echo "state digests differ from $dir/digests.txt" >&2
  exit 1
fi
