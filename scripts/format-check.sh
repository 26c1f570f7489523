#!/usr/bin/env bash
# Fails when a C++ file of ours is not as clang-format (.clang-format) writes it, naming the
# files; `scripts/format-check.sh --fix` rewrites them. The OpenFOAM adapter's .C/.H equation
# files keep OpenFOAM's own style and are left out.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.h' '*.hpp' | grep -v '^adapters/openfoam/.*\.[CH]$')
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
  exit 0
fi
bad=()
for f in "${files[@]}"; do
  clang-format --dry-run -Werror "$f" > /dev/null 2>&1 || bad+=("$f")
done
if [ ${#bad[@]} -gt 0 ]; then
  echo "format: ${#bad[@]} file(s) not as clang-format writes them (scripts/format-check.sh --fix):"
  printf '  %s\n' "${bad[@]}"
  exit 1
fi
echo "format: ${#files[@]} files as clang-format writes them"
