#!/usr/bin/env bash
# Build the Debian package meshprojection_<version>_amd64.deb from this clone:
# install the dependencies, a Release build of the filter, its Python
# package and the ParaView plugin (no tests, no benchmark) into
# ${PACKAGE_BUILD_DIR:-build-package} for the prefix /usr, then CPack's DEB
# generator (CMake/MeshProjectionPackaging.cmake). Prints the package's path
# last.
#
#   bash Scripts/package.sh
#   sudo apt install ./build-package/meshprojection_<version>_amd64.deb
#
# The package depends on the exact versions of Debian's paraview and
# python3-paraview installed here (a plugin loads only into the ParaView it
# was built against). ccache is used when it is installed.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PACKAGE_BUILD_DIR:-$root/build-package}"

bash "$root/Scripts/install-deps.sh" >&2

launcher=()
if command -v ccache >/dev/null 2>&1; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi

# Debian's hardening link flags (read-only relocations, immediate binding).
export LDFLAGS="${LDFLAGS:-$(DEB_BUILD_MAINT_OPTIONS=hardening=+all dpkg-buildflags --get LDFLAGS)}"
# Source and build paths (__FILE__ in VTK's error messages) written relative
# to the clone and the build directory: the package names neither.
prefix_maps="-ffile-prefix-map=${root}/= -ffile-prefix-map=${build}/="

cmake -S "$root" -B "$build" -G Ninja \
  -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_INSTALL_PREFIX=/usr \
  "-DCMAKE_C_FLAGS=${CFLAGS:-} ${prefix_maps}" \
  "-DCMAKE_CXX_FLAGS=${CXXFLAGS:-} ${prefix_maps}" \
  -DMESHPROJECTION_PYTHON_DESTINATION=lib/python3/dist-packages \
  -DMESHPROJECTION_BUILD_TESTING=OFF \
  -DMESHPROJECTION_BUILD_BENCHMARKS=OFF \
  -DMESHPROJECTION_DEB_PACKAGE=ON \
  -DParaView_DIR=/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11 \
  "${launcher[@]}" >&2
cmake --build "$build" --parallel "$(nproc)" >&2

# The package's name from CPack's own configuration, so that a stale .deb of
# another version in the build directory is never the one printed.
version=$(sed -n 's/^set(CPACK_PACKAGE_VERSION "\(.*\)")$/\1/p' "$build/CPackConfig.cmake")
arch=$(dpkg --print-architecture)
deb="$build/meshprojection_${version}_${arch}.deb"
rm -f "$deb"
(cd "$build" && cpack -G DEB --config CPackConfig.cmake) >&2
test -f "$deb"
echo "$deb"
