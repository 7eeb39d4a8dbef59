#!/usr/bin/env bash
# `benches/tick.rs` of this checkout beside the same benchmark of another commit, in one run:
# benches/tick_against.sh COMMIT [ROUNDS] [FILTER] (ROUNDS default 3; FILTER a criterion filter,
# default the per-tick groups). Builds COMMIT from a git worktree in a temporary directory, in a
# target dir of its own kept between runs (benches/other_commit.sh), runs both binaries ROUNDS times interleaved and prints per benchmark the best (least) median
# time of each and their ratio, this / COMMIT. Prints the load average before and after: on a
# shared machine compare only ratios measured in one run.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
COMMIT="${1:?usage: benches/tick_against.sh COMMIT [ROUNDS] [FILTER]}"
ROUNDS="${2:-3}"
FILTER="${3:-tick_default_actuator|twenty_ticks_after_excitation_step}"
source "$ROOT/benches/other_commit.sh"
other_checkout "$COMMIT"
bench_pair tick

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for r in $(seq "$ROUNDS"); do
  for b in this other_bin; do
    echo "round $r of $ROUNDS: $b" >&2
    # Criterion prints the name, then `time: [low median high]` (on the same line or the next).
    "$TMP/$b" --bench --noplot "$FILTER" 2>/dev/null | grep -E '^[a-z_]+/|time:' | paste -d' ' - - |
      sed "s/^/$b /" >>"$TMP/out"
  done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

awk -v other="$COMMIT" '
  function ns(v, u) { return u == "ns" ? v : u == "µs" ? v * 1e3 : u == "ms" ? v * 1e6 : v * 1e9 }
  {
    for (i = 1; i <= NF; i++) if ($i == "time:") { med = ns($(i + 3), $(i + 4)); break }
    key = $2
    if (!(key in seen)) { seen[key] = 1; order[++n] = key }
    if (!((key, $1) in best) || med < best[key, $1]) best[key, $1] = med
  }
  END {
    printf "%-50s %12s %12s %8s\n", "benchmark", "this ns", other " ns", "ratio"
    for (i = 1; i <= n; i++) {
      k = order[i]
      printf "%-50s %12.0f %12.0f %8.3f\n", k, best[k, "this"], best[k, "other_bin"], best[k, "this"] / best[k, "other_bin"]
    }
  }' "$TMP/out"
