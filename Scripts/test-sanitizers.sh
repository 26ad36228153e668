#!/usr/bin/env bash
# The second tier of tests, after Scripts/test.sh (which installs the
# dependencies; this script builds what it needs): the filter's tests again
# with every mesh renumbered inside the filter; the kernel's threaded tests
# under ThreadSanitizer (Scripts/tsan-kernel.sh); then the C++ code built
# again with clang's AddressSanitizer and UBSan (Scripts/build-sanitized.sh),
# running the kernel and VTK C++ tests and the whole-filter fuzzer there,
# and the VTK C++ tests and the fuzzer's corpus once more with every mesh
# renumbered; last, the Debian package built, installed, checked and removed
# (Scripts/test-package.sh).
# Rendering tests run under one virtual X server started with -noreset (see
# Scripts/test.sh).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
bash "$root/Scripts/build.sh"
cd "$build"
# Every mesh renumbered along space inside the filter (the outputs must not
# change), without the kernel fuzzers and the install test.
MESHPROJECTION_RENUMBERING=always timeout 1800 xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
  ctest --output-on-failure --parallel 2 -LE Fuzz -E "^Example\.|^Kernel\."

# The kernel's concurrent code (renumbering's point sets, shared rows' sets, the
# search, assembly and solve in ranges) under ThreadSanitizer.
timeout 900 bash "$root/Scripts/tsan-kernel.sh"

bash "$root/Scripts/build-sanitized.sh"
cd "${SANITIZE_DIR:-$root/build-sanitized}"
ASAN_OPTIONS=abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  timeout 2400 xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure --parallel 2
# The renumbering's copies and maps under the sanitizers too (the corpus's
# meshes are below the size Automatic renumbers).
MESHPROJECTION_RENUMBERING=always ASAN_OPTIONS=abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  timeout 1200 xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
  ctest --output-on-failure --parallel 2 -R "FiltersCxx|Sanitize\.FilterCorpus"

# The Debian package: built, checked extracted into a throwaway root and
# installed with apt, then removed (Scripts/test-package.sh).
timeout 1800 bash "$root/Scripts/test-package.sh"
