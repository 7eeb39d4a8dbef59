#!/usr/bin/env bash
# The steady tick's time, this checkout beside another commit, in pairs: the loop of
# examples/steady_ticks.rs (the steady tick of benches/tick.rs) built in both, then ROUNDS
# rounds that each run this checkout's loop and the other's back to back (which goes first
# alternates), TICKS ticks each. A pair spans about a second, so the machine's load, which
# drifts over minutes on a shared VM, weighs on both runs of a pair alike; the figure is the
# median over the rounds of each pair's ratio, with the spread (lowest and highest ratio) and
# the median time per tick of each.
#
#   benches/tick_paired.sh COMMIT [ROUNDS] [TICKS]     (default 21 rounds of 200000 ticks)
#   FORMULATION=rigid benches/tick_paired.sh COMMIT      (the elbow's muscles on rigid tendons)
#   OTHER_FEATURES=without-energetics benches/tick_paired.sh HEAD
#                                                      (this tick with and without its energetics)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
COMMIT="${1:?usage: benches/tick_paired.sh COMMIT [ROUNDS] [TICKS]}"
ROUNDS="${2:-21}"
TICKS="${3:-200000}"
# The muscles' formulation (examples/steady_ticks.rs: massed, equilibrium, rigid); both commits'
# examples must know it (436f057's and later do).
FORMULATION="${FORMULATION:-massed}"
source "$ROOT/benches/other_commit.sh"
other_checkout "$COMMIT"
steady_ticks_pair

ns_of() { # wall time of `$1 MODEL TICKS FORMULATION`, ns
  local t0 t1
  t0="$(date +%s%N)"
  "$1" "$2" "$TICKS" "$FORMULATION" >/dev/null
  t1="$(date +%s%N)"
  echo $((t1 - t0))
}
echo "formulation: $FORMULATION; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-8s %12s %12s %8s %16s\n' model "this ns" "$COMMIT ns" ratio "ratio low-high"
for model in hill huxley; do
  : >"$TMP/pairs"
  for r in $(seq "$ROUNDS"); do
    if [ $((r % 2)) -eq 1 ]; then
      t="$(ns_of "$TMP/this" "$model")"
      o="$(ns_of "$TMP/other_bin" "$model")"
    else
      o="$(ns_of "$TMP/other_bin" "$model")"
      t="$(ns_of "$TMP/this" "$model")"
    fi
    echo "$t $o" >>"$TMP/pairs"
  done
  # Median of the per-pair ratios and of each side's time per tick.
  awk -v m="$model" -v n="$TICKS" '
    function median(a, k,   i, j, x) {
      for (i = 2; i <= k; i++) { x = a[i]; for (j = i - 1; j >= 1 && a[j] > x; j--) a[j + 1] = a[j]; a[j + 1] = x }
      return k % 2 ? a[(k + 1) / 2] : (a[k / 2] + a[k / 2 + 1]) / 2
    }
    { k++; r[k] = $1 / $2; t[k] = $1 / n; o[k] = $2 / n }
    END {
      lo = hi = r[1]; for (i = 2; i <= k; i++) { if (r[i] < lo) lo = r[i]; if (r[i] > hi) hi = r[i] }
      printf "%-8s %12.0f %12.0f %8.3f %7.3f-%-8.3f\n", m, median(t, k), median(o, k), median(r, k), lo, hi
    }' "$TMP/pairs"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
