#!/usr/bin/env bash
# Install the dependencies, build, and run every test (kernel, VTK C++ with
# images, VTK Python, pvpython, MPI, ParaView GUI, the fuzzers' corpora and
# a fixed exploration, installed C++ example). The second tier, the same
# code renumbered, under ThreadSanitizer and under AddressSanitizer/UBSan,
# is Scripts/test-sanitizers.sh (CI, .ci/run, runs both).
# Rendering tests run under one virtual X server, started with -noreset: by
# default an X server resets when its last client disconnects, and a client
# connecting during that reset is refused ("bad X server connection"), which
# would fail a test at random when two rendering tests run in parallel.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
bash "$root/Scripts/install-deps.sh"
bash "$root/Scripts/build.sh"
cd "$build"
timeout 3000 xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure --parallel 2
