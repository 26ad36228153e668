#!/usr/bin/env bash
# Install the dependencies, build, and run every test (kernel, VTK C++ with
# images, VTK Python, pvpython, ParaView GUI, installed C++ example).
# Rendering tests run under one virtual X server.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
bash "$root/Scripts/install-deps.sh"
bash "$root/Scripts/build.sh"
cd "$build"
timeout 3000 xvfb-run -a ctest --output-on-failure --parallel 2
