#!/usr/bin/env bash
# The paper's fluidization-flow sweep: runs the coating bed at 1, 50, 100 and 200 L/min, one run
# folder each, then one comparison report over the four (CV over time, CV against mean coating,
# fits, extrapolations side by side).
#   scripts/sweep-flows.sh [SCENARIO] [OUTDIR] [extra cosim run args, e.g. --set coupling.end_time=2]
# Defaults: scenarios/plasma-coating-bed (quick size, ~7 min a flow here), runs/flow-sweep.
# FLOWS="50 200" scripts/sweep-flows.sh runs a subset. A flow whose run folder already holds a
# completed summary.json is not run again, so an interrupted sweep resumes where it stopped.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
scene="${1:-scenarios/plasma-coating-bed}"
out="${2:-runs/flow-sweep}"
shift $(( $# > 2 ? 2 : $# ))
flows="${FLOWS:-1 50 100 200}"
cosim="build/bin/cosim"
[ -x "$cosim" ] || { echo "sweep-flows: $cosim not built: run scripts/build.sh first" >&2; exit 1; }
mkdir -p "$out"
runs=()
for f in $flows; do
  dir="$out/flow-$f"
  runs+=("$dir")
  if [ -f "$dir/summary.json" ] && grep -q '"status": *"completed"' "$dir/summary.json"; then
    echo "== flow $f L/min: already done ($dir)"
    continue
  fi
  echo "== flow $f L/min -> $dir"
  "$cosim" run "$scene" --set "flow_lpm=$f" -o "$dir" --overwrite "$@"
done
echo "== comparison report"
"$cosim" report "${runs[@]}" -o "$out/report"
echo "sweep-flows: open $out/report/comparison.html (each flow: $out/report/flow-N/report.html)"
