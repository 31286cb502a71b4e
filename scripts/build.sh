#!/bin/bash
# Configures and builds tmfdem (Release by default) in build-<type>/.
# usage: scripts/build.sh [Release|Debug]
set -euo pipefail
cd "$(dirname "$0")/.."
type=${1:-Release}
dir=build-$(echo "$type" | tr '[:upper:]' '[:lower:]')
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE="$type" > /dev/null
cmake --build "$dir" -j "${TMFDEM_JOBS:-2}"
echo "[tmfdem] built $dir/tmfdem"
