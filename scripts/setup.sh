#!/usr/bin/env bash
# Quick start, step 1: install what is needed, build, and solve the paper's 5-dof chain (§5.2).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
echo
echo "== build/spp solve examples/chain5.json --t1-max 12 --t2-max 12 --admissible-only"
build/spp solve examples/chain5.json --t1-max 12 --t2-max 12 --admissible-only
