#!/usr/bin/env bash
# Configures and builds spp into build/ (Release, Ninja): library, build/spp, tests and benchmarks.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSPP_BUILD_TESTS=ON -DSPP_BUILD_BENCH=ON >/dev/null
cmake --build build -j "$(nproc)"
