#!/usr/bin/env bash
# `simulate pulse` in-process (examples/pulse_time.rs: `Scenario::run` of one clamped muscle,
# 3000 ticks, and the same ticks through the runner without records), this checkout beside
# another commit, in pairs: ROUNDS rounds that each run this checkout's example and the other's
# once with two rounds of its own (which goes first alternates). Prints, per line of the example
# (hill, hill-steps, hill-setup, the same for huxley, and each of the process's first round as
# NAME-first), the median µs per muscle-tick of each and the median over the rounds of each
# pair's ratio (this / other), with the lowest and highest ratio.
#
#   benches/pulse_paired.sh COMMIT [ROUNDS]     (default 31 rounds)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
COMMIT="${1:?usage: benches/pulse_paired.sh COMMIT [ROUNDS]}"
ROUNDS="${2:-31}"
source "$ROOT/benches/other_commit.sh"
other_checkout "$COMMIT"
example_pair pulse_time

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
: >"$TMP/pairs"
for r in $(seq "$ROUNDS"); do
  if [ $((r % 2)) -eq 1 ]; then
    "$TMP/this" 2 >"$TMP/t"
    "$TMP/other_bin" 2 >"$TMP/o"
  else
    "$TMP/other_bin" 2 >"$TMP/o"
    "$TMP/this" 2 >"$TMP/t"
  fi
  paste -d' ' "$TMP/t" "$TMP/o" >>"$TMP/pairs" # NAME us force NAME us force
done
printf '%-14s %10s %10s %8s %16s\n' what "this µs" "$COMMIT µs" ratio "ratio low-high"
awk '
  function median(a, k,   i, j, x) {
    for (i = 2; i <= k; i++) { x = a[i]; for (j = i - 1; j >= 1 && a[j] > x; j--) a[j + 1] = a[j]; a[j + 1] = x }
    return k % 2 ? a[(k + 1) / 2] : (a[k / 2] + a[k / 2 + 1]) / 2
  }
  $1 != $4 || $3 != $6 { print "the two disagree: " $0 > "/dev/stderr"; bad = 1 }
  { if (!($1 in k)) order[++names] = $1; n = ++k[$1]; r[$1, n] = $2 / $5; t[$1, n] = $2; o[$1, n] = $5 }
  END {
    for (w = 1; w <= names; w++) {
      m = order[w]; lo = hi = r[m, 1]
      for (i = 1; i <= k[m]; i++) { rr[i] = r[m, i]; tt[i] = t[m, i]; oo[i] = o[m, i]; if (rr[i] < lo) lo = rr[i]; if (rr[i] > hi) hi = rr[i] }
      printf "%-14s %10.3f %10.3f %8.3f %7.3f-%-8.3f\n", m, median(tt, k[m]), median(oo, k[m]), median(rr, k[m]), lo, hi
    }
    exit bad
  }' "$TMP/pairs"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
