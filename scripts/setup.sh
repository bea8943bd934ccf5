#!/usr/bin/env bash
# Quick start, step 1: install what is needed, build, and solve the paper's 5-dof chain (§5.2).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
cmake --install build --component python >/dev/null  # import spp from any directory
echo
echo "== build/spp solve examples/chain5.json --t1-max 12 --t2-max 12 --admissible-only"
build/spp solve examples/chain5.json --t1-max 12 --t2-max 12 --admissible-only
echo
echo "== /usr/bin/python3 -c 'import spp; ...'   (the Python package, installed for Debian's python3)"
/usr/bin/python3 -c "import spp; r = spp.solve(spp.System.from_json('examples/chain5.json'), t1_max=12, t2_max=12); print(r.brief_report())"
