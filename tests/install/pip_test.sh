#!/usr/bin/env bash
# The pip route, end to end and offline: copies the source tree SOURCE_DIR (its tracked and
# untracked, not ignored files) to a scratch directory, makes a venv of PYTHON (default Debian's
# /usr/bin/python3) with the system's site packages, runs `pip install --no-build-isolation
# --no-index .` there (setup.py: scikit-build and the project's CMake build), then, outside the
# source tree, imports the installed module and meshes the torus, and runs the installed program.
# The venv must hold the module and the program only: no libraries, headers or CMake package.
# Usage: pip_test.sh SOURCE_DIR [PYTHON]
set -euo pipefail
source_dir=$(realpath "$1")
python=${2:-/usr/bin/python3}
if ! "$python" -c "import skbuild, venv, numpy" 2> /dev/null; then
  echo "pip_test: $python needs scikit-build, venv and numpy (scripts/install-deps.sh --dev)" >&2
  exit 1
fi
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

mkdir "$scratch/src"
if git -C "$source_dir" rev-parse --is-inside-work-tree > /dev/null 2>&1; then
  (cd "$source_dir" && git ls-files -z --cached --others --exclude-standard \
     | tar --null --files-from=- --ignore-failed-read -cf - 2> /dev/null) | tar -xf - -C "$scratch/src"
else
  (cd "$source_dir" && tar --exclude='./build*' --exclude=./out --exclude=./_skbuild -cf - .) | tar -xf - -C "$scratch/src"
fi

"$python" -m venv --system-site-packages "$scratch/venv"
venv=$scratch/venv
start=$SECONDS
if ! (cd "$scratch/src" && "$venv/bin/pip" install -v --no-build-isolation --no-index . > "$scratch/pip.log" 2>&1); then
  tail -n 60 "$scratch/pip.log"
  echo "pip_test: pip install failed" >&2
  exit 1
fi
echo "pip_test: pip install took $((SECONDS - start)) s"

cd "$scratch"
"$venv/bin/python" - "$venv" <<'EOF'
import os, sys
import delmesh
venv = os.path.realpath(sys.argv[1])
where = os.path.realpath(delmesh.__file__)
assert where.startswith(os.path.join(venv, "lib")) and "site-packages" in where, where
r = delmesh.mesh(surface="torus")
assert r.status == "complete", r.status
print("python:", where[len(venv) + 1:], r.status)
EOF
"$venv/bin/delmesh" mesh --surface sphere --quiet --out s.off --stats s.json
grep -q '"status": "complete"' s.json
if [ -e "$venv/include/delmesh" ] || compgen -G "$venv/lib/libdelmesh_*" > /dev/null || [ -e "$venv/lib/cmake/delmesh" ]; then
  echo "pip_test: the venv holds development files (libraries, headers or the CMake package)" >&2
  exit 1
fi
echo "pip_test: pip installs a working module and program into a venv"
