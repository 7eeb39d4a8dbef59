#!/usr/bin/env bash
# The share of a steady tick (`benches/tick.rs`, tick_default_actuator) spent on the energetics,
# per model, from a sampling profile rather than from two versions' times (which drift with the
# load): `perf record` with DWARF call graphs while the benchmark runs, then the inclusive
# share of where the energetics are computed in a tick: sim::part::Part::energy_of (per muscle:
# a new command's terms, MuscleEnergy::terms_of; the fluxes and probe at the tick's end,
# Part::metabolic; the start powers) and MuscleEnergy::commit (the integrals).
#
#   benches/energy_share.sh [SECONDS]      (default 4 s of profile per model; needs `perf`)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SECONDS_PER_MODEL="${1:-4}"
command -v perf >/dev/null || { echo "energy_share: needs perf (linux-perf)" >&2; exit 1; }
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
BIN="$(cd "$ROOT" && cargo bench --bench tick --no-run --message-format=json 2>/dev/null |
  grep '"kind":\["bench"\]' | sed -n 's/.*"executable":"\([^"]*\)".*/\1/p' | tail -n 1)"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-8s %10s %10s %10s %10s %8s\n' model energy_of metabolic terms_of commit total
for model in hill huxley; do
  perf record --quiet --call-graph dwarf,16384 -F 2000 -o "$TMP/$model.data" \
    "$BIN" --bench --noplot "tick_default_actuator/$model\$" --profile-time "$SECONDS_PER_MODEL" \
    >/dev/null 2>&1
  perf report -i "$TMP/$model.data" --children --stdio 2>/dev/null >"$TMP/$model.txt"
  share() {
    grep -E "^ +[0-9.]+%" "$TMP/$model.txt" | grep -F "$1" | head -n 1 | awk '{print $1}' | tr -d % || true
  }
  p="$(share 'sim::part::Part::energy_of')"
  m="$(share 'sim::part::Part::metabolic')"
  x="$(share 'MuscleEnergy::terms_of')"
  c="$(share 'MuscleEnergy::commit')"
  t="$(awk -v a="${p:-0}" -v b="${c:-0}" 'BEGIN { printf "%.1f", a + b }')"
  printf '%-8s %9s%% %9s%% %9s%% %9s%% %7s%%\n' "$model" "${p:-0}" "${m:-0}" "${x:-0}" "${c:-0}" "$t"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
