#!/usr/bin/env bash
# Configures and builds everything (Release, warnings on) into build/. Idempotent and incremental.
#   scripts/build.sh              build
#   COSIM_JOBS=4 scripts/build.sh more parallel jobs (default: number of cores)
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
jobs="${COSIM_JOBS:-$(nproc)}"
if [ ! -f build/build.ninja ]; then
  cmake --preset default
fi
cmake --build build -j "$jobs"
