#!/usr/bin/env bash
# Builds delmesh (Release) and runs every test: the fast tier and the slow tier (the catalog's
# topology, Theorem 6.1 at lambda 0.06 and 0.03 on every catalog surface, the recheck lemma).
# Pass --fast to run the fast tier only.  Both then dry-run (snakemake -n) the full sweep workflow
# experiments/Snakefile (every surface, λ and seed of its defaults) against the built lambda_sweep,
# locally and through the Slurm profile experiments/profiles/slurm (scripts/test-slurm.sh runs
# that profile on a real one-node Slurm).
# No mode runs the tests labelled `extra` (the pip route, tests/install/pip_test.sh, which compiles
# the libraries again): `ctest --test-dir build -L extra` runs them.
# Pass --sanitize to build the libraries, the program, the test suites and the libFuzzer targets of
# fuzz/ with clang++, AddressSanitizer and UndefinedBehaviorSanitizer (-O1, in build-sanitize/,
# experiments left out) and run the fast tier there; any sanitizer report fails the test that
# triggered it.  scripts/fuzz.sh runs the fuzz targets of the same build directory.
# Pass --debug to build everything as Debug with assertions on (assert, CGAL's and Eigen's
# preconditions, libstdc++'s checked containers via _GLIBCXX_ASSERTIONS; -O1 rather than -O0 for
# the tests' run time; in build-debug/) and run the fast tier there; a failed assertion fails its test.
# First installs the Debian packages of building and of testing if some are missing
# (scripts/install-deps.sh --dev).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --dev
if [ "${1:-}" = "--debug" ]; then
  build=${DELMESH_DEBUG_BUILD_DIR:-build-debug}
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug -G Ninja -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g -D_GLIBCXX_ASSERTIONS"
  cmake --build "$build" -j "$(nproc)"
  ctest --test-dir "$build" --output-on-failure -LE 'slow|extra'
  exit
fi
if [ "${1:-}" = "--sanitize" ]; then
  build=${DELMESH_SANITIZE_BUILD_DIR:-build-sanitize}
  # The configuration of scripts/fuzz.sh (keep the two in step): one build serves both.  The
  # libraries carry libFuzzer's coverage instrumentation (-fsanitize=fuzzer-no-link), whose
  # callbacks ASan's runtime provides in the test programs.
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER="${CXX:-clang++}" \
    -DCMAKE_CXX_FLAGS_RELEASE="-O1 -gline-tables-only -DNDEBUG" -DDELMESH_BUILD_FUZZERS=ON \
    -DDELMESH_BUILD_TESTS=ON -DDELMESH_BUILD_EXPERIMENTS=OFF
  cmake --build "$build" -j "${DELMESH_JOBS:-$(nproc)}"
  export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1}
  export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
  export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan.supp:print_suppressions=0}
  ctest --test-dir "$build" --output-on-failure -j "$(nproc)" -LE 'slow|extra'
  exit
fi
build=${DELMESH_BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -G Ninja
cmake --build "$build" -j "$(nproc)"
if [ "${1:-}" = "--fast" ]; then
  ctest --test-dir "$build" --output-on-failure -j "$(nproc)" -LE 'slow|extra'
else
  ctest --test-dir "$build" --output-on-failure -j "$(nproc)" -LE extra
fi
command -v snakemake >/dev/null || { echo "test.sh: snakemake is missing (scripts/install-deps.sh --dev)" >&2; exit 1; }
mkdir -p "$build/snakemake-dry-run"
snakemake -s experiments/Snakefile --directory "$build/snakemake-dry-run" -n --quiet --cores 2 \
  --config out="$(realpath "$build")/snakemake-dry-run/out" bin="$(realpath "$build")/experiments/lambda_sweep"
snakemake -s experiments/Snakefile --directory "$build/snakemake-dry-run" -n --quiet \
  --profile experiments/profiles/slurm \
  --config out="$(realpath "$build")/snakemake-dry-run/out" bin="$(realpath "$build")/experiments/lambda_sweep"
echo "test.sh: dry runs of experiments/Snakefile (local and through the Slurm profile) passed"
/usr/bin/python3 paper/test_paper_common.py   # the figures' CSV reader, PDF and PNG, readable log axes
