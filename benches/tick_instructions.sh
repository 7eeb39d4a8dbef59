#!/usr/bin/env bash
# The steady tick's work in instructions, this checkout beside another commit: the loop of
# examples/steady_ticks.rs (the steady tick of benches/tick.rs) built in both, run under
# valgrind's callgrind (instructions executed, exactly; no hardware counters needed, which a VM
# may not expose) for two lengths, and the difference per tick, so that set-up is not counted.
# Unlike times, instruction counts do not drift with the machine's load; they are not times
# either (a cache miss or a division costs more than an addition).
#
#   benches/tick_instructions.sh COMMIT       (needs valgrind; builds COMMIT in a git worktree)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
COMMIT="${1:?usage: benches/tick_instructions.sh COMMIT}"
command -v valgrind >/dev/null || { echo "tick_instructions: needs valgrind" >&2; exit 1; }
source "$ROOT/benches/other_commit.sh"
other_checkout "$COMMIT"
steady_ticks_pair

count() { # instructions of `$1 MODEL TICKS`
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$1" "$2" "$3" 2>&1 >/dev/null |
    sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
short=2000
long=22000
printf '%-8s %16s %16s %8s\n' model "this /tick" "$COMMIT /tick" ratio
for model in hill huxley; do
  per_tick() {
    local a b
    a="$(count "$1" "$model" "$short")"
    b="$(count "$1" "$model" "$long")"
    echo $(((b - a) / (long - short)))
  }
  t="$(per_tick "$TMP/this")"
  o="$(per_tick "$TMP/other_bin")"
  printf '%-8s %16s %16s %8s\n' "$model" "$t" "$o" "$(awk -v a="$t" -v b="$o" 'BEGIN { printf "%.3f", a / b }')"
done
