#!/usr/bin/env bash
# The ROS 2 tests: a real rclpy peer (ROS 2 kilted from PyPI, Fast DDS) against our node.
#
#   scripts/test-ros.sh [pytest args...]     e.g. scripts/test-ros.sh -k params -x
#
# Creates/updates the Python environment (scripts/py-env.sh), builds the node (debug), then runs
# pytest on tests/python/ inside a fresh network namespace with only loopback up when the
# machine allows it (root + unshare), and always with loopback-only discovery and a
# test-specific ROS_DOMAIN_ID. Exits with pytest's exit code.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

VENV="$("$ROOT/scripts/py-env.sh" | tail -n 1)"

TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
case "$TARGET_DIR" in /*) ;; *) TARGET_DIR="$ROOT/$TARGET_DIR" ;; esac
BIN="$TARGET_DIR/debug/muscle_actuator"
# scripts/test-all.sh sets MUSCLE_ACTUATOR_BUILT=1: its `cargo test --all-targets` has just built
# this binary (the integration tests run it), and a plain `cargo build` would compile the crate
# again with other features (dev-dependencies unify features differently).
if [ "${MUSCLE_ACTUATOR_BUILT:-}" != 1 ] || [ ! -x "$BIN" ]; then
  echo "[test-ros] building the node (cargo build)" >&2
  cargo build --quiet --bin muscle_actuator
fi
[ -x "$BIN" ] || { echo "[test-ros] no binary at $BIN" >&2; exit 1; }

export MUSCLE_ACTUATOR_BIN="$BIN"
export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
unset ROS_LOCALHOST_ONLY
export ROS_DOMAIN_ID="${MUSCLE_ACTUATOR_TEST_DOMAIN:-$((120 + $$ % 80))}"
export PYTHONDONTWRITEBYTECODE=1

# Default to the whole suite unless a test path was given.
DEFAULT_PATH=("$ROOT/tests/python")
for a in "$@"; do
  case "$a" in -*) ;; *) if [ -e "${a%%::*}" ]; then DEFAULT_PATH=(); fi ;; esac
done
PYTEST=("$VENV/bin/python" -m pytest -p no:cacheprovider "${DEFAULT_PATH[@]}" "$@")

if [ "${MUSCLE_ACTUATOR_NO_NETNS:-}" != 1 ] && command -v unshare >/dev/null && command -v ip >/dev/null \
  && unshare -n true 2>/dev/null; then
  echo "[test-ros] running in a loopback-only network namespace (domain $ROS_DOMAIN_ID)" >&2
  set +e
  unshare -n bash -c 'ip link set lo up && exec "$@"' bash "${PYTEST[@]}"
  rc=$?
else
  echo "[test-ros] no network namespace here: loopback-only discovery (domain $ROS_DOMAIN_ID)" >&2
  set +e
  "${PYTEST[@]}"
  rc=$?
fi
exit $rc
