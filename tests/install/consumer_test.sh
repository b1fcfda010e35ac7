#!/usr/bin/env bash
# The installed package as a user meets it: `cmake --install` of this build
# into a scratch prefix, then tests/install/consumer (find_package(skinmesh
# CONFIG REQUIRED), target_link_libraries(consumer skinmesh::skinmesh)) is
# configured, built and run on two weighted points and on a bundled molecule.
# Usage: consumer_test.sh BUILD_DIR CXX_COMPILER
set -euo pipefail
build=$1
cxx=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log"
echo "installed: $(find "$tmp/prefix" -type f | wc -l) files, $(find "$tmp/prefix/include" -name '*.h' | wc -l) headers"
cmake -S "$root/tests/install/consumer" -B "$tmp/consumer" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=Release > "$tmp/configure.log" || { cat "$tmp/configure.log"; exit 1; }
cmake --build "$tmp/consumer" > "$tmp/build.log" 2>&1 || { cat "$tmp/build.log"; exit 1; }
"$tmp/consumer/consumer"
"$tmp/consumer/consumer" "$root/data/ligand_2zmm.pdb"
