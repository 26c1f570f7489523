#!/usr/bin/env bash
# clang-tidy with the project's chosen checks (.clang-tidy: bugs and needless copies that the
# compiler's warnings miss) over our sources, in parallel; a finding fails, naming file, line and
# check. Needs a configured build (compile_commands.json; scripts/build.sh). Left out: the tests,
# and the files that include OpenFOAM's v1912 headers, which use GCC-only attributes that clang
# rejects. `scripts/tidy.sh FILE...` checks only those files.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build="${COSIM_BUILD:-build}"
if [ ! -f "$build/compile_commands.json" ]; then
  echo "tidy: $build/compile_commands.json missing: build first (scripts/build.sh)" >&2
  exit 1
fi
if [ $# -gt 0 ]; then
  files=("$@")
else
  mapfile -t files < <(python3 - "$build/compile_commands.json" "$PWD" <<'PY'
import json, sys
root = sys.argv[2] + "/"
seen = set()
for e in json.load(open(sys.argv[1])):
    f = e["file"]
    rel = f[len(root):] if f.startswith(root) else None
    if rel is None or rel in seen:
        continue
    if rel.startswith(("tests/", "fuzz/", "bench/", "build")) or rel.startswith("adapters/openfoam/"):
        continue
    seen.add(rel)
    print(rel)
PY
)
fi
jobs="$(nproc)"
echo "tidy: ${#files[@]} files, $jobs at a time"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
printf '%s\n' "${files[@]}" | xargs -P "$jobs" -I{} sh -c \
  'clang-tidy -p "$1" --quiet "$2" > "$3.$$" 2>&1 || { cat "$3.$$" >> "$3"; rm -f "$3.$$"; exit 1; }; rm -f "$3.$$"' \
  _ "$build" {} "$log" || true
if [ -s "$log" ]; then
  grep -E "(warning|error):" "$log" | sort -u
  echo "tidy: findings above (.clang-tidy lists the checks)"
  exit 1
fi
echo "tidy: no findings"
