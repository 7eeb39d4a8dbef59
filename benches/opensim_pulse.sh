#!/usr/bin/env bash
# `pulse` per muscle-tick, this project in-process beside OpenSim's Thelen2003 and Millard2012
# muscles from PyPI, in one run: examples/pulse_time.rs (release) and benches/opensim_pulse.py,
# ROUNDS rounds interleaved (default 7). OpenSim goes into its own venv ($BENCH_OPENSIM_VENV,
# default target/opensim-venv), made on first use.
#
#   bash benches/opensim_pulse.sh [ROUNDS]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ROUNDS="${1:-7}"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
VENV="${BENCH_OPENSIM_VENV:-$CARGO_TARGET_DIR/opensim-venv}"
if [ ! -x "$VENV/bin/python" ] || ! "$VENV/bin/python" -c "import opensim" 2>/dev/null; then
  python3 -m venv "$VENV"
  "$VENV/bin/pip" install --quiet "opensim==4.6.*"
fi
source "$ROOT/benches/other_commit.sh"
PULSE_TIME="$(cd "$ROOT" && cargo build --release --example pulse_time --message-format=json 2>/dev/null |
  executable_of example)"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
PULSE_FORMULATIONS=1 "$VENV/bin/python" "$ROOT/benches/opensim_pulse.py" "$ROUNDS" "$PULSE_TIME"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
