#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, `cmake --preset fuzz`: clang with the address and
# undefined-behaviour sanitizers, into build-fuzz/) and runs each for a bounded time, seeded
# with the shipped scenes (scenario, expression), one message of every kind (protocol) and the
# saved corpus fuzz/corpus/<target>/. A crash leaves its input in build-fuzz/artifacts/ and
# makes the script exit non-zero: copy it to fuzz/corpus/<target>/ (replayed by ctest from then
# on), make it a regression test in tests/orchestrator/ and fix it.
#
#   scripts/fuzz.sh [SECONDS]      each target for SECONDS (default 30)
#   COSIM_JOBS=N                   build jobs (default: number of cores)
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
secs="${1:-30}"
jobs="${COSIM_JOBS:-$(nproc)}"
out=build-fuzz

if [ ! -f "$out/build.ninja" ]; then
  cmake --preset fuzz >/dev/null
fi
cmake --build "$out" --target fuzz_scenario fuzz_expression fuzz_protocol fuzz_protocol_seeds \
  -j "$jobs"

# Seeds: every shipped scene, and every ${expression} in them.
seeds="$out/seeds"
rm -rf "$seeds"
mkdir -p "$seeds/scenario" "$seeds/expression" "$out/corpus/scenario" "$out/corpus/expression" \
  "$out/corpus/protocol" "$out/artifacts"
i=0
while IFS= read -r f; do
  i=$((i + 1))
  cp "$f" "$seeds/scenario/scene-$i.yaml"
done < <(find scenarios -name '*.yaml' | sort)
i=0
while IFS= read -r e; do
  i=$((i + 1))
  printf '%s' "$e" >"$seeds/expression/expr-$i"
  printf '${%s}' "$e" >"$seeds/expression/text-$i"
done < <(grep -rhoE '\$\{[^}]+\}' scenarios | sed -E 's/^\$\{//; s/\}$//' | sort -u)

# One message of every kind.
"$out/bin/fuzz_protocol_seeds" "$seeds/protocol"

status=0
for target in scenario expression protocol; do
  dict=()
  if [ -f "fuzz/$target.dict" ]; then dict=(-dict="fuzz/$target.dict"); fi
  saved=()
  if [ -d "fuzz/corpus/$target" ]; then saved=("fuzz/corpus/$target"); fi
  echo "== fuzz_$target for $secs s"
  log="$out/fuzz_$target.log"
  if ! "$out/bin/fuzz_$target" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 \
      -max_len=65536 -print_final_stats=1 -artifact_prefix="$out/artifacts/$target-" \
      "${dict[@]}" "$out/corpus/$target" "$seeds/$target" "${saved[@]}" >"$log" 2>&1; then
    echo "fuzz_$target FOUND A PROBLEM (input in $out/artifacts/):"
    grep -E "ERROR|SUMMARY|Test unit written|uncaught|terminate" "$log" | head -20
    status=1
  fi
  # The last status line (executions, coverage) and the totals.
  grep -E '^#[0-9]+' "$log" | tail -1
  grep -E 'stat::number_of_executed_units|stat::peak_rss_mb' "$log" || true
done
exit $status
