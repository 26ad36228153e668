#!/usr/bin/env bash
# The kernel's concurrent code under ThreadSanitizer: the kernel and the unit
# tests that run it in several tasks on std::threads (the renumbering's
# point sets and sort, the neighbours, the search and assembly in ranges, the
# shared rows' bit sets, the solve) compiled by clang with -fsanitize=thread
# into ${TSAN_DIR:-build-tsan}, then run. A data race fails the run.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${TSAN_DIR:-$root/build-tsan}"
mkdir -p "$out"
flags=(-std=c++17 -O1 -g -fsanitize=thread -I"$root/Filters/Kernel" -I"$root/Testing/Support/Cxx"
  -I/usr/include/eigen3)
# Every room of the kernel (its Testing folder holds the tests: only the
# threaded ones below).
sources=()
for s in "$root"/Filters/Kernel/*/*.cxx; do
  [[ $s == "$root"/Filters/Kernel/Testing/* ]] || sources+=("$s")
done
sources+=("$root"/Filters/Kernel/Testing/TestSpatialOrder.cxx "$root"/Filters/Kernel/Testing/TestCellNeighbors.cxx
  "$root"/Filters/Kernel/Testing/TestSpaces.cxx "$root"/Filters/Kernel/Testing/TestMortarProjector.cxx
  "$root"/Filters/Kernel/Testing/TestWorkerPool.cxx)
objects=()
for s in "${sources[@]}"; do
  objects+=("$out/$(basename "${s%.cxx}").o")
done
# One object per source, on every core.
printf '%s\n' "${sources[@]}" | xargs -P "$(nproc)" -I{} sh -c \
  'clang++ "$@" -c "{}" -o "'"$out"'/$(basename "{}" .cxx).o"' sh "${flags[@]}"
clang++ -fsanitize=thread "${objects[@]}" -lgtest -lgtest_main -lpthread -o "$out/ThreadedKernelTests"
TSAN_OPTIONS="halt_on_error=1" "$out/ThreadedKernelTests"
