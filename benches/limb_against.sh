#!/usr/bin/env bash
# `benches/limb.rs` of this checkout beside the same benchmark of another commit, in one run:
# benches/limb_against.sh COMMIT [RUNS] (RUNS default 3; LIMB_CASES and LIMB_MODELS restrict
# both, as for `cargo bench --bench limb`). Builds COMMIT's own limb benchmark from a git
# worktree (benches/other_commit.sh), runs the two RUNS times interleaved and prints per case the
# best (least) µs per two-muscle actuator of each, their ratio COMMIT / this (above 1: this
# checkout is cheaper) and this checkout's work per tick. Prints the load average before and
# after: on a shared machine compare only ratios measured in one run.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
COMMIT="${1:?usage: benches/limb_against.sh COMMIT [RUNS]}"
RUNS="${2:-3}"
source "$ROOT/benches/other_commit.sh"
other_checkout "$COMMIT"
bench_pair limb

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for r in $(seq "$RUNS"); do
  for b in this other_bin; do
    echo "run $r of $RUNS: $b" >&2
    "$TMP/$b" --bench | sed "s/^/$b /" >>"$TMP/out"
  done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

awk -v other="$COMMIT" '
  $2 == "limb" { next }
  {
    key = $2 " " $3 " " $4 " " $5
    if (!(key in seen)) { seen[key] = 1; order[++n] = key }
    if (!((key, $1) in us) || $7 < us[key, $1]) us[key, $1] = $7
    if ($1 == "this") work[key] = sprintf("%s / %s / %s / %s", $9, $10, $11, $12)
  }
  END {
    printf "%-6s %-7s %4s %-10s %10s %12s %7s  %s\n", "limb", "model", "mus", "load",
      "this µs/a", other " µs/a", "ratio", "this rhs / solves / LU / sub-steps per tick"
    for (i = 1; i <= n; i++) {
      k = order[i]; split(k, f, " ")
      p = ((k, "other_bin") in us) ? sprintf("%12.2f", us[k, "other_bin"]) : sprintf("%12s", "-")
      r = ((k, "other_bin") in us) ? sprintf("%7.3f", us[k, "other_bin"] / us[k, "this"]) : sprintf("%7s", "-")
      printf "%-6s %-7s %4s %-10s %10.2f %s %s  %s\n", f[1], f[2], f[3], f[4], us[k, "this"], p, r, work[k]
    }
  }' "$TMP/out"
