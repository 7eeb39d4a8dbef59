#!/usr/bin/env bash
# The speed against the program this project grew from: this program's `benches/limb.rs`
# (k-elbow banks in one limb, and the `arm`) against the previous two-muscle program, commit
# dcf2021 (TR-BDF2, dense 12 × 12 matrix), stepping k separate actuators:
# benches/previous.sh [RUNS] (default 3).
#
# Builds both release (the previous one from a git worktree of dcf2021 in a temporary directory,
# with benches/previous/limb_separate.rs dropped in as its benches/limb_previous.rs, in the same
# CARGO_TARGET_DIR so the dependencies are shared), runs them RUNS times interleaved, and prints
# per case the best (least) µs per two-muscle actuator of each, their ratio (previous / this:
# above 1 means this program is cheaper), and the summary figures of docs/benchmarks.md.
# LIMB_MODELS and LIMB_CASES (benches/limb.rs) restrict both. Prints the load average before and
# after: on a shared machine compare only ratios measured in one run.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
PREVIOUS=dcf2021
RUNS="${1:-3}"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
TMP="$(mktemp -d)"
cleanup() {
  git -C "$ROOT" worktree remove --force "$TMP/previous" 2>/dev/null || true
  rm -rf "$TMP"
}
trap cleanup EXIT

# The benchmark executable a `cargo bench --no-run` built, from its JSON messages.
executable() {
  grep '"kind":\["bench"\]' | sed -n 's/.*"executable":"\([^"]*\)".*/\1/p' | tail -n 1
}

git -C "$ROOT" worktree add --detach --quiet "$TMP/previous" "$PREVIOUS"
cp "$ROOT/benches/previous/limb_separate.rs" "$TMP/previous/benches/limb_previous.rs"
printf '\n[[bench]]\nname = "limb_previous"\nharness = false\n' >>"$TMP/previous/Cargo.toml"
# Another version number gives that program's crate its own artifacts in the shared target dir:
# with the same name and version cargo would write both to the same files, and a later build of
# this program could take the other's as up to date.
sed -i 's/^version = "0.1.0"$/version = "0.1.0-dcf2021"/' "$TMP/previous/Cargo.toml"
THIS_BIN="$(cd "$ROOT" && cargo bench --bench limb --no-run --message-format=json 2>/dev/null | executable)"
PREV_BIN="$(cd "$TMP/previous" && cargo bench --bench limb_previous --no-run --message-format=json 2>/dev/null | executable)"
[ -x "$THIS_BIN" ] && [ -x "$PREV_BIN" ] || { echo "build failed" >&2; exit 1; }

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for r in $(seq "$RUNS"); do
  echo "run $r of $RUNS: this program, then $PREVIOUS" >&2
  "$THIS_BIN" --bench | sed 's/^/this /' >>"$TMP/out"
  "$PREV_BIN" --bench | sed 's/^/prev /' >>"$TMP/out"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

# Columns after the tag: limb model muscles load µs/tick µs/actuator µs/muscle rhs solves LU sub.
awk '
  $2 == "limb" { next }
  {
    key = $2 " " $3 " " $4 " " $5
    if (!(key in seen)) { seen[key] = 1; order[++n] = key }
    if (!((key, $1) in us) || $7 < us[key, $1]) us[key, $1] = $7
    if ($1 == "this") work[key] = sprintf("%s / %s / %s / %s", $9, $10, $11, $12)
  }
  END {
    printf "%-6s %-7s %4s %-10s %10s %10s %7s  %s\n", "limb", "model", "mus", "load",
      "this µs/a", "prev µs/a", "ratio", "this rhs / solves / LU / sub-steps per tick"
    for (i = 1; i <= n; i++) {
      k = order[i]; split(k, f, " ")
      p = ((k, "prev") in us) ? sprintf("%10.2f", us[k, "prev"]) : sprintf("%10s", "-")
      r = ((k, "prev") in us) ? sprintf("%7.2f", us[k, "prev"] / us[k, "this"]) : sprintf("%7s", "-")
      printf "%-6s %-7s %4s %-10s %10.2f %s %s  %s\n", f[1], f[2], f[3], f[4], us[k, "this"], p, r, work[k]
      if ((k, "prev") in us) {
        g = f[2] " " f[4]; ratio = us[k, "prev"] / us[k, "this"]
        if (!(g in lo) || ratio < lo[g]) lo[g] = ratio
        if (!(g in hi) || ratio > hi[g]) hi[g] = ratio
      }
    }
    print ""
    print "ratio previous / this over the banks (bars: huxley realistic 3, huxley step 4, hill realistic 1.5):"
    for (m = 1; m <= 2; m++) for (l = 1; l <= 3; l++) {
      model = (m == 1) ? "hill" : "huxley"; load = (l == 1) ? "steady" : (l == 2) ? "step" : "realistic"
      g = model " " load
      if (g in lo) printf "  %-6s %-9s %.2f-%.2f\n", model, load, lo[g], hi[g]
    }
    print "cost per muscle at 50 over at 2 (bar 1.5), and the arm tick over the two-muscle tick (bar 3 for huxley):"
    for (m = 1; m <= 2; m++) for (l = 1; l <= 3; l++) {
      model = (m == 1) ? "hill" : "huxley"; load = (l == 1) ? "steady" : (l == 2) ? "step" : "realistic"
      a = "bank1 " model " 2 " load; b = "bank25 " model " 50 " load; c = "arm " model " 6 " load
      if (!((a, "this") in us)) continue
      printf "  %-6s %-9s", model, load
      if ((b, "this") in us) printf "  50/2 %.2f", us[b, "this"] / us[a, "this"]
      if ((c, "this") in us) printf "  arm/2-muscle tick %.2f", 3 * us[c, "this"] / us[a, "this"]
      printf "\n"
    }
  }' "$TMP/out"
