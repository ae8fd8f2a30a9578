#!/usr/bin/env bash
# The first set-up command of the README: installs the Debian packages if some are missing,
# builds the `delmesh` program (Release) and meshes the default catalog surface, the torus,
# writing out/torus.off (the mesh) and out/torus.json (its statistics).
# Extra arguments are passed to `delmesh mesh` (e.g. --lambda 0.03, --size-bound 0.1).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${DELMESH_BUILD_DIR:-build}
bash scripts/install-deps.sh
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -G Ninja
cmake --build "$build" --target delmesh -j "$(nproc)"
mkdir -p out
set +e
"$build/delmesh" mesh --surface torus --out out/torus.off --stats out/torus.json "$@"
status=$?
set -e
if [ $status -eq 0 ] || [ $status -eq 3 ]; then
  "$build/delmesh" check out/torus.off
fi
exit $status
