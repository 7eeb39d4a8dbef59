#!/usr/bin/env bash
# Runs one of the rclpy benchmarks of the node: benches/rclpy-bench.sh SCRIPT [--release] [ARGS...]
# Builds the node (debug by default; --release for the figures that matter), prepares the
# Python environment, and runs benches/SCRIPT on loopback only (scripts/lib.sh: in a fresh
# network namespace when root, always with loopback-only discovery and a domain of its own).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/lib.sh"
cd "$ROOT"
script="$1"
shift
profile=debug
args=()
for a in "$@"; do
  if [ "$a" = --release ]; then profile=release; else args+=("$a"); fi
done
VENV="$(python_env)"
if [ $profile = release ]; then cargo build --quiet --release --bin muscle_actuator; else cargo build --quiet --bin muscle_actuator; fi
loopback_env
exec_on_loopback rclpy-bench "$VENV/bin/python" "$ROOT/benches/$script" --bin "$(target_dir)/$profile/muscle_actuator" "${args[@]}"
