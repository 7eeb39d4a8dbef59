#!/usr/bin/env bash
# The Python package's benchmarks (benches/python_bench.py; docs/benchmarks.md#python):
#
#   benches/python-bench.sh [WHEEL] [-- ARGS...]
#
# Installs WHEEL (default: builds one with `.venv/bin/maturin build --release` into
# target/wheels) with numpy, mujoco, gymnasium and myosuite into the bench venv ($BENCH_VENV, default
# target/bench-venv; created when missing), builds the `limb` bench binary (release) and runs
# benches/python_bench.py with it, passing ARGS on (--reps N, --skip overhead,throughput,mujoco,gym,myosuite).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/lib.sh"
cd "$ROOT"
TARGET="$(target_dir)"
wheel=""
if [ $# -gt 0 ] && [ "$1" != -- ]; then
  wheel="$(realpath "$1")"
  shift
fi
[ "${1:-}" = -- ] && shift

if [ -z "$wheel" ]; then
  echo "[python-bench] building the wheel (maturin build --release)" >&2
  mkdir -p "$TARGET/wheels"
  stamp="$(mktemp "$TARGET/wheels/.bench-XXXXXX")"
  trap 'rm -f "$stamp"' EXIT
  .venv/bin/maturin build --release --quiet -m python/Cargo.toml --out "$TARGET/wheels" >&2
  wheel="$(find "$TARGET/wheels" -maxdepth 1 -name 'muscle_actuator-*.whl' -newer "$stamp" | head -n 1)"
  rm -f "$stamp"
  [ -n "$wheel" ] || { echo "[python-bench] maturin wrote no wheel to $TARGET/wheels" >&2; exit 1; }
fi

VENV="${BENCH_VENV:-$TARGET/bench-venv}"
[ -x "$VENV/bin/python" ] || python3 -m venv "$VENV"
if ! "$VENV/bin/python" -c 'import numpy, mujoco, gymnasium, myosuite' 2>/dev/null; then
  "$VENV/bin/pip" install --quiet numpy mujoco gymnasium myosuite >&2
fi
"$VENV/bin/pip" install --quiet --no-deps --force-reinstall "$wheel" >&2
echo "[python-bench] $(basename "$wheel") in $VENV" >&2

echo "[python-bench] building benches/limb.rs (cargo bench --no-run)" >&2
limb="$(cargo bench --quiet --bench limb --no-run --message-format=json \
  | "$VENV/bin/python" -c '
import json, sys
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m["target"]["name"] == "limb" and m.get("executable"):
        print(m["executable"])')"
[ -x "$limb" ] || { echo "[python-bench] no limb bench binary found" >&2; exit 1; }

exec "$VENV/bin/python" "$ROOT/benches/python_bench.py" --limb-bin "$limb" "$@"
