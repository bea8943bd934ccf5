#!/usr/bin/env bash
# Quick start, step 2: run every test. On a fresh machine it installs and builds what it needs first.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
cmake --install build --component python >/dev/null  # import spp from any directory
cd build
ctest -j "$(nproc)" --output-on-failure
