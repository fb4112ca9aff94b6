#!/usr/bin/env bash
# Shared by the section scripts that run delmesh beside other meshers on the same inputs
# (bench/parts/mesh3d.sh, slivers.sh): installing the other meshers, timing a run, reading
# bench_mesh_quality's key=value line, and writing an OFF surface as STL for Gmsh.

# need_comparison_tools: installs TetGen, Gmsh and GNU time from Debian's packages where
# they are missing.
need_comparison_tools() {
  if ! command -v tetgen >/dev/null; then apt-get install -y tetgen >&2; fi
  if ! command -v gmsh >/dev/null; then DEBIAN_FRONTEND=noninteractive apt-get install -y gmsh >&2; fi
  if [ ! -x /usr/bin/time ]; then apt-get install -y time >&2; fi
}

# timed <limit seconds> <timefile> <command...>: runs the command under GNU time, stopped
# after the limit of wall time; prints "cpu_seconds kbytes exit_code" (cpu = user + system).
timed() {
  local limit=$1 out=$2
  shift 2
  local code=0
  /usr/bin/time -f "%U %S %M" -o "$out" timeout "$limit" "$@" >/dev/null 2>&1 || code=$?
  awk -v c="$code" 'END { printf "%.2f %s %s\n", $1 + $2, $3, c }' "$out"
}

# get <key=value line> <key>: the value of one key.
get() { echo "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"; }

# off_to_stl IN.off OUT.stl: writes a triangle OFF surface as ASCII STL (Gmsh reads no OFF).
off_to_stl() {
  awk 'NR == 1 { next } NF == 0 || /^#/ { next }
       !n { nv = $1; nf = $2; n = 1; next }
       k < nv { x[k] = $1; y[k] = $2; z[k] = $3; k++; next }
       $1 == 3 { printf "facet normal 0 0 0\nouter loop\nvertex %s %s %s\nvertex %s %s %s\nvertex %s %s %s\nendloop\nendfacet\n",
                 x[$2], y[$2], z[$2], x[$3], y[$3], z[$3], x[$4], y[$4], z[$4] }
       BEGIN { k = 0; print "solid s" } END { print "endsolid s" }' "$1" > "$2"
}
