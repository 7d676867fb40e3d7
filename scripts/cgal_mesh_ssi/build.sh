#!/bin/sh
# Build cgal_ssi.cpp (CGAL's exact mesh intersection, timed) outside the repository.
#   sh scripts/cgal_mesh_ssi/build.sh [OUTPUT]     (default /tmp/cgal_ssi)
# Needs CGAL 5.x headers, Boost, GMP and MPFR: on Debian/Ubuntu
#   apt-get install -y libcgal-dev cmake g++
set -eu
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-/tmp/cgal_ssi}
if [ ! -f /usr/include/CGAL/version.h ] && [ ! -f /usr/local/include/CGAL/version.h ]; then
  echo "build.sh: CGAL headers not found: apt-get install -y libcgal-dev cmake g++" >&2
  exit 1
fi
g++ -O2 -DNDEBUG -std=c++17 -o "$out" "$here/cgal_ssi.cpp" -lgmp -lmpfr
echo "$out"
