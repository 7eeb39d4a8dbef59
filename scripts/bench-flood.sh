#!/usr/bin/env bash
# Flood benchmark: quiet vs flooded windows of the release node, skipped ticks and lateness.
#
#   scripts/bench-flood.sh [--bin PATH] [bench_flood.py args...]
#     e.g. scripts/bench-flood.sh --runs 5 --duration 10 --record off
#
# Without --bin, builds the release node (cargo build --release; honours CARGO_TARGET_DIR).
# Prepares the Python environment (scripts/py-env.sh), then runs scripts/bench_flood.py on
# loopback only (scripts/lib.sh): in a fresh network namespace when root, always with
# loopback-only discovery and a domain of its own; its rclpy publishers use the tests' Fast DDS
# profile (tests/python/fastdds_profile.xml). A benchmark, not a test: it prints a table and
# asserts nothing.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cd "$ROOT"
have_bin=0
for a in "$@"; do [ "$a" = --bin ] && have_bin=1; done
VENV="$(python_env)"
args=("$@")
if [ $have_bin = 0 ]; then
  cargo build --quiet --release --bin muscle_actuator
  args=(--bin "$(target_dir)/release/muscle_actuator" "${args[@]}")
fi
loopback_env
export ROS_DISTRO="${ROS_DISTRO:-kilted}"
export FASTDDS_DEFAULT_PROFILES_FILE="${FASTDDS_DEFAULT_PROFILES_FILE:-$ROOT/tests/python/fastdds_profile.xml}"
exec_on_loopback bench-flood "$VENV/bin/python" "$ROOT/scripts/bench_flood.py" "${args[@]}"
