#!/usr/bin/env bash
# Runs one of the Python node benchmarks: benches/py-bench.sh SCRIPT [--release] [ARGS...]
# Builds the node (debug by default; --release for the figures that matter), prepares the
# Python environment, and runs benches/SCRIPT on loopback only (in a fresh network namespace
# when root).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
script="$1"
shift
profile=debug
args=()
for a in "$@"; do
  if [ "$a" = --release ]; then profile=release; else args+=("$a"); fi
done
VENV="$("$ROOT/scripts/py-env.sh" | tail -n 1)"
if [ $profile = release ]; then cargo build --quiet --release --bin muscle_actuator; else cargo build --quiet --bin muscle_actuator; fi
BIN="${CARGO_TARGET_DIR:-$ROOT/target}/$profile/muscle_actuator"
export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST ROS_DOMAIN_ID="${ROS_DOMAIN_ID:-$((120 + $$ % 80))}"
cmd=("$VENV/bin/python" "$ROOT/benches/$script" --bin "$BIN" "${args[@]}")
if [ "$(id -u)" = 0 ] && unshare -n true 2>/dev/null; then
  exec unshare -n bash -c 'ip link set lo up && exec "$@"' bash "${cmd[@]}"
fi
exec "${cmd[@]}"
