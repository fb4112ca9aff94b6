#!/usr/bin/env bash
# Section "Sliver removal" of docs/BENCHMARKS.md (issue 6 item 5): `delmesh mesh` at
# radius-edge bound 1.414 without and with the dihedral window 20-150 degrees
# (`--min-dihedral 20 --max-dihedral 150`: dihedral-bound refinement and the improvement
# pass, refiners/tet3d/sliver_improvement.h), beside TetGen 1.5 (`tetgen -pq1.414/15 -O`,
# Debian package tetgen) on the same PLC and Gmsh's HXT mesher (`gmsh -3 -algo hxt
# -optimize`, Debian package gmsh) on the surface or STEP file. Quality of every output is
# measured by the same code (bench_mesh_quality, toolkit/quality). Prints markdown on
# stdout. Run through `bash bench/run.sh slivers`.
set -euo pipefail
source "$(dirname "$0")/../mesher_comparison.sh"
BIN="${DELMESH_BENCH_BIN:?run through bench/run.sh}"
CORPUS="${DELMESH_CORPUS_DIR:?run through bench/run.sh}"
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
DATA="$(dirname "$BIN")/slivers-data"
BOUND=1.414
LIMIT=300  # seconds of wall time before a run counts as failed (exit 124)
LOW=20
HIGH=150
RUNS=3  # alternating runs of delmesh without and with the window; medians reported

need_comparison_tools
rm -rf "$DATA"
mkdir -p "$DATA"

INPUTS=(
  "$CORPUS/surface/cgal-sphere.off"
  "$CORPUS/surface/trimesh-busted.stl"
  "$CORPUS/surface/cgal-fandisk.off"
  "$CORPUS/surface/cgal-bear.off"
  "$CORPUS/surface/cgal-bunny00.off"
  "$ROOT/tests/data/mesh/tetgen_example.poly"
  "$CORPUS/step/pocc-io1-ug-214.stp"
  "$CORPUS/step/as-mechanism.stp"
)

# median <number...>: the median of the numbers.
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { printf "%.2f", (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
# quality <mesh file>: the key=value line of bench_mesh_quality with the window, or empty.
quality() { "$BIN/bench_mesh_quality" "$1" 1.415 "$LOW" "$HIGH" 2>/dev/null || true; }
# json_number <file> <key>: the first number after "key": in a --stats file.
json_number() { [ -f "$1" ] && tr -d '\n ' < "$1" | sed -n "s/.*\"$2\":\([0-9.eE+-]*\).*/\1/p" | head -1 || true; }
# elsewhere <stats.json>: the tets outside the window that touch no small input
# angle (quality.elsewhere.outside_dihedral_window) and the tets of that group.
elsewhere() {
  [ -f "$1" ] || return 0
  tr -d '\n ' < "$1" | sed -n 's/.*"elsewhere":{"tets":\([0-9]*\),[^}]*"outside_dihedral_window":\([0-9]*\).*/\2 of \1/p' | head -1
}

# row <input> <run> <cpu> <exit> <quality line> <added %> <elsewhere> <status>
row() {
  local q=$5
  if [ -z "$q" ]; then
    echo "| $1 | $2 | — | $3 | — | — | — | — | — | failed (exit $4) |"
    return
  fi
  awk -v i="$1" -v m="$2" -v cpu="$3" -v t="$(get "$q" tets)" -v dmin="$(get "$q" min_dihedral)" \
    -v dmax="$(get "$q" max_dihedral)" -v pct="$(get "$q" outside_pct)" -v add="$6" -v e="$7" -v s="$8" \
    'BEGIN { printf "| %s | %s | %d | %.2f | %s | %.2f | %.2f | %.3f | %s | %s |\n",
             i, m, t, cpu, add, dmin, dmax, pct, e, s }'
}

echo "## Sliver removal (dihedral window 20-150 degrees)"
echo
echo "delmesh at radius-edge bound $BOUND (\`delmesh mesh -pq$BOUND\`: TetGen's meaning, so the region"
echo "volume bounds of example.poly apply to neither mesher) without and with"
echo "\`--min-dihedral $LOW --max-dihedral $HIGH\` (dihedral-bound refinement, then flips and smoothing:"
echo "refiners/tet3d/sliver_improvement.h), on the \`.poly\` that \`delmesh import\` writes for the"
echo "input (for STEP files, after delmesh's own tessellation). TetGen 1.5 runs on the same \`.poly\`"
echo "with \`tetgen -pq$BOUND/15 -O -Q\` (radius-edge $BOUND, minimum dihedral 15 degrees, its default"
echo "optimization level 2: flips and smoothing). Gmsh 4.8 runs its HXT mesher with its tet"
echo "optimizer as a user would: \`gmsh -3 -algo hxt -optimize -nt 1\` on the surface file (a \`.geo\`"
echo "merging the STL as one discrete surface bounding one volume) or the STEP file (Gmsh's own"
echo "tessellation and sizing, so its counts differ by design; it has no \`.poly\` reader). CPU"
echo "seconds are user + system of the whole process (reading, meshing, writing; \`/usr/bin/time\`,"
echo "one core per run, 5-minute wall-time limit, shared 2-core machine; delmesh's two rows per input"
echo "give the median of $RUNS runs, without and with the window alternately); *+time* is the CPU time the window"
echo "adds to delmesh's run without it. Quality of every output is measured by the same code"
echo "(\`bench_mesh_quality\`): smallest and largest dihedral angle in degrees and the share of tets"
echo "with a dihedral angle outside [$LOW, $HIGH]. *Away from small angles* is delmesh's own count"
echo "(\`--stats\`: \`quality.elsewhere\`) of the tets outside the window among those touching no"
echo "small input angle (docs/MESHING.md, \"Small input angles\"); *status* is delmesh's."
echo
echo "| input | run | tets | CPU s | +time | min dihedral | max dihedral | outside [$LOW, $HIGH] (%) | away from small angles: outside of tets | status |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---|"
for src in "${INPUTS[@]}"; do
  name=$(basename "$src")
  stem="${name%.*}"
  poly="$DATA/$stem.poly"
  if [[ "$src" == *.poly ]]; then cp "$src" "$poly"; else "$BIN/delmesh" import "$src" -o "$poly" --quiet; fi

  # The two delmesh runs alternate RUNS times; each row gives its median CPU time, so the
  # window's added time is not one run's noise on a shared machine.
  plain_cpus=() window_cpus=()
  for ((run = 0; run < RUNS; run++)); do
    read -r cpu0 _ code0 < <(timed "$LIMIT" "$DATA/time.txt" "$BIN/delmesh" mesh -pq"$BOUND" "$poly" --quiet \
      --stats "$DATA/$stem.plain.json" -o "$DATA/$stem.plain.node")
    plain_cpus+=("$cpu0")
    read -r cpu kb code < <(timed "$LIMIT" "$DATA/time.txt" "$BIN/delmesh" mesh -pq"$BOUND" "$poly" --quiet \
      --min-dihedral "$LOW" --max-dihedral "$HIGH" --stats "$DATA/$stem.win.json" -o "$DATA/$stem.win.node")
    window_cpus+=("$cpu")
  done
  cpu0=$(median "${plain_cpus[@]}")
  cpu=$(median "${window_cpus[@]}")
  status=$(json_number "$DATA/$stem.plain.json" unmet_tets)
  row "$name" "delmesh -q$BOUND" "$cpu0" "$code0" "$(quality "$DATA/$stem.plain.ele")" "" "" "${status:+$status unmet}"

  added=$(awk -v a="$cpu0" -v b="$cpu" 'BEGIN { if (a > 0) printf "%+.0f%%", 100 * (b - a) / a; else print "—" }')
  status=$(json_number "$DATA/$stem.win.json" unmet_tets)
  row "$name" "delmesh -q$BOUND, window" "$cpu" "$code" "$(quality "$DATA/$stem.win.ele")" "$added" \
    "$(elsewhere "$DATA/$stem.win.json")" "${status:+$status unmet}"

  cp "$poly" "$DATA/tg_$stem.poly"
  read -r cpu kb code < <(timed "$LIMIT" "$DATA/time.txt" tetgen -pq"$BOUND"/15 -O -Q "$DATA/tg_$stem.poly")
  row "$name" "TetGen -pq$BOUND/15 -O" "$cpu" "$code" "$(quality "$DATA/tg_$stem.1.ele")" "" "" ""

  gmsh_input=""
  case "$src" in
    *.stl) gmsh_input="$src" ;;
    *.off)
      gmsh_input="$DATA/$stem.stl"
      off_to_stl "$src" "$gmsh_input"
      ;;
  esac
  if [ -n "$gmsh_input" ]; then
    printf 'Merge "%s";\nSurface Loop(1) = {1};\nVolume(1) = {1};\n' "$gmsh_input" > "$DATA/$stem.geo"
    read -r cpu kb code < <(timed "$LIMIT" "$DATA/time.txt" gmsh -3 -algo hxt -optimize -nt 1 "$DATA/$stem.geo" \
      -o "$DATA/$stem.hxt.mesh")
    row "$name" "Gmsh HXT (surface)" "$cpu" "$code" "$(quality "$DATA/$stem.hxt.mesh")" "" "" ""
  elif [[ "$src" == *.stp || "$src" == *.step ]]; then
    read -r cpu kb code < <(timed "$LIMIT" "$DATA/time.txt" gmsh -3 -algo hxt -optimize -nt 1 "$src" -o "$DATA/$stem.hxt.mesh")
    row "$name" "Gmsh HXT (STEP)" "$cpu" "$code" "$(quality "$DATA/$stem.hxt.mesh")" "" "" ""
  fi
done
echo
echo "Notes. The tets delmesh leaves outside the window touch small input angles (the"
echo "classification of docs/MESHING.md \"Small input angles\": segments meeting below 60 degrees, a"
echo "segment meeting a facet below 69.3 degrees, facets meeting below 90 degrees) unless the"
echo "*away from small angles* column says otherwise; TetGen and Gmsh report no such split, the"
echo "*outside* column measures all three the same way. A row \"failed (exit 124)\" is a run"
echo "stopped at the time limit; other exit codes are the tool's own failure."
