#!/usr/bin/env bash
# ctest fuzz_parsers: builds delmesh's libFuzzer targets (tests/fuzz/*_fuzz.cpp) in a separate
# clang build and runs each for a bounded time from a small inline seed corpus. Fails when
# clang is missing, the build fails, or any target finds a crash, leak, timeout or
# sanitizer report (the reproducer is left in <work dir>/artifacts/).
# Usage: run_fuzzers.sh <source dir> <work dir> [seconds per target, default 20]
set -euo pipefail

src=$1
work=$2
seconds=${3:-20}
targets=(triangle_format stl off obj ply tetgen)

if ! command -v clang >/dev/null || ! command -v clang++ >/dev/null; then
  echo "run_fuzzers: clang/clang++ not found (bash .ci/install-deps installs clang and libclang-rt-14-dev)" >&2
  exit 1
fi

build=$work/build
mkdir -p "$build"
CC=clang CXX=clang++ cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDELMESH_FUZZ=ON \
  -DDELMESH_BUILD_TESTS=OFF -DDELMESH_BUILD_BENCH=OFF -DDELMESH_WITH_OCCT=OFF -DDELMESH_WERROR=ON >/dev/null
cmake --build "$build" -j2 --target "${targets[@]/#/fuzz_}"

# Seeds: one small valid file per format.
seeds=$work/seeds
rm -rf "$seeds" "$work/corpus" "$work/artifacts"
mkdir -p "$seeds"/{triangle_format,stl,off,obj,ply,tetgen} "$work/artifacts"
printf '4 2 0 1\n1 0 0 1\n2 1 0 1\n3 1 1 0\n4 0 1 0\n' >"$seeds/triangle_format/square.node"
printf '4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n4 1\n1 1 2 5\n2 2 3 5\n3 3 4 5\n4 4 1 5\n1\n1 0.5 0.5\n' \
  >"$seeds/triangle_format/square_hole.poly"
printf 'solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n' \
  >"$seeds/stl/ascii.stl"
{ head -c 80 /dev/zero; printf '\001\000\000\000'; head -c 12 /dev/zero
  printf '\000\000\000\000\000\000\000\000\000\000\000\000'
  printf '\000\000\200\077\000\000\000\000\000\000\000\000'
  printf '\000\000\000\000\000\000\200\077\000\000\000\000'
  printf '\000\000'; } >"$seeds/stl/binary.stl"
printf 'OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n' >"$seeds/off/tet.off"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvn 0 0 1\nf 1 3 2\nf 1/1 2/1 4/1\nf 2//1 3//1 4//1\nf -4 -1 -2\nl 1 2\n' \
  >"$seeds/obj/tet.obj"
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n' \
  >"$seeds/ply/ascii.ply"
{ printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n'
  head -c 12 /dev/zero; printf '\000\000\200\077\000\000\000\000\000\000\000\000'
  printf '\000\000\000\000\000\000\200\077\000\000\000\000'
  printf '\003\000\000\000\000\001\000\000\000\002\000\000\000'; } >"$seeds/ply/binary.ply"
# tetgen: the first byte picks the kind (0 .node, 1 .poly, 2 .smesh).
printf '\0004 3 0 1\n1 0 0 0 1\n2 1 0 0 1\n3 0 1 0 1\n4 0 0 1 1\n' >"$seeds/tetgen/tet.node"
printf '\0014 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n4 1\n1 0 1\n3 1 3 2\n1 0 2\n3 1 2 4\n1 0 3\n3 2 3 4\n1 0 4\n3 1 4 3\n0\n1\n1 0.1 0.1 0.1 7 0.01\n# facet_marker 1 name "a b" color #ff00A0\n# region 7 name "r"\n' \
  >"$seeds/tetgen/tet.poly"
printf '\0024 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n4 1\n3 1 3 2 1\n3 1 2 4 2\n3 2 3 4 3\n3 1 4 3 4\n0\n0\n' \
  >"$seeds/tetgen/tet.smesh"

failed=()
for t in "${targets[@]}"; do
  mkdir -p "$work/corpus/$t"
  echo "run_fuzzers: fuzz_$t for ${seconds}s" >&2
  if ! "$build/bin/fuzz_$t" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=4096 \
       -print_final_stats=1 -artifact_prefix="$work/artifacts/$t-" \
       "$work/corpus/$t" "$seeds/$t" 2>"$work/$t.log"; then
    failed+=("$t")
    tail -n 60 "$work/$t.log" >&2
  else
    grep -E '^stat::number_of_executed_units|^Done' "$work/$t.log" >&2 || true
  fi
done

if ((${#failed[@]})); then
  echo "run_fuzzers: FAILED: ${failed[*]} (reproducers in $work/artifacts/)" >&2
  exit 1
fi
echo "run_fuzzers: all ${#targets[@]} targets ran ${seconds}s each without a finding" >&2
