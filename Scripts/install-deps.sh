#!/usr/bin/env bash
# Install the Debian 12 (bookworm) packages needed to configure, build and
# test MeshProjection against Debian's ParaView 5.11.0 (bundled VTK 9.2):
# the VTK module + Python wrapping + ParaView plugin, and the C++/pvpython/GUI
# tests under Xvfb.
#
# Idempotent: when every package below is already installed, apt is not run.
#
# Why so many -dev packages: paraview-dev's CMake config
# (find_package(ParaView) without COMPONENTS) find_package()s the external
# dependency of *every* VTK/ParaView module as REQUIRED, but the paraview-dev
# package itself only depends on qttools5-dev-tools and libeigen3-dev.
#
# NEVER add libvtk9-dev or python3-vtk9: they conflict with python3-paraview.
set -euo pipefail

PACKAGES=(
  # --- toolchain ---
  cmake
  ninja-build
  g++

  # --- ParaView 5.11 + its bundled VTK 9.2 ---
  paraview
  paraview-dev
  python3-paraview
  openmpi-bin                # mpiexec: the MPI tests (vtkPMeshProjectionFilter) and bench_mpi.py

  # --- needed by paraview-dev's CMake config, not pulled in by it ---
  python3-matplotlib         # Benchmarks/plot_benchmark.py (docs/performance.md's plot)
  python3-scipy              # meshprojection.operator_matrices (scipy.sparse) and its tests
  python3-gmsh               # the surface tests' meshes (Gmsh's Python API)
  python3-dev                # FindPython3 Development.Module (VTK::Python); also builds the wrapping
  libopenmpi-dev             # FindMPI C (VTK::mpi); needed even with COMPONENTS
  qtbase5-dev                # Qt5 Core/Gui/Widgets/Network (ParaView pq* modules)
  libqt5opengl5-dev          # Qt5 OpenGL (VTK::GUISupportQt)
  libqt5svg5-dev             # Qt5 Svg (ParaView::pqComponents)
  qttools5-dev               # Qt5 Help (pq* modules; plugin XML documentation)
  qtxmlpatterns5-dev-tools   # `xmlpatterns`, run at BUILD time for the plugin's XML documentation
  libutfcpp-dev              # utf8cpp (VTK::utf8)
  libdouble-conversion-dev   # double-conversion (VTK::doubleconversion)
  libgl-dev                  # OpenGL headers/libGL (VTK::opengl)
  libglew-dev                # GLEW (VTK::glew, RenderingOpenGL2)
  libx11-dev                 # X11 (VTK::RenderingUI / RenderingOpenGL2)
  libgl2ps-dev               # GL2PS 1.4.2 (VTK::gl2ps)
  libtheora-dev              # THEORA (VTK::theora)
  libavformat-dev            # FFMPEG 5.1 avformat (VTK::IOFFMPEG)
  libavcodec-dev             # FFMPEG 5.1 avcodec
  libavutil-dev              # FFMPEG 5.1 avutil
  libswscale-dev             # FFMPEG 5.1 swscale
  libnetcdf-dev              # NetCDF (VTK::netcdf)
  libhdf5-dev                # HDF5 C;HL (VTK::hdf5); serial h5cc is what FindHDF5 picks
  libgdal-dev                # GDAL (VTK::IOGDAL)
  liblz4-dev                 # LZ4 (VTK::lz4)
  liblzma-dev                # LZMA (VTK::lzma)
  libtiff-dev                # TIFF (VTK::tiff)
  libpng-dev                 # PNG (VTK::png)
  libjpeg-dev                # JPEG (VTK::jpeg)
  zlib1g-dev                 # ZLIB (VTK::zlib)
  libxml2-dev                # LibXml2 (VTK::libxml2)
  libexpat1-dev              # EXPAT (VTK::expat)
  libfreetype-dev            # Freetype (VTK::freetype)
  libboost-dev               # Boost 1.74.0 EXACT, headers only
  libeigen3-dev              # Eigen3 (VTK::eigen); also used by the filter kernel

  # --- tests ---
  libgtest-dev               # GoogleTest for the kernel unit tests
  clang-format               # the C++ format check (Style.ClangFormat, .clang-format)
  clang                      # the libFuzzer harness (Testing/Fuzzing/Intersection) is built with clang++
  libclang-rt-14-dev         #   libFuzzer, AddressSanitizer and UBSan runtimes
  xvfb                       # X server for rendering tests (Debian's VTK/ParaView is GLX-only:
  xauth                      #   no EGL/OSMesa, pvbatch/pvpython need an X display); xvfb-run needs xauth
  libgl1-mesa-dri            # llvmpipe/swrast GL driver used under Xvfb

  # --- the Debian package (Scripts/package.sh, Scripts/test-package.sh) ---
  dpkg-dev                   # dpkg-shlibdeps (CPack's Depends) and dpkg-buildflags
  file                       # CPack's DEB generator finds the shared libraries with it
  lintian                    # the package's policy check (no errors)
)

if [[ ${EUID} -eq 0 ]]; then
  SUDO=()
elif command -v sudo >/dev/null 2>&1; then
  SUDO=(sudo)
else
  echo "install-deps.sh: must run as root or with sudo available" >&2
  exit 1
fi

missing_packages() {
  local pkg status
  for pkg in "${PACKAGES[@]}"; do
    status=$(dpkg-query -W -f='${db:Status-Status}' "${pkg}" 2>/dev/null || true)
    if [[ ${status} != installed ]]; then
      printf '%s\n' "${pkg}"
    fi
  done
}

mapfile -t MISSING < <(missing_packages)
if [[ ${#MISSING[@]} -eq 0 ]]; then
  echo "install-deps.sh: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

echo "install-deps.sh: installing ${#MISSING[@]} missing package(s): ${MISSING[*]}"
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" apt-get update

# Refuse to proceed if apt would remove anything (python3-paraview in particular).
removals=$("${SUDO[@]}" apt-get install -s -y --no-install-recommends "${MISSING[@]}" | grep '^Remv' || true)
if [[ -n ${removals} ]]; then
  echo "install-deps.sh: apt would remove packages; aborting:" >&2
  echo "${removals}" >&2
  exit 1
fi

# Only the missing ones: listing installed packages would also upgrade them.
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive \
  apt-get install -y --no-install-recommends "${MISSING[@]}"

mapfile -t STILL_MISSING < <(missing_packages)
if [[ ${#STILL_MISSING[@]} -ne 0 ]]; then
  echo "install-deps.sh: still not installed: ${STILL_MISSING[*]}" >&2
  exit 1
fi
echo "install-deps.sh: done"
