#!/usr/bin/env bash
# Sets everything up on a bare Debian 12 machine, builds, runs the default scene with live
# progress and writes its report. Extra arguments go to `cosim run` (e.g. --set flow_lpm=50);
# COSIM_SCENE=scenarios/settling-sphere picks a seconds-long analytic scene instead.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
scene="${COSIM_SCENE:-scenarios/plasma-coating-bed}"   # the quick coating bed, about 9 minutes
echo "== setup"; scripts/setup.sh
echo "== build"; scripts/build.sh
echo "== run $scene"
out="runs/$(basename "$scene")-$(date +%Y%m%d-%H%M%S)"
build/bin/cosim run "$scene" -o "$out" "$@"
if build/bin/cosim --help 2>/dev/null | grep -q report; then
  echo "== report"
  build/bin/cosim report "$out" || echo "(report incomplete: see above)"
fi
echo "results: $out"
