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
# A 24-bit screen (xvfb-run's default is 8-bit, which GLX visuals may lack)
[ -z "${DISPLAY:-}" ] && display=(xvfb-run -a -s "-screen 0 800x600x24")
# ParaView aborts (SIGABRT) when it cannot create its X window, which a virtual X server that is
# still starting on a busy machine can cause: that, and only that, is tried once more.
for attempt in 1 2; do
  status=0
  "${display[@]}" pvpython "$here/check_particles_in_paraview.py" "$work/run/particles.xmf" \
    "$work/view.png" || status=$?
  [ "$status" -eq 134 ] && [ "$attempt" -eq 1 ] && { echo "ParaView could not open its window (SIGABRT); once more" >&2; continue; }
  exit "$status"
done
