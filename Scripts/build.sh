#!/usr/bin/env bash
# Configure and build MeshProjection against Debian's ParaView 5.11 into
# ${BUILD_DIR:-build}. Used by Scripts/main.sh and Scripts/test.sh.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -G Ninja \
  -DCMAKE_BUILD_TYPE=Release \
  -DParaView_DIR=/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11
cmake --build "$build" --parallel "$(nproc)"
