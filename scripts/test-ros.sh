#!/usr/bin/env bash
# The ROS 2 tests: a real rclpy peer (ROS 2 kilted from PyPI, Fast DDS) against our node.
#
#   scripts/test-ros.sh [pytest args...]     e.g. scripts/test-ros.sh -k params -x
#
# Creates/updates the Python environment (scripts/py-env.sh), builds the node (debug), then runs
# pytest on tests/python/ inside a fresh network namespace with only loopback up when the
# machine allows it (root + unshare; MUSCLE_ACTUATOR_NO_NETNS=1 to run without), and always with
# loopback-only discovery and a test-specific ROS_DOMAIN_ID (MUSCLE_ACTUATOR_TEST_DOMAIN to
# choose it); scripts/lib.sh has the set-up. Exits with pytest's exit code.
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cd "$ROOT"

VENV="$(python_env)"

# The Foxglove test client's packages (tests/foxglove, for tests/python/test_foxglove.py), from
# its lock file with `npm ci`; skipped while node_modules holds what the lock file says (a stamp
# of its hash). Before the network namespace: npm needs the registry. A failure here fails that
# test module only.
FOX="$ROOT/tests/foxglove"
fox_hash="$(sha256sum "$FOX/package-lock.json" | cut -c1-16)"
if ! command -v npm >/dev/null; then
  echo "[test-ros] no npm: tests/foxglove's packages not installed" >&2
elif [ "$(cat "$FOX/node_modules/.stamp-lock" 2>/dev/null || true)" != "$fox_hash" ]; then
  echo "[test-ros] installing the Foxglove test client's packages (npm ci)" >&2
  if (cd "$FOX" && npm ci --no-audit --no-fund --loglevel=error >&2); then
    echo "$fox_hash" >"$FOX/node_modules/.stamp-lock"
  else
    echo "[test-ros] npm ci failed in tests/foxglove: test_foxglove.py will fail" >&2
  fi
fi

BIN="$(target_dir)/debug/muscle_actuator"
# scripts/test-all.sh sets MUSCLE_ACTUATOR_BUILT=1: its `cargo test --all-targets` has just built
# this binary (the integration tests run it), and a plain `cargo build` would compile the crate
# again with other features (dev-dependencies unify features differently).
if [ "${MUSCLE_ACTUATOR_BUILT:-}" != 1 ] || [ ! -x "$BIN" ]; then
  echo "[test-ros] building the node (cargo build)" >&2
  cargo build --quiet --bin muscle_actuator
fi
[ -x "$BIN" ] || { echo "[test-ros] no binary at $BIN" >&2; exit 1; }

export MUSCLE_ACTUATOR_BIN="$BIN"
loopback_env

# Default to the whole suite unless a test path was given.
DEFAULT_PATH=("$ROOT/tests/python")
for a in "$@"; do
  case "$a" in -*) ;; *) if [ -e "${a%%::*}" ]; then DEFAULT_PATH=(); fi ;; esac
done
exec_on_loopback test-ros "$VENV/bin/python" -m pytest -p no:cacheprovider "${DEFAULT_PATH[@]}" "$@"
