#!/usr/bin/env bash
# The Python wheel built from scratch here and at another commit, side by side: the two builds
# run at once in fresh target directories (so the machine's load weighs on both alike), and the
# script prints each one's wall and CPU time, the wheel's size and the number of crates the
# extension compiles (`cargo tree -p muscle_actuator_python`).
#
#   benches/wheel_pair.sh COMMIT        (maturin from $VENV, default .venv: scripts/py-env.sh)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
COMMIT="${1:?usage: benches/wheel_pair.sh COMMIT}"
VENV="${VENV:-$ROOT/.venv}"
source "$ROOT/benches/other_commit.sh"
other_checkout "$COMMIT"
build() { # CHECKOUT OUT: a release wheel of CHECKOUT built in OUT/target, timed into OUT/time
  mkdir -p "$2"
  (cd "$1" && { TIMEFORMAT='%R %U %S'; time CARGO_TARGET_DIR="$2/target" "$VENV/bin/maturin" \
    build --release --quiet -m python/Cargo.toml --out "$2/wheels" -i "$VENV/bin/python" \
    >/dev/null 2>&1; } 2>"$2/time")
}
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
build "$ROOT" "$TMP/this_wheel" & build "$TMP/other" "$TMP/other_wheel" & wait
printf '%-10s %8s %8s %10s %7s\n' build "wall s" "CPU s" "wheel MB" crates
for w in this other; do
  read -r real user sys <"$TMP/${w}_wheel/time"
  size="$(stat -c%s "$TMP/${w}_wheel"/wheels/*.whl)"
  dir="$ROOT"; [ "$w" = other ] && dir="$TMP/other"
  crates="$(cd "$dir" && cargo tree -p muscle_actuator_python -e normal --prefix none | sort -u | wc -l)"
  awk -v w="$w" -v r="$real" -v u="$user" -v s="$sys" -v b="$size" -v c="$crates" \
    'BEGIN { printf "%-10s %8.0f %8.0f %10.1f %7d\n", w, r, u + s, b / 1e6, c }'
done
