#!/usr/bin/env bash
# Benchmark section "STEP import": import_step (read with XDE, heal, sew, glue, tessellate,
# refine the face triangulations, build the PLC) on every STEP file of the corpus, largest
# first, one process per file so that the peak resident memory is the file's own
# (getrusage in bench_step_import). Default options: chordal deflection 1/1000 of the
# bounding-box diagonal, angular deflection 20 degrees, surface refinement to 20 degrees.
# Prints a markdown section on stdout. Environment (set by bench/run.sh): DELMESH_BENCH_BIN,
# DELMESH_CORPUS_DIR.
set -euo pipefail

bin="${DELMESH_BENCH_BIN:?run through bench/run.sh}"
corpus="${DELMESH_CORPUS_DIR:?run through bench/run.sh}"

echo "## STEP import"
echo
echo "\`import_step\` (importers/step/) on every STEP file of the corpus, largest first; one"
echo "process per file (\`build-bench/bin/bench_step_import FILE\`), Release build, one core."
echo "Times are wall-clock and CPU (user + system) seconds for the whole import (the machine is"
echo "shared, so CPU time is the steadier figure); RSS is the process peak (OCCT's libraries"
echo "account for about 45 MB of it). *facets* counts all facets, *polygons* the planar CAD faces"
echo "written as one polygonal facet; *markers* distinct CAD face ids, *regions* region points"
echo "(pieces of overlapping solids each get one). Angles: smallest angle of a triangular facet"
echo "(curved and tilted planar faces, after the surface refinement), the number of triangular"
echo "facets below 10 degrees, and the smallest corner of a polygonal facet (a CAD feature, not"
echo "a tessellation artefact). No reference tool runs beside it (Gmsh is not installed)."
echo
echo "| file | size | wall s | CPU s | peak RSS MB | vertices | facets | polygons | markers | regions | min triangle angle | triangles < 10° | min polygon corner |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
while read -r size file; do
  row="$("$bin/bench_step_import" "$file" || true)"
  kb=$(( size / 1024 ))
  # Insert the size column after the file name.
  echo "$row" | sed -e "s/^| \([^|]*\) |/| \1 | ${kb} KB |/" -e "s|$corpus/||g"
done < <(find "$corpus/step" -maxdepth 1 -type f \( -name '*.stp' -o -name '*.step' \) -printf '%s %p\n' | sort -rn)
echo
echo "Surface refinement (importers/step/surface_refinement.h) replaces BRepMesh's triangles on"
echo "curved and tilted planar faces by a Delaunay refinement in each face's scaled parameter"
echo "plane, bounded at 20 degrees, with a point budget of twice the tessellation's vertices"
echo "plus 2000; it is undone for the whole model when it would fold a face or lower the"
echo "smallest angle (the rows whose triangle counts equal BRepMesh's). Angles left below the"
echo "bound sit at CAD corners where two edges meet at a small angle, at tiny CAD edges (below"
echo "1/20 of the chordal deflection), or where the budget ran out (long thin periodic faces)."
