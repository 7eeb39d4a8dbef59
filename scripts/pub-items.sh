#!/usr/bin/env bash
# scripts/pub-items.sh: the public items of each library crate, counted as docs/layout.md counts
# them: lines declaring a `pub` fn, struct, enum, trait, type, const, static, mod or use (not
# `pub(crate)`, not fields), outside test code (tests/ folders, tests.rs files and what follows
# a `#[cfg(test)]` module in a file).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
for crate in crates/core crates/measured crates/recording; do
  [ -d "$crate/src" ] || continue
  n=0
  while IFS= read -r f; do
    c=$(awk '/^[[:space:]]*#\[cfg\(test\)\]/ { t = 1; next }
             t && /^[[:space:]]*(pub(\(crate\))? )?mod / { exit }
             { t = 0 }
             /^[[:space:]]*pub (unsafe )?(fn|struct|enum|trait|type|const|static|mod|use) / { n++ }
             END { print n + 0 }' "$f")
    n=$((n + c))
  done < <(find "$crate/src" -name '*.rs' -not -path '*/tests/*' -not -name 'tests.rs')
  echo "$crate: $n"
done
