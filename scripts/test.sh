#!/usr/bin/env bash
# Sets everything up on a bare Debian 12 machine, builds, and runs the whole test suite (ctest).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
echo "== setup"; scripts/setup.sh
echo "== build"; scripts/build.sh
echo "== tests"
cd build
ctest --output-on-failure --timeout 900 "$@"
