#!/usr/bin/env bash
# Installs the Debian 12 packages delmesh needs.  Usage: install-deps.sh [--dev]
#
# Without arguments: what building and running need, that is the default build of CMakeLists.txt
# (the libraries, the program `delmesh`, the Python module, the test suites and the experiment
# programs).  Boost.Test is in this set because the default build compiles the test suites
# (DELMESH_BUILD_TESTS is on by default) and CMakeLists.txt requires it in every build.
#
# --dev adds what running the tests and the rest of the workflow needs: clang, its sanitizer and
# libFuzzer runtimes and llvm-symbolizer (scripts/test.sh --sanitize, scripts/fuzz.sh); snakemake
# (experiments/Snakefile); matplotlib (figures, paper/); CGAL's data archive libcgal-demo (the
# tests on CGAL's sample meshes, the remeshing experiments); scikit-image (experiments/
# certify_peers.py); scikit-build and venv (the pip route and its test, tests/install/
# pip_test.sh); chromium (headless screenshots of `delmesh report` pages); npm (fetches three.js
# for `delmesh report` at build time), taken from Debian only when no `npm` command exists, since
# Debian's npm would conflict with a Node.js installed from elsewhere.
#
# Idempotent: only missing packages are installed.  Run as root (or with sudo).
set -euo pipefail

dev=false
case "${1:-}" in
  "") ;;
  --dev) dev=true ;;
  *) echo "error: unknown argument '$1' (usage: install-deps.sh [--dev])" >&2; exit 2 ;;
esac

packages=(
  build-essential cmake ninja-build pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libmpfi-dev
  libginac-dev libcln-dev
  libeigen3-dev
  libtbb-dev
  libgoogle-perftools-dev  # tcmalloc_minimal for the meshing programs (CMakeLists.txt)
  libboost-dev libboost-test-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev
  python3 python3-dev python3-numpy pybind11-dev  # the Python module (python/)
)
if $dev; then
  packages+=(
    clang libclang-rt-dev llvm
    snakemake
    python3-matplotlib
    libcgal-demo
    python3-skimage
    python3-skbuild python3-venv
    chromium
  )
  command -v npm > /dev/null || packages+=(npm)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: installed ${missing[*]}"
