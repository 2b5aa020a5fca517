#!/usr/bin/env bash
# Seeds each fuzz target's corpus (fuzz/corpus/TARGET, not committed) from the test corpora,
# each file named after its path so that none overwrites another.
set -euo pipefail
cd "$(dirname "$0")/.."
seed() { # TARGET PATTERN...
  local target=$1; shift
  mkdir -p "fuzz/corpus/$target"
  for pattern in "$@"; do
    find tests specs -name "$pattern" -type f | while read -r f; do
      cp "$f" "fuzz/corpus/$target/${f//\//_}"
    done
  done
  echo "fuzz/corpus/$target: $(ls "fuzz/corpus/$target" | wc -l) seeds"
}
seed asl '*.asl'
seed pipeline '*.asl'
seed pddl '*.pddl'
seed manifest '*.toml'
seed report '*.json'
