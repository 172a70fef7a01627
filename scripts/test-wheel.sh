#!/usr/bin/env bash
# Build the release wheel and run the test suite against the *installed* wheel.
#
#   scripts/test-wheel.sh            # PYTHON=python3.12 scripts/test-wheel.sh for another Python
#   KEEP=1 scripts/test-wheel.sh     # keep the temporary folder (wheel, venv) for inspection
#
# Steps: `maturin build --release` into a temporary folder; a fresh virtual environment there;
# the wheel installed into it with its [test] extras; then pytest on this repository's tests/,
# started from a folder outside the source tree and without PYTHONPATH, so `import watersim`
# can only find the installed wheel (tests/test_run_outputs.py checks it, WATERSIM_TEST_INSTALLED
# =1). Data files the package needs at run time must therefore be package data
# (python/watersim/data), which this catches. The tests still read examples/ and docs/ from the
# source tree, as files.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
python="${PYTHON:-python3}"
maturin="${MATURIN:-maturin}"
work="$(mktemp -d "${TMPDIR:-/tmp}/watersim-wheel.XXXXXX")"

cleanup() {
  if [ "${KEEP:-0}" = "1" ]; then
    echo "test-wheel: kept $work"
  else
    rm -rf "$work"
  fi
}
trap cleanup EXIT

echo "test-wheel: building the release wheel (maturin build --release)"
(cd "$root" && "$maturin" build --release --interpreter "$python" --out "$work/dist")

shopt -s nullglob
wheels=("$work"/dist/watersim-*.whl)
shopt -u nullglob
if [ "${#wheels[@]}" -ne 1 ]; then
  echo "test-wheel: expected one wheel in $work/dist, found ${#wheels[@]}" >&2
  exit 1
fi
wheel="${wheels[0]}"

echo "test-wheel: fresh virtual environment in $work/venv"
"$python" -m venv "$work/venv"
venv_python="$work/venv/bin/python"
"$venv_python" -m pip install --quiet --upgrade pip
"$venv_python" -m pip install --quiet "${wheel}[test]"

mkdir -p "$work/run"
cd "$work/run"
unset PYTHONPATH

# The package imported from here must be the installed one.
location="$("$venv_python" -c 'import watersim; print(watersim.__file__)')"
case "$location" in
  "$work/venv/"*) echo "test-wheel: testing $location" ;;
  *)
    echo "test-wheel: watersim imports from $location, not from the wheel" >&2
    exit 1
    ;;
esac

WATERSIM_TEST_INSTALLED=1 "$venv_python" -m pytest -q \
  -c "$root/pyproject.toml" --rootdir "$root" -p no:cacheprovider "$root/tests" "$@"
