#!/usr/bin/env bash
# Sets everything up on a bare Debian 12 machine, checks the format, builds, runs clang-tidy's
# chosen checks (.clang-tidy), fuzzes each libFuzzer target for a bounded
# time (COSIM_FUZZ_SECONDS, default 20) and runs the whole test suite (ctest).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
echo "== setup"; scripts/setup.sh
echo "== format"; scripts/format-check.sh
echo "== build"; scripts/build.sh
echo "== tidy"; scripts/tidy.sh
# The libFuzzer targets (scenario loader, expression evaluator, protocol decoder), each for a
# bounded time after an instrumented build of about 10 CPU-minutes; a crash fails the suite and
# leaves its input in build-fuzz/artifacts/ (docs/when-things-go-wrong.md, "Fuzzing")
echo "== fuzz"; scripts/fuzz.sh "${COSIM_FUZZ_SECONDS:-20}"
echo "== tests"
# The Slurm tests start a one-node cluster (scripts/local-slurm.sh) and leave it running for each
# other; it is stopped when the suite ends, whatever its outcome.
trap 'scripts/local-slurm.sh stop > /dev/null 2>&1 || true' EXIT
(cd build && ctest --output-on-failure --timeout 900 "$@")
