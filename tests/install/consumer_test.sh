#!/usr/bin/env bash
# The installed package, end to end: installs the build BUILD_DIR into a scratch prefix, configures
# and builds the consumer project CONSUMER_DIR against it with find_package(delmesh), runs it, and
# runs the installed program.  Usage: consumer_test.sh BUILD_DIR CONSUMER_DIR
set -euo pipefail
build=$1
consumer=$2
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cmake --install "$build" --prefix "$scratch/prefix" > "$scratch/install.log"
cmake -S "$consumer" -B "$scratch/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$scratch/prefix" \
      > "$scratch/configure.log"
cmake --build "$scratch/build" -j2 > "$scratch/build.log"
"$scratch/build/consumer"
cd "$scratch"
"$scratch/prefix/bin/delmesh" mesh --surface sphere --quiet --out s.off --stats s.json
grep -q '"status": "complete"' s.json
echo "consumer_test: the installed library and program work"
