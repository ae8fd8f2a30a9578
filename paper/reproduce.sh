#!/usr/bin/env bash
# Reproduces every figure and table of paper/: builds the experiment programs (Release), runs them
# (CSV files and meshes under $OUT), then runs the figure and table scripts (PNG and tables under
# $OUT/figures and $OUT/tables).  The scripts read only those CSV and mesh files.  The λ sweep runs
# as the Snakemake workflow experiments/Snakefile ($JOBS jobs at a time, one delmesh thread each),
# which also draws its figures.  Fig. 13 remeshes meshes of CGAL's data archive (package
# libcgal-demo), extracted into $OUT/remesh/inputs.
#
#   paper/reproduce.sh [--quick] [--skip-build]
#     OUT=out  BUILD=build-paper  JOBS=2  TIME_LIMIT=600 (seconds per delmesh run)
#   --quick: λ ∈ {0.06, 0.05} on sphere, torus, metaball only, only the CGAL benchmark, and only
#            elephant, eight and knot1 remeshed.
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
  cmake --build "$BUILD" --target lambda_sweep compare_cgal remesh -j "$JOBS"
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

CGAL_DATA=/usr/share/doc/libcgal-dev/data.tar.gz
REMESH="elephant eight knot1"
[ "$QUICK" = 1 ] || REMESH="$REMESH knot2 femur bunny00"
mkdir -p "$OUT/remesh/inputs"
inputs=()
for name in $REMESH; do
  tar -xzf "$CGAL_DATA" -C "$OUT/remesh/inputs" "data/meshes/$name.off"
  inputs+=("$OUT/remesh/inputs/data/meshes/$name.off")
done
"$BUILD/experiments/remesh" --time-limit "$TIME_LIMIT" --out-dir "$OUT" "${inputs[@]}"

PY=/usr/bin/python3
"$PY" "$ROOT/paper/fig12_meshes.py" --out "$OUT"
"$PY" "$ROOT/paper/fig13_remesh.py" --out "$OUT"
"$PY" "$ROOT/paper/cgal_table.py" --out "$OUT"
"$PY" "$ROOT/paper/demo_figure.py" --out "$OUT" || echo "reproduce: no demo meshes (run compare_cgal with the demo experiment)"
echo "reproduce: figures in $OUT/figures, tables in $OUT/tables"
