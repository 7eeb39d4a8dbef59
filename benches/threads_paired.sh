#!/usr/bin/env bash
# The threaded bank's time, this checkout beside another commit, in pairs:
# examples/bank_threads.rs (100 elbows under the realistic load, on two threads) built in both,
# then ROUNDS rounds that each run this checkout's bank and the other's back to back (which goes
# first alternates), 3 rounds of 1000 ticks each. The figure is the median over the rounds of
# each pair's ratio of two-thread times (other / this: above 1, this checkout is faster), with
# the spread and the median µs per tick of each.
#
#   benches/threads_paired.sh COMMIT [ROUNDS] [ELBOWS]     (default 15 rounds, 100 elbows)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
COMMIT="${1:?usage: benches/threads_paired.sh COMMIT [ROUNDS] [ELBOWS]}"
ROUNDS="${2:-15}"
ELBOWS="${3:-100}"
source "$ROOT/benches/other_commit.sh"
other_checkout "$COMMIT"
built() { # examples/bank_threads.rs, built in the checkout $1
  (cd "$1" && cargo build --release --example bank_threads --message-format=json 2>/dev/null) |
    executable_of example
}
cp "$ROOT/examples/bank_threads.rs" "$TMP/other/examples/"
cp "$ROOT/benches/common/bank.rs" "$TMP/other/benches/common/"
cp "$(built "$ROOT")" "$TMP/this"
cp "$(CARGO_TARGET_DIR="$OTHER_TARGET_DIR" built "$TMP/other")" "$TMP/other_bin"

us_of() { # the two-thread µs per tick of `$1 ELBOWS 2 3 MODEL`
  "$1" "$ELBOWS" 2 3 "$2" | sed -n 's/.*, 2 threads \([0-9.]*\) µs\/tick; throughput.*/\1/p'
}
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-8s %12s %12s %8s %16s\n' model "this µs" "$COMMIT µs" ratio "ratio low-high"
for model in hill huxley; do
  : >"$TMP/pairs"
  for r in $(seq "$ROUNDS"); do
    if [ $((r % 2)) -eq 1 ]; then
      t="$(us_of "$TMP/this" "$model")"
      o="$(us_of "$TMP/other_bin" "$model")"
    else
      o="$(us_of "$TMP/other_bin" "$model")"
      t="$(us_of "$TMP/this" "$model")"
    fi
    echo "$t $o" >>"$TMP/pairs"
  done
  awk -v m="$model" '
    function median(a, k,   i, j, x) {
      for (i = 2; i <= k; i++) { x = a[i]; for (j = i - 1; j >= 1 && a[j] > x; j--) a[j + 1] = a[j]; a[j + 1] = x }
      return k % 2 ? a[(k + 1) / 2] : (a[k / 2] + a[k / 2 + 1]) / 2
    }
    { k++; r[k] = $2 / $1; t[k] = $1; o[k] = $2 }
    END {
      lo = hi = r[1]; for (i = 2; i <= k; i++) { if (r[i] < lo) lo = r[i]; if (r[i] > hi) hi = r[i] }
      printf "%-8s %12.1f %12.1f %8.3f %7.3f-%-8.3f\n", m, median(t, k), median(o, k), median(r, k), lo, hi
    }' "$TMP/pairs"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
