#!/usr/bin/env bash
# Shared by bench/parts/*.sh: off_to_stl IN.off OUT.stl writes a triangle OFF surface as
# ASCII STL, for Gmsh (which reads no OFF).
off_to_stl() {
  awk 'NR == 1 { next } NF == 0 || /^#/ { next }
       !n { nv = $1; nf = $2; n = 1; next }
       k < nv { x[k] = $1; y[k] = $2; z[k] = $3; k++; next }
       $1 == 3 { printf "facet normal 0 0 0\nouter loop\nvertex %s %s %s\nvertex %s %s %s\nvertex %s %s %s\nendloop\nendfacet\n",
                 x[$2], y[$2], z[$2], x[$3], y[$3], z[$3], x[$4], y[$4], z[$4] }
       BEGIN { k = 0; print "solid s" } END { print "endsolid s" }' "$1" > "$2"
}
