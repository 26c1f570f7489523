#!/usr/bin/env bash
# ctest paraview.ParticlesVisibleInTheDefaultView: records the run of coated-particles.yaml with
# cosim and opens its particles.xmf with ParaView's own Python (pvpython), in a virtual X server
# when there is no display (ParaView 5.11 of Debian renders through X).
#
#   check_particles_in_paraview.sh COSIM_EXECUTABLE
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cosim="$1"

missing=""
command -v pvpython >/dev/null || missing="pvpython (Debian packages paraview, python3-paraview)"
if [ -z "${DISPLAY:-}" ] && ! command -v xvfb-run >/dev/null; then
  missing="${missing:+$missing, }xvfb-run (Debian packages xvfb, xauth)"
fi
if [ -n "$missing" ]; then
  echo "FAIL: $missing not installed: run scripts/setup.sh (it installs everything the tests use)" >&2
  exit 1
fi

work="$(mktemp -d "${TMPDIR:-/tmp}/cosim-paraview.XXXXXX")"
trap 'rm -rf "$work"' EXIT
"$cosim" run "$here/coated-particles.yaml" -o "$work/run" --quiet

display=()
[ -z "${DISPLAY:-}" ] && display=(xvfb-run -a)
"${display[@]}" pvpython "$here/check_particles_in_paraview.py" "$work/run/particles.xmf" \
  "$work/view.png"
