#!/usr/bin/env bash
# Section "3D Delaunay" of docs/BENCHMARKS.md: delmesh's Delaunay tetrahedralization
# (toolkit/tetmesh) against TetGen 1.5 (`tetgen -Q`, Debian package) on the same .node
# files: 1M points uniform in a cube and 1M points on a sphere (bench_delaunay3d
# generate, deterministic). Prints markdown on stdout. Run through `bash bench/run.sh tet3d`.
set -euo pipefail
BIN="${DELMESH_BENCH_BIN:?run through bench/run.sh}"
N="${DELMESH_TET3D_POINTS:-1000000}"
DATA="$(dirname "$BIN")/tet3d-data"

if ! command -v tetgen >/dev/null; then apt-get install -y tetgen >&2; fi
if [ ! -x /usr/bin/time ]; then apt-get install -y time >&2; fi

"$BIN/bench_delaunay3d" generate "$DATA" "$N"
rm -f "$DATA/ratios.txt"

# timed <outfile> <command...>: runs the command under GNU time; prints
# "wall_seconds cpu_seconds kbytes" (cpu = user + system).
timed() {
  local out=$1
  shift
  /usr/bin/time -f "%e %U %S %M" -o "$out" "$@" >/dev/null 2>&1
  awk '{ printf "%s %.2f %s\n", $1, $2 + $3, $4 }' "$out"
}

echo "## 3D Delaunay tetrahedralization (toolkit/tetmesh)"
echo
echo "Input: ${N} points uniform in the unit cube, and ${N} points on the unit sphere"
echo "(rounded to doubles, hence not exactly cospherical but nearly so everywhere: almost"
echo "every insphere and hull orient3d test needs the exact stage of the predicates). Same"
echo "\`.node\` files for both tools, run back to back, one core each. *Library* is the"
echo "in-process call \`delaunay_tetrahedralize\` on the points read from the \`.node\` file,"
echo "handed over by move so that the mesh is built in the reader's array (times exclude file"
echo "I/O; memory is the whole process's peak RSS, points included). *CLI* and *TetGen* are whole runs: read"
echo "\`.node\`, tetrahedralize, write \`.node\` + \`.ele\` (TetGen also writes \`.face\`),"
echo "measured with \`/usr/bin/time\`. The machine is shared with other jobs, so wall time is"
echo "inflated by waiting for a core; CPU time (user + system) is the steadier figure and the"
echo "rates use it. Bytes/tet = peak RSS / tets (finite tets: the mesh also stores one infinite"
echo "tet per hull face, about 2 per hull vertex, which on the sphere is every point)."
echo
echo "| input | run | tets | wall s | CPU s | points/CPU s | tets/CPU s | peak RSS (MB) | bytes/tet |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|"
for set in uniform sphere; do
  node="$DATA/$set.node"
  lib=$("$BIN/bench_delaunay3d" run "$node")
  get() { echo "$lib" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
  tets=$(get tets)
  awk -v s="$set" -v t="$tets" -v sec="$(get build_s)" -v cpu="$(get cpu_s)" -v rss="$(get peak_rss_bytes)" -v n="$N" \
    'BEGIN { printf "| %s | delmesh library | %d | %.2f | %.2f | %.0f | %.0f | %.0f | %.1f |\n", s, t, sec, cpu, n/cpu, t/cpu, rss/1048576, rss/t }'

  read -r cli_s cli_cpu cli_kb < <(timed "$DATA/time.txt" "$BIN/delmesh" delaunay "$node" -o "$DATA/$set.dm.node" --quiet)
  cli_tets=$(head -1 "$DATA/$set.dm.ele" | awk '{print $1}')
  awk -v s="$set" -v t="$cli_tets" -v sec="$cli_s" -v cpu="$cli_cpu" -v kb="$cli_kb" -v n="$N" \
    'BEGIN { printf "| %s | delmesh CLI | %d | %.2f | %.2f | %.0f | %.0f | %.0f | %.1f |\n", s, t, sec, cpu, n/cpu, t/cpu, kb/1024, kb*1024/t }'

  cp "$node" "$DATA/tg_$set.node"
  read -r tg_s tg_cpu tg_kb < <(timed "$DATA/time.txt" tetgen -Q "$DATA/tg_$set.node")
  tg_tets=$(head -1 "$DATA/tg_$set.1.ele" | awk '{print $1}')
  awk -v s="$set" -v t="$tg_tets" -v sec="$tg_s" -v cpu="$tg_cpu" -v kb="$tg_kb" -v n="$N" \
    'BEGIN { printf "| %s | TetGen 1.5 -Q | %d | %.2f | %.2f | %.0f | %.0f | %.0f | %.1f |\n", s, t, sec, cpu, n/cpu, t/cpu, kb/1024, kb*1024/t }'
  echo "$set $cli_s $tg_s $cli_cpu $tg_cpu" >> "$DATA/ratios.txt"
done
echo
echo "Ratio delmesh CLI / TetGen on whole runs (target: at most 0.5):"
echo
awk '{ printf "- %s: CPU time %.2f, wall time %.2f\n", $1, $4/$5, $2/$3 }' "$DATA/ratios.txt"
rm -f "$DATA/ratios.txt"
echo
echo "Equal tet counts are expected: the Delaunay tetrahedralization of points in general"
echo "position is unique, so both tools must produce the same tets."
