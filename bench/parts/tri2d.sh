#!/usr/bin/env bash
# Benchmark section: the 2D kernels through the library API (no file output).
# Delaunay of uniform random points (bench_delaunay2d) and Delaunay refinement of
# Triangle's A.poly (corpus drufat-a.poly) with a maximum area of 5e-8 (bench_refine2d).
set -euo pipefail
bin="${DELMESH_BENCH_BIN:?run through bench/run.sh}"
corpus="${DELMESH_CORPUS_DIR:?}"
echo "## 2D Delaunay and refinement kernels (library API)"
echo
echo "Delaunay triangulation of uniform random points in the unit square (BRIO + Hilbert"
echo "order, Bowyer-Watson insertion with exact predicates). Times exclude generating the"
echo "points; CPU time is the steadier figure on a shared machine."
echo
# One process per run, so that each peak resident size is that run's own.
"$bin/bench_delaunay2d" 100000
"$bin/bench_delaunay2d" 1000000 | tail -n +3
echo
echo "Refinement of A.poly (\`drufat-a.poly\`) with a maximum triangle area of 5e-8, at"
echo "three minimum angles (Ruppert with concentric shells and the Quitter; times include"
echo "the constrained Delaunay triangulation and building the output mesh, not file I/O)."
echo "Bytes per triangle: peak resident memory growth of the run divided by the triangles."
echo
"$bin/bench_refine2d" "$corpus/poly2d/drufat-a.poly" 5e-8 20
for angle in 30 33; do
  "$bin/bench_refine2d" "$corpus/poly2d/drufat-a.poly" 5e-8 "$angle" | tail -n +3
done
echo
echo "The same input without an area bound (quality only):"
echo
"$bin/bench_refine2d" "$corpus/poly2d/drufat-a.poly" 0 20 30 33 40
