# Sourced by the benchmarks that measure this checkout beside another commit in one run
# (benches/tick_against.sh, benches/tick_instructions.sh, benches/tick_paired.sh,
# benches/threads_paired.sh, benches/pulse_paired.sh, benches/limb_against.sh). With ROOT set
# to this checkout:
#
#   other_checkout COMMIT    TMP: a temporary directory, removed on exit; "$TMP/other": COMMIT
#                            in a git worktree, built with the cargo features OTHER_FEATURES if
#                            set (`without-energetics`: the tick without its energetics);
#                            OTHER_TARGET_DIR: where to build it
#   executable_of KIND       the last executable of KIND (bench, example) in cargo's JSON
#                            messages on stdin
#   example_pair NAME        after other_checkout: examples/NAME.rs built in both (the other's
#                            own, or this checkout's copied where it has none), as "$TMP/this" and "$TMP/other_bin"
#   steady_ticks_pair        example_pair steady_ticks
#   bench_pair NAME          after other_checkout: each checkout's own benches/NAME.rs built in
#                            it, as "$TMP/this" and "$TMP/other_bin"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
# The other commit builds in a target dir of its own, kept between runs: cargo hashes a path
# dependency (the vendored rustdds) by its place in the workspace, so the two checkouts' copies
# would share artifacts and each build would leave the other's in place of its own.
OTHER_TARGET_DIR="$CARGO_TARGET_DIR/other-commit"

other_checkout() {
  TMP="$(mktemp -d)"
  trap 'git -C "$ROOT" worktree remove --force "$TMP/other" 2>/dev/null || true; rm -rf "$TMP"' EXIT
  git -C "$ROOT" worktree add --detach --quiet "$TMP/other" "$1"
  if [ -n "${OTHER_FEATURES:-}" ]; then
    echo "other: $1 with the features $OTHER_FEATURES" >&2
  fi
}

executable_of() {
  grep "\"kind\":\[\"$1\"\]" | sed -n 's/.*"executable":"\([^"]*\)".*/\1/p' | tail -n 1
}

example_pair() { # NAME: this checkout's examples/NAME.rs built here and in the other checkout
  built() { # the example's executable, built in the checkout $1 (with features $3)
    (cd "$1" && cargo build --release --example "$2" ${3:+--features "$3"} \
      --message-format=json 2>/dev/null) | executable_of example
  }
  # The other commit's own copy where it has one (its API may have other paths); else this one.
  [ -e "$TMP/other/examples/$1.rs" ] || cp "$ROOT/examples/$1.rs" "$TMP/other/examples/"
  cp "$(built "$ROOT" "$1")" "$TMP/this"
  cp "$(CARGO_TARGET_DIR="$OTHER_TARGET_DIR" built "$TMP/other" "$1" "${OTHER_FEATURES:-}")" \
    "$TMP/other_bin"
}

bench_pair() { # NAME: each checkout's own benches/NAME.rs, built in it
  built() { # the benchmark's executable, built in the checkout $1 (with features $3)
    (cd "$1" && cargo bench --bench "$2" --no-run ${3:+--features "$3"} \
      --message-format=json 2>/dev/null) | executable_of bench
  }
  cp "$(built "$ROOT" "$1")" "$TMP/this"
  cp "$(CARGO_TARGET_DIR="$OTHER_TARGET_DIR" built "$TMP/other" "$1" "${OTHER_FEATURES:-}")" \
    "$TMP/other_bin"
}

steady_ticks_pair() {
  example_pair steady_ticks
}
