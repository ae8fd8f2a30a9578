#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ (clang++, AddressSanitizer, UndefinedBehaviorSanitizer) and
# runs each for SECONDS (default 60).  Usage:
#   scripts/fuzz.sh [SECONDS] [TARGET...]     targets: fuzz_expression fuzz_read_off fuzz_read_ply
#                                             fuzz_read_obj fuzz_read_stl fuzz_command_line fuzz_input_mesh
#                                             fuzz_output_paths (default: all)
# The build directory is the sanitized test build's (build-sanitize/, configured as
# scripts/test.sh --sanitize does, so each reuses what the other built).
# Each target starts from its seed corpus fuzz/corpus/<target>/ (read only) and the inputs found by
# earlier runs, kept in build-sanitize/corpus/<target>/; it uses fuzz/<target>.dict if present and
# the extra libFuzzer flags of fuzz/<target>.options if present (e.g. -max_len=...).  A crash, leak,
# timeout (> DELMESH_FUZZ_TIMEOUT seconds for one input, default 10) or out-of-memory leaves the input
# in build-sanitize/artifacts/<target>/; the script still runs the other targets, prints the
# executions per target and exits non-zero.  Replay an input: build-sanitize/fuzz/<target> FILE.
# Leaks: LeakSanitizer checks the whole process when each target ends (a leak fails the run).
# libFuzzer's check after every input that allocates more than it frees (-detect_leaks=1) stops
# the process and scans its memory each time; GiNaC's and CGAL's caches make that most inputs, which
# cut the expression target from ~7800 to ~600 executions per second, so it is off
# (-detect_leaks=0).  To find the input behind a leak, replay the corpus with it on:
#   build-sanitize/fuzz/<target> -detect_leaks=1 -runs=0 build-sanitize/corpus/<target>
# Environment: DELMESH_FUZZ_BUILD_DIR (DELMESH_SANITIZE_BUILD_DIR, else build-sanitize), DELMESH_JOBS
# (nproc), DELMESH_FUZZ_FLAGS (extra libFuzzer flags for every target, e.g. -runs=1000000 to stop at
# that many executions), CXX (clang++).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
all_targets=(fuzz_expression fuzz_read_off fuzz_read_ply fuzz_read_obj fuzz_read_stl fuzz_command_line fuzz_input_mesh
             fuzz_output_paths)
if [ $# -gt 0 ]; then targets=("$@"); else targets=("${all_targets[@]}"); fi
build=${DELMESH_FUZZ_BUILD_DIR:-${DELMESH_SANITIZE_BUILD_DIR:-build-sanitize}}
jobs=${DELMESH_JOBS:-$(nproc)}
timeout=${DELMESH_FUZZ_TIMEOUT:-10}

# The configuration of scripts/test.sh --sanitize (keep the two in step).
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER="${CXX:-clang++}" \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -gline-tables-only -DNDEBUG" -DDELMESH_BUILD_FUZZERS=ON \
  -DDELMESH_BUILD_TESTS=ON -DDELMESH_BUILD_EXPERIMENTS=OFF
cmake --build "$build" -j "$jobs" --target "${targets[@]}"

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan.supp:print_suppressions=0}
if command -v llvm-symbolizer >/dev/null; then export ASAN_SYMBOLIZER_PATH=${ASAN_SYMBOLIZER_PATH:-$(command -v llvm-symbolizer)}; fi

failed=0
summary=()
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  artifacts="$build/artifacts/$target"
  log="$build/logs/$target.log"
  mkdir -p "$corpus" "$artifacts" "$(dirname "$log")"
  flags=(-max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=2048 -print_final_stats=1 -detect_leaks=0
         -artifact_prefix="$artifacts/")
  if [ -f "fuzz/$target.dict" ]; then flags+=(-dict="fuzz/$target.dict"); fi
  if [ -f "fuzz/$target.options" ]; then
    read -r -a extra < <(grep -v '^#' "fuzz/$target.options" | tr '\n' ' ') || true  # (no final newline)
    flags+=("${extra[@]}")
  fi
  if [ -n "${DELMESH_FUZZ_FLAGS:-}" ]; then read -r -a extra <<< "$DELMESH_FUZZ_FLAGS"; flags+=("${extra[@]}"); fi
  echo "=== $target: ${seconds}s ${flags[*]}"
  set +e
  "$build/fuzz/$target" "${flags[@]}" "$corpus" "fuzz/corpus/$target" >"$log" 2>&1
  status=$?
  set -e
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  if [ $status -eq 0 ]; then
    result="ok"
  else
    failed=1
    artifact=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | tail -1)
    reason=$(grep -m1 -E 'ERROR: (libFuzzer|AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer)|runtime error:|^fuzz: .* threw' "$log" || true)
    result="FAILED (exit $status) ${reason:-see $log} ${artifact:+input: $artifact}"
    tail -n 60 "$log"
  fi
  echo "=== $target: ${executions:-?} executions: $result"
  summary+=("$(printf '%-18s %12s executions  %s' "$target" "${executions:-?}" "$result")")
done

echo
echo "fuzz.sh: ${seconds}s per target (logs in $build/logs/)"
printf '%s\n' "${summary[@]}"
exit $failed
