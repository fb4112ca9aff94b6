#!/usr/bin/env bash
# Benchmark section "delmesh tri end to end": the command line as users run it, file
# reading and writing included, on the two inputs of issue 2:
#   * Delaunay triangulation of 1,000,000 uniform random points (a generated .node file,
#     deterministic: bench_tri2d_random_points, seed 1), without and with writing the result;
#   * refinement of A.poly (corpus poly2d/drufat-a.poly) at 30 degrees with max area 5e-8,
#     without and with writing .node/.ele/.poly.
# Wall time and peak resident memory come from /usr/bin/time -v (Debian package `time`),
# the triangle count from delmesh's summary. Shewchuk's Triangle runs beside it when the
# Debian package triangle-bin can be installed (it is in the non-free component).
# Prints a markdown section on stdout. Environment (set by bench/run.sh): DELMESH_BENCH_BIN,
# DELMESH_CORPUS_DIR.
set -euo pipefail

bin="${DELMESH_BENCH_BIN:?run through bench/run.sh}"
corpus="${DELMESH_CORPUS_DIR:?run through bench/run.sh}"
apoly="$corpus/poly2d/drufat-a.poly"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; elif command -v sudo >/dev/null; then sudo "$@"; else return 1; fi; }

if [ ! -x /usr/bin/time ]; then
  echo "tri2d_io: installing the Debian package 'time'" >&2
  as_root apt-get install -y -qq time >/dev/null
fi
if ! command -v triangle >/dev/null; then
  if apt-cache policy triangle-bin 2>/dev/null | grep -q 'Candidate: [0-9]'; then
    echo "tri2d_io: installing the Debian package 'triangle-bin' (reference)" >&2
    as_root apt-get install -y -qq triangle-bin >/dev/null || true
  fi
fi

"$bin/bench_tri2d_random_points" 1000000 "$work/points.node" 1
cp "$apoly" "$work/A.poly"

repeat="${TRI2D_IO_REPEAT:-3}"
rows=()
# measure LABEL KIND COMMAND...: runs the command $repeat times under /usr/bin/time -v and
# appends a table row for the fastest run (the machine is shared, so the minimum is the
# least disturbed figure). KIND is delmesh or triangle (where the triangle count is read).
measure() {
  local label="$1" kind="$2"
  shift 2
  local best_wall="" best_rss="" best_cpu="" run wall rss_kb cpu
  for ((run = 0; run < repeat; run++)); do
    if ! /usr/bin/time -v -o "$work/time.txt" "$@" >"$work/out.txt" 2>"$work/err.txt"; then
      echo "tri2d_io: '$label' failed:" >&2
      cat "$work/err.txt" >&2
      rows+=("| $label | failed | | | | | | | |")
      return
    fi
    wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {
             n = split($2, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i]; print s }' "$work/time.txt")
    rss_kb=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$work/time.txt")
    cpu=$(awk -F': ' '/User time \(seconds\)|System time \(seconds\)/ {s += $2} END {print s}' "$work/time.txt")
    if [ -z "$best_wall" ] || awk -v a="$wall" -v b="$best_wall" 'BEGIN { exit !(a < b) }'; then
      best_wall=$wall
      best_rss=$rss_kb
      best_cpu=$cpu
      cp "$work/out.txt" "$work/best.txt"
    fi
  done
  local triangles phases=""
  if [ "$kind" = delmesh ]; then
    triangles=$(awk '/^triangles:/ {print $2}' "$work/best.txt")
    phases=$(sed -n 's/^time: *[0-9.]* s (\(.*\))$/\1/p' "$work/best.txt")
  else
    triangles=$(grep -Eo '(Mesh|Output) triangles: *[0-9]+' "$work/best.txt" | tail -1 | grep -Eo '[0-9]+$' || true)
  fi
  triangles=${triangles:-0}
  rows+=("$(awk -v l="$label" -v t="$triangles" -v w="$best_wall" -v c="$best_cpu" -v r="$best_rss" -v ph="$phases" 'BEGIN {
    tps = (w > 0) ? t / w : 0; cps = (c > 0) ? t / c : 0; bpt = (t > 0) ? r * 1024 / t : 0;
    printf "| %s | %d | %.2f | %.2f | %.2f M | %.2f M | %.0f | %.0f | %s |", l, t, w, c, tps / 1e6, cps / 1e6, r / 1024, bpt, ph }')")
}

dm="$bin/delmesh"
measure "delmesh: Delaunay, 1M points, no output" delmesh "$dm" tri "$work/points.node" --no-output
measure "delmesh: Delaunay, 1M points, write .node/.ele" delmesh "$dm" tri -P "$work/points.node" -o "$work/dm-points.node"
measure "delmesh: A.poly -pq30a5e-8, no output" delmesh "$dm" tri -pq30a5e-8 "$work/A.poly" --no-output
measure "delmesh: A.poly -pq30a5e-8, write .node/.ele/.poly" delmesh "$dm" tri -pq30a5e-8 "$work/A.poly" -o "$work/dm-A.node"

triangle_note="Shewchuk's Triangle was not run: the Debian package triangle-bin is not available from the configured package sources (it lives in Debian's non-free component)."
if command -v triangle >/dev/null; then
  triangle_note="Triangle: $(command -v triangle), run with -V to report its triangle count (its -N -E -P suppress output files)."
  cp "$work/points.node" "$work/tp.node"
  cp "$work/A.poly" "$work/tA.poly"
  measure "Triangle: Delaunay, 1M points, no output" triangle triangle -VNEP "$work/tp.node"
  measure "Triangle: Delaunay, 1M points, write .node/.ele" triangle triangle -V "$work/tp.node"
  measure "Triangle: A.poly -pq30a0.00000005, no output" triangle triangle -VNEPpq30a0.00000005 "$work/tA.poly"
  measure "Triangle: A.poly -pq30a0.00000005, write .node/.ele/.poly" triangle triangle -Vpq30a0.00000005 "$work/tA.poly"
fi

echo "## delmesh tri end to end (tri2d_io)"
echo
echo "The \`delmesh tri\` command line as a user runs it: process wall time and peak resident"
echo "memory from \`/usr/bin/time -v\`, reading the input and (where stated) writing the result"
echo "included; the fastest of $repeat runs each. The machine is shared with other jobs, so wall"
echo "times are inflated when it is loaded; CPU time (user + system) is the steadier figure. The"
echo "phases are delmesh's own split of its wall time. Inputs: 1,000,000 uniform random points in the unit square"
echo "(\`bench_tri2d_random_points 1000000 points.node 1\`, $(du -h "$work/points.node" | cut -f1)B),"
echo "and \`A.poly\` (corpus \`poly2d/drufat-a.poly\`) refined to 30 degrees with max area 5e-8."
echo "Machine: $(nproc) cores shared with other jobs (load average $(cut -d' ' -f1-3 /proc/loadavg) at the end of the run),"
echo "$(awk '/MemTotal/ {printf "%.0f GB", $2 / 1048576}' /proc/meminfo) RAM; delmesh $(git -C "$(dirname "$0")/../.." rev-parse --short HEAD 2>/dev/null || echo '?') Release build."
echo
echo "| run | triangles | wall s | CPU s | triangles/s (wall) | triangles/s (CPU) | peak RSS MB | bytes/triangle | phases (s, wall) |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---|"
for r in "${rows[@]}"; do echo "$r"; done
echo
echo "$triangle_note"
echo "Targets of issue 2 (Triangle 1.6 measured on this machine class): 1M-point Delaunay 1.8 s"
echo "including reading the .node file, 3.9 s with writing the result; A.poly at -pq30a5e-8:"
echo "2.66M triangles in 2.3-2.7 s without file output, 5-7 s writing .node/.ele;"
echo "at most 100 bytes per triangle at peak (Triangle: about 158)."
