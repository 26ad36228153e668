#!/usr/bin/env bash
# The second build of Scripts/test-sanitizers.sh: the kernel, the VTK
# module, their C++ tests and the whole-filter fuzzer compiled by clang with
# AddressSanitizer, UndefinedBehaviorSanitizer and libFuzzer's coverage, into
# ${SANITIZE_DIR:-build-sanitized}. No Python wrapping, no plugin.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SANITIZE_DIR:-$root/build-sanitized}"
cmake -S "$root" -B "$build" -G Ninja \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g -DNDEBUG" \
  -DMESHPROJECTION_SANITIZE=ON \
  -DMESHPROJECTION_WRAP_PYTHON=OFF \
  -DMESHPROJECTION_BUILD_PLUGIN=OFF \
  -DParaView_DIR=/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11
cmake --build "$build" --parallel "$(nproc)"
