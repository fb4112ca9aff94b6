#!/usr/bin/env bash
# Benchmark section "import": import + exact validation of the largest corpus inputs
# (surface meshes; STEP files when delmesh is built with OpenCASCADE). One process per
# file so that the peak RSS column is that file's own.
set -euo pipefail
bin="$DELMESH_BENCH_BIN/bench_import"
corpus="$DELMESH_CORPUS_DIR"
echo "## Import"
echo
echo "\`bench_import FILE\`: \`import_file()\` with default options (surface meshes: exact weld,"
echo "repairs, orientation, exact self-intersection check, shells, coplanar merge), then"
echo "\`validate_plc()\` on the result; wall-clock seconds on one core and the process's peak"
echo "resident memory. Refused inputs show the time to refuse them."
echo
files=()
for f in cgal-bunny00.off cgal-armadillo.off cgal-bear.off occt-tr12j.stl cgal-u-arch.off \
         occt-motor.stl occt-sh2.stl occt-propeller.stl trimesh-tray-bottom.stl; do
  files+=("$corpus/surface/$f")
done
if "$bin" --has-cad; then
  for f in trimesh-box-sides.step occt-linkrods.step gmsh-fusee-rocket.stp as-capot-40mm.stp; do
    files+=("$corpus/step/$f")
  done
else
  echo "(This build has no OpenCASCADE: STEP files are not part of this run.)"
  echo
fi
first=1
for f in "${files[@]}"; do
  if [ $first -eq 1 ]; then
    "$bin" "$f" || true
    first=0
  else
    "$bin" "$f" | tail -n +3 || true
  fi
done
