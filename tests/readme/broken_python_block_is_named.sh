#!/bin/bash
# README's Python block is run by the README check (it was not: found by an independent attack): a README whose block
# calls a method that does not exist makes scripts/readme-check.sh exit 1 naming the block's line and the error.
# Usage: broken_python_block_is_named.sh SOURCE_DIR BUILD_DIR
set -u
src=$1 build=$2
tmp=$(mktemp -d) && trap 'rm -rf "$tmp"' EXIT
sed 's/^r\.to_dataframe()  /r.no_such_method()/' "$src/README.md" > "$tmp/README.md"
cmp -s "$src/README.md" "$tmp/README.md" && { echo "README has no line 'r.to_dataframe()': update this test"; exit 1; }
line=$(( $(grep -n '^import numpy as np, pickle, spp' "$tmp/README.md" | cut -d: -f1) ))
out=$(bash "$src/scripts/readme-check.sh" --readme "$tmp/README.md" "$build" 2>&1); rc=$?
echo "$out"
[ "$rc" -eq 1 ] || { echo "expected exit 1, got $rc"; exit 1; }
echo "$out" | grep -q "README.md:$line: the Python block fails: .*no_such_method" || { echo "block at $line not named"; exit 1; }
