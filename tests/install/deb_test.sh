#!/usr/bin/env bash
# The Debian package, end to end: `cpack -G DEB` in BUILD_DIR, then the package unpacked into a
# scratch root (dpkg-deb -x, as dpkg would install it, without touching the machine): its program
# meshes the sphere and its Python module meshes the torus, outside the source and build trees.
# Usage: deb_test.sh BUILD_DIR [PYTHON] (the interpreter the module was built for; none: no module)
set -euo pipefail
build=$1
python=${2:-}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
(cd "$scratch" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$scratch/package" > cpack.log)
deb=$(ls "$scratch"/package/delmesh_*.deb)
dpkg-deb -I "$deb" > "$scratch/info"
grep -q '^ Depends:.*libginac' "$scratch/info"
dpkg-deb -x "$deb" "$scratch/root"
cd "$scratch"
"$scratch/root/usr/bin/delmesh" mesh --surface sphere --quiet --out s.off --stats s.json
grep -q '"status": "complete"' s.json
if [ -n "$python" ]; then
  PYTHONPATH="$scratch/root/usr/lib/python3/dist-packages" "$python" -c \
    "import delmesh; r = delmesh.mesh(surface='torus'); assert r.status == 'complete', r.status; print('python:', r.status)"
fi
echo "deb_test: $(basename "$deb") installs a working program and module"
