#!/usr/bin/env bash
# The paper's fluidization-flow sweep: runs the coating bed at 1, 50, 100 and 200 L/min, one run
# folder each, then one comparison report over the four (CV over time, CV against mean coating,
# fits, extrapolations side by side).
#   scripts/sweep-flows.sh [SCENARIO] [OUTDIR] [extra cosim run args, e.g. --set coupling.end_time=2]
# Defaults: scenarios/plasma-coating-bed (quick size, ~7 min a flow here), runs/flow-sweep.
# FLOWS="50 200" scripts/sweep-flows.sh runs a subset; SEEDS="10007 10009" runs each flow once per
# LIGGGHTS insertion seed (primes above 10000, as LIGGGHTS requires; another packing of the same
# bed: the run-to-run noise), into
# flow-F-seed-S. A flow whose run folder already holds a
# completed summary.json is not run again; one that stopped before its end (Ctrl-C, a kill, a
# job's time limit) and holds a checkpoint is continued with `cosim resume`, so a sweep of long
# runs (scenarios/plasma-coating-bed/study.yaml) is run in pieces by calling it again.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
scene="${1:-scenarios/plasma-coating-bed}"
out="${2:-runs/flow-sweep}"
shift $(( $# > 2 ? 2 : $# ))
flows="${FLOWS:-1 50 100 200}"
seeds="${SEEDS:-}"
cosim="build/bin/cosim"
[ -x "$cosim" ] || { echo "sweep-flows: $cosim not built: run scripts/build.sh first" >&2; exit 1; }
mkdir -p "$out"
runs=()
for f in $flows; do
  for seed in ${seeds:-scene}; do
    dir="$out/flow-$f"
    extra=()
    if [ "$seed" != scene ]; then
      dir="$out/flow-$f-seed-$seed"
      extra=(--set "insert_seed=$seed")
    fi
    runs+=("$dir")
    if [ -f "$dir/summary.json" ] && grep -q '"status": *"completed"' "$dir/summary.json"; then
      echo "== flow $f L/min: already done ($dir)"
      continue
    fi
    if compgen -G "$dir/checkpoints/*/orchestrator.json" > /dev/null; then
      echo "== flow $f L/min: resuming $dir from its newest checkpoint"
      "$cosim" resume "$dir" "$@"
      continue
    fi
    echo "== flow $f L/min -> $dir"
    "$cosim" run "$scene" --set "flow_lpm=$f" "${extra[@]}" -o "$dir" --overwrite "$@"
  done
done
echo "== comparison report"
"$cosim" report "${runs[@]}" -o "$out/report"
echo "sweep-flows: open $out/report/comparison.html (each flow: $out/report/flow-N/report.html)"
