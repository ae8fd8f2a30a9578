#!/usr/bin/env bash
# Installs every Debian package that building, testing and running the experiments of delmesh needs
# (clang, its sanitizer and libFuzzer runtimes and llvm-symbolizer for scripts/fuzz.sh; snakemake
# for the sweep workflow experiments/Snakefile).
# Idempotent: packages already present are skipped by apt-get.  Run as root (or with sudo).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libmpfi-dev
  libginac-dev libcln-dev
  libeigen3-dev
  libtbb-dev
  libgoogle-perftools-dev  # tcmalloc_minimal for the meshing programs (CMakeLists.txt)
  libboost-dev libboost-test-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev
  libbenchmark-dev
  python3 python3-matplotlib
  python3-dev python3-numpy pybind11-dev  # the Python module (python/)
  snakemake
  libcgal-demo
  clang libclang-rt-dev llvm
)

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
