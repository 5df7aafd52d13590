#!/bin/bash
# The shipped hard query set is what `collide2d hardset` with its defaults
# writes, bit for bit (run by CI from the clang -O0 build too: the queries
# are built from + − × ÷ and sqrt only, the oracle in 60 digits).
# Usage: hardset_regenerates.sh COLLIDE2D SOURCE_DIR
set -euo pipefail
exe="$1" root="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$exe" hardset --jsonl "$work/hard.jsonl" -o "$work/hard.h5" >/dev/null 2>&1
if ! cmp -s "$work/hard.jsonl" "$root/datasets/hard/hard_queries.jsonl"; then
  echo "collide2d hardset writes a different dataset from datasets/hard/hard_queries.jsonl:"
  diff <(head -c 2000 "$work/hard.jsonl") <(head -c 2000 "$root/datasets/hard/hard_queries.jsonl") | head -5
  exit 1
fi
echo "hardset: identical to the shipped dataset ($(wc -l <"$work/hard.jsonl") queries)"
