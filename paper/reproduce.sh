#!/usr/bin/env bash
# Reproduces every figure and table of paper/: builds the experiment programs (Release), runs them
# (CSV files and meshes under $OUT), then runs the figure and table scripts (PNG and tables under
# $OUT/figures and $OUT/tables).  The scripts read only those CSV and mesh files.  The λ sweep runs
# as the Snakemake workflow experiments/Snakefile ($JOBS jobs at a time, one delmesh thread each),
# which also draws its figures.
#
#   paper/reproduce.sh [--quick] [--skip-build]
#     OUT=out  BUILD=build-paper  JOBS=2  TIME_LIMIT=600 (seconds per delmesh run)
#   --quick: λ ∈ {0.06, 0.05} on sphere, torus, metaball only, and only the CGAL benchmark.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="$(realpath -m "${OUT:-out}")"
BUILD="${BUILD:-$ROOT/build-paper}"
JOBS="${JOBS:-2}"
TIME_LIMIT="${TIME_LIMIT:-600}"
QUICK=0
BUILD_IT=1
for arg in "$@"; do
  case "$arg" in
    --quick) QUICK=1 ;;
    --skip-build) BUILD_IT=0 ;;
    *) echo "usage: $0 [--quick] [--skip-build]" >&2; exit 2 ;;
  esac
done

if [ "$BUILD_IT" = 1 ]; then
  cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$BUILD" --target lambda_sweep compare_cgal -j "$JOBS"
fi
mkdir -p "$OUT"

sweep() {
  snakemake -s "$ROOT/experiments/Snakefile" --directory "$OUT" --cores "$JOBS" \
      --config out="$OUT" bin="$BUILD/experiments/lambda_sweep" time_limit="$TIME_LIMIT" "$@"
}
if [ "$QUICK" = 1 ]; then
  sweep surfaces=sphere,torus,metaball lambdas=0.06,0.05
  "$BUILD/experiments/compare_cgal" --experiments benchmark --time-limit "$TIME_LIMIT" --out-dir "$OUT"
else
  sweep surfaces=sphere,ellipsoid,torus,genus2,metaball,two_blobs,thin_handle,near_sheets \
      lambdas=0.06,0.05,0.04,0.03,0.02
  "$BUILD/experiments/compare_cgal" --time-limit "$TIME_LIMIT" --out-dir "$OUT"
fi

PY=/usr/bin/python3
"$PY" "$ROOT/paper/fig12_meshes.py" --out "$OUT"
"$PY" "$ROOT/paper/cgal_table.py" --out "$OUT"
"$PY" "$ROOT/paper/demo_figure.py" --out "$OUT" || echo "reproduce: no demo meshes (run compare_cgal with the demo experiment)"
echo "reproduce: figures in $OUT/figures, tables in $OUT/tables"
