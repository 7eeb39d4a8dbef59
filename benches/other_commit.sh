# Sourced by the benchmarks that measure this checkout beside another commit in one run
# (benches/tick_against.sh, benches/tick_instructions.sh). With ROOT set to this checkout:
#
#   other_checkout COMMIT    TMP: a temporary directory, removed on exit; "$TMP/other": COMMIT
#                            in a git worktree, with the patch OTHER_PATCH applied if set
#                            (benches/without_energetics.patch: this tick without its energetics);
#                            OTHER_TARGET_DIR: where to build it
#   executable_of KIND       the last executable of KIND (bench, example) in cargo's JSON
#                            messages on stdin
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
# The other commit builds in a target dir of its own, kept between runs: cargo hashes a path
# dependency (the vendored rustdds) by its place in the workspace, so the two checkouts' copies
# would share artifacts and each build would leave the other's in place of its own.
OTHER_TARGET_DIR="$CARGO_TARGET_DIR/other-commit"

other_checkout() {
  TMP="$(mktemp -d)"
  trap 'git -C "$ROOT" worktree remove --force "$TMP/other" 2>/dev/null || true; rm -rf "$TMP"' EXIT
  git -C "$ROOT" worktree add --detach --quiet "$TMP/other" "$1"
  if [ -n "${OTHER_PATCH:-}" ]; then
    git -C "$TMP/other" apply "$(cd "$(dirname "$OTHER_PATCH")" && pwd)/$(basename "$OTHER_PATCH")"
    echo "other: $1 with $(basename "$OTHER_PATCH") applied" >&2
  fi
}

executable_of() {
  grep "\"kind\":\[\"$1\"\]" | sed -n 's/.*"executable":"\([^"]*\)".*/\1/p' | tail -n 1
}
