#!/usr/bin/env bash
# The main job, from a fresh Debian 12 machine: install the dependencies,
# build, and project the sample source field onto the sample target mesh.
# For each sample pair NAME (lshape2d, lshape3d, sphere, trace) writes build/main/NAME-projected.vtu,
# build/main/NAME-intersections.vtp (2D, surfaces) or .vtu (3D) and build/main/NAME.png,
# and prints a summary.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
bash "$root/Scripts/install-deps.sh"
bash "$root/Scripts/build.sh"
timeout 600 xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython "$root/Scripts/project_sample.py" \
  --plugin "$build/lib/paraview-5.11/plugins/MeshProjection/MeshProjection.so" \
  --out-dir "$build/main" "$@"
