#!/usr/bin/env bash
# Runs every benchmark part (bench/parts/*.sh) against a Release build and assembles
# docs/BENCHMARKS.md from the sections they write to docs/benchmarks/*.md.
# Usage: bash bench/run.sh [part ...]   (default: all parts)
#        bash bench/run.sh --assemble    (only rebuild docs/BENCHMARKS.md from the sections)
set -euo pipefail
cd "$(dirname "$0")/.."

assemble() {
  {
    echo "# delmesh benchmarks"
    echo
    echo "Produced by \`bash bench/run.sh\` on the project machine (2 cores, 24 GB, Debian 12);"
    echo "one core per run unless stated. Each section names its inputs and the reference tools run beside delmesh."
    echo
    for f in docs/benchmarks/*.md; do cat "$f"; echo; done
  } > docs/BENCHMARKS.md
  echo "bench: wrote docs/BENCHMARKS.md" >&2
}

if [ "${1:-}" = "--assemble" ]; then
  assemble
  exit 0
fi
cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DDELMESH_BUILD_TESTS=OFF >/dev/null
cmake --build build-bench -j2 >/dev/null
export DELMESH_BENCH_BIN="$PWD/build-bench/bin"
export DELMESH_CORPUS_DIR="${DELMESH_CORPUS_DIR:-$(cd .. && pwd)/shared/corpus}"
mkdir -p docs/benchmarks
parts=("$@")
if [ ${#parts[@]} -eq 0 ]; then
  for f in bench/parts/*.sh; do parts+=("$(basename "$f" .sh)"); done
fi
for part in "${parts[@]}"; do
  echo "bench: $part" >&2
  bash "bench/parts/$part.sh" > "docs/benchmarks/$part.md"
done
assemble
