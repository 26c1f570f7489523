#!/usr/bin/env bash
# The coating bed's resolution studies of docs/studies.md (section 2): CFD cell size and
# coarse-graining factor, 0.4 s of coating at 100 L/min, each against its finest variant
# (--finest 0: the 3.2 mm cells, cg 4).
#   scripts/study-coating-bed.sh [OUTDIR]        (default runs/; about 30 minutes here)
# Cell size: the vessel (36 mm), nozzle (4 mm, one cell), bed (4000 parcels) and coating zone stay
# the same; the side blocks get 5, 4 or 3 cells across 16 mm (3.2, 4.0, 5.3 mm, cell/parcel
# 2.1 to 3.6) and the height cells follow.
# Coarse-graining: the bed mass is fixed (4000 parcels at cg 5), parcels scale as cg^-3.
# Completed variants are read back, not run again (cosim study --rerun to force).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
out="${1:-runs}"
cosim="build/bin/cosim"
common=(--set coupling.end_time=0.4)
"$cosim" study scenarios/plasma-coating-bed --vary cell=0.0032,0.004,0.00533 \
  "${common[@]}" --finest 0 -o "$out/study-coating-cell"
"$cosim" study scenarios/plasma-coating-bed --vary cg=4,5,6 \
  --set 'n_grains=${round(4000*(5/cg)^3)}' "${common[@]}" --finest 0 -o "$out/study-coating-cg"
