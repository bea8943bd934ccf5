#!/bin/bash
# The README check's own test: a README whose figure was changed (the rod's 2 admissible SPPs stated as 3) makes
# scripts/readme-check.sh exit 1 naming that line, the stated and the measured value.
# Usage: stale_figure_is_named.sh SOURCE_DIR BUILD_DIR
set -u
src=$1 build=$2
tmp=$(mktemp -d) && trap 'rm -rf "$tmp"' EXIT
sed 's/^has 2 admissible SPPs in/has 3 admissible SPPs in/' "$src/README.md" > "$tmp/README.md"
cmp -s "$src/README.md" "$tmp/README.md" && { echo "README has no line 'has 2 admissible SPPs in': update this test"; exit 1; }
line=$(grep -n '^has 3 admissible SPPs in' "$tmp/README.md" | cut -d: -f1)
out=$(bash "$src/scripts/readme-check.sh" --readme "$tmp/README.md" "$build" 2>&1); rc=$?
echo "$out"
[ "$rc" -eq 1 ] || { echo "expected exit 1, got $rc"; exit 1; }
echo "$out" | grep -q "README.md:$line: states '3', .* gives '2'" || { echo "line $line not named"; exit 1; }
[ "$(echo "$out" | grep -c ': states ')" -eq 1 ] || { echo "expected exactly one stale figure"; exit 1; }
