#!/bin/bash
# The README's second command: install what is missing, build Release, run
# the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-dependencies.sh
bash scripts/build.sh Release
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd build-release
ctest -j "${TMFDEM_JOBS:-$(nproc)}" --output-on-failure --timeout 1200
