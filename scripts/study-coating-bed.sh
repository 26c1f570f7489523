#!/usr/bin/env bash
# The coating bed's resolution studies of docs/studies.md (section 2): cell size and
# coarse-graining factor, each against its finest variant, 0.4 s of coating at 100 L/min.
#   scripts/study-coating-bed.sh [OUTDIR]        (default runs/; about 25 minutes here)
# Cell size: the mesh keeps 9 cells across (nozzle = one cell), so the vessel is 9 cells wide
# (30, 36, 40 mm) and the parcel count keeps the bed depth; velocities are per area and the
# coating zone is fixed (4 mm -> 10 mm radius), so only the resolution changes.
# Coarse-graining: the bed mass is fixed (4000 parcels at cg 5), parcels scale as cg^-3.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
out="${1:-runs}"
cosim="build/bin/cosim"
common=(--set coupling.end_time=0.4 --set zone_base_radius=0.004 --set zone_top_radius=0.01)
"$cosim" study scenarios/plasma-coating-bed --vary cell=0.0033,0.004,0.0045 \
  --set 'W=${9*cell}' --set 'n=${cell}' --set 'hn=${cell}' --set 'n_grains=${round(4000*(9*cell/0.036)^2)}' \
  "${common[@]}" -o "$out/study-coating-cell"
"$cosim" study scenarios/plasma-coating-bed --vary cg=4,5,6 \
  --set 'n_grains=${round(4000*(5/cg)^3)}' "${common[@]}" -o "$out/study-coating-cg"
