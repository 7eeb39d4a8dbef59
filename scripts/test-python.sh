#!/usr/bin/env bash
# The Python package's tests (docs/python.md):
#
#   scripts/test-python.sh [pytest args...]     e.g. scripts/test-python.sh -k rollout -x
#
# Creates/updates .venv (scripts/py-env.sh: maturin, numpy, gymnasium, matplotlib, pandas, ray,
# mypy), builds the wheel from python/ (maturin, release, abi3 for CPython >= 3.11) into
# target/wheels, installs it into .venv, checks the stubs _core.pyi against it (mypy.stubtest),
# builds the command-line binary (debug) the parity tests compare against, and runs pytest on
# python/tests in a loopback-only network namespace when the machine allows it (Ray's local
# cluster and the node started by a test stay on 127.0.0.1).
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cd "$ROOT"

VENV="$(python_env)"
TARGET="$(target_dir)"

BIN="$TARGET/debug/muscle_actuator"
# As in scripts/test-ros.sh: after `cargo test --all-targets` the binary is there.
if [ "${MUSCLE_ACTUATOR_BUILT:-}" != 1 ] || [ ! -x "$BIN" ]; then
  echo "[test-python] building the command line (cargo build)" >&2
  cargo build --quiet --bin muscle_actuator
fi

echo "[test-python] building the wheel (maturin build --release)" >&2
rm -f "$TARGET"/wheels/muscle_actuator-*.whl
"$VENV/bin/maturin" build --release --quiet -m python/Cargo.toml --out "$TARGET/wheels" \
  -i "$VENV/bin/python" >&2
"$VENV/bin/python" -m pip install --disable-pip-version-check -q --force-reinstall --no-deps \
  "$TARGET"/wheels/muscle_actuator-*.whl >&2

# The stubs against the built extension: every name, signature and class of _core.pyi as the
# module has it (mypy's stubtest; run outside the source tree so that the installed package is
# the one checked), with mypy's defaults: a configuration of an empty [mypy] section.
echo "[test-python] checking python/muscle_actuator/_core.pyi (mypy.stubtest)" >&2
printf '[mypy]\n' > "$TARGET/stubtest-mypy.ini"
(cd "$TARGET" && "$VENV/bin/python" -m mypy.stubtest --mypy-config-file stubtest-mypy.ini \
  muscle_actuator._core) >&2

export MUSCLE_ACTUATOR_BIN="$BIN"
loopback_env
exec_on_loopback test-python "$VENV/bin/python" -m pytest -p no:cacheprovider "$ROOT/python/tests" "$@"
