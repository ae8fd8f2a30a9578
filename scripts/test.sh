#!/usr/bin/env bash
# Builds delmesh (Release) and runs the default (fast) test tier.  Pass --all to add the slow tier.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${DELMESH_BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -G Ninja
cmake --build "$build" -j "$(nproc)"
if [ "${1:-}" = "--all" ]; then
  ctest --test-dir "$build" --output-on-failure
else
  ctest --test-dir "$build" --output-on-failure -LE slow
fi
