#!/usr/bin/env bash
# Builds delmesh (Release) and runs every test: the fast tier and the slow tier (the catalog's
# topology, Theorem 6.1 at lambda 0.06 and 0.03 on every catalog surface, the recheck lemma).
# Pass --fast to run the fast tier only.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${DELMESH_BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -G Ninja
cmake --build "$build" -j "$(nproc)"
if [ "${1:-}" = "--fast" ]; then
  ctest --test-dir "$build" --output-on-failure -LE slow
else
  ctest --test-dir "$build" --output-on-failure
fi
