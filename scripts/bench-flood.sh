#!/usr/bin/env bash
# Flood benchmark: quiet vs flooded windows of the release node, skipped ticks and lateness.
#
#   scripts/bench-flood.sh [--bin PATH] [bench_flood.py args...]
#     e.g. scripts/bench-flood.sh --runs 5 --duration 10 --record off
#
# Without --bin, builds the release node (cargo build --release; honours CARGO_TARGET_DIR).
# Prepares the Python environment (scripts/py-env.sh), then runs scripts/bench_flood.py on
# loopback only: in a fresh network namespace when root, always with loopback-only discovery
# and a domain of its own. A benchmark, not a test: it prints a table and asserts nothing.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
have_bin=0
for a in "$@"; do [ "$a" = --bin ] && have_bin=1; done
VENV="$("$ROOT/scripts/py-env.sh" | tail -n 1)"
args=("$@")
if [ $have_bin = 0 ]; then
  cargo build --quiet --release --bin muscle_actuator
  TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
  case "$TARGET_DIR" in /*) ;; *) TARGET_DIR="$ROOT/$TARGET_DIR" ;; esac
  args=(--bin "$TARGET_DIR/release/muscle_actuator" "${args[@]}")
fi
export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
unset ROS_LOCALHOST_ONLY
export ROS_DOMAIN_ID="${ROS_DOMAIN_ID:-$((120 + $$ % 80))}"
export ROS_DISTRO="${ROS_DISTRO:-kilted}"
export FASTDDS_DEFAULT_PROFILES_FILE="${FASTDDS_DEFAULT_PROFILES_FILE:-$ROOT/tests/python/fastdds_profile.xml}"
export PYTHONDONTWRITEBYTECODE=1
cmd=("$VENV/bin/python" "$ROOT/scripts/bench_flood.py" "${args[@]}")
if [ "${MUSCLE_ACTUATOR_NO_NETNS:-}" != 1 ] && [ "$(id -u)" = 0 ] && command -v ip >/dev/null \
  && unshare -n true 2>/dev/null; then
  exec unshare -n bash -c 'ip link set lo up && exec "$@"' bash "${cmd[@]}"
fi
echo "[bench-flood] no network namespace here: loopback-only discovery (domain $ROS_DOMAIN_ID)" >&2
exec "${cmd[@]}"
