# The Debian package meshprojection_<version>_amd64.deb (CPack's DEB
# generator; Scripts/package.sh configures with MESHPROJECTION_DEB_PACKAGE=ON
# and CMAKE_INSTALL_PREFIX=/usr and runs cpack). Included by the top
# CMakeLists.txt after the install() rules of the filter and the plugin.
#
# What the package holds is what `cmake --install` installs, plus, from
# Packaging/debian: the copyright file and the changelog (both in
# /usr/share/doc/meshprojection, as Debian policy wants them), and the
# maintainer scripts that register the plugin with ParaView (postinst,
# postrm), byte-compile and clean the Python package (postinst, prerm), and
# the ldconfig trigger for the shared library (triggers).

set(mp_debian_dir "${PROJECT_SOURCE_DIR}/Packaging/debian")
set(mp_doc_dest "${CMAKE_INSTALL_DATADIR}/doc/meshprojection")

# ---- The changelog: Debian's format, its top entry this version ------------
# A native package (no Debian revision), so lintian wants changelog.gz.
file(STRINGS "${mp_debian_dir}/changelog" mp_changelog_top LIMIT_COUNT 1)
if (NOT mp_changelog_top MATCHES "^meshprojection \\(${PROJECT_VERSION}\\) ")
  message(FATAL_ERROR
    "Packaging/debian/changelog's top entry is `${mp_changelog_top}`, "
    "not version ${PROJECT_VERSION} (project(VERSION) in CMakeLists.txt): add an entry.")
endif ()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${mp_debian_dir}/changelog")
set(mp_changelog_gz "${CMAKE_BINARY_DIR}/Packaging/changelog.gz")
file(MAKE_DIRECTORY "${CMAKE_BINARY_DIR}/Packaging")
# -n: no name or time stamp in the gzip header (reproducible; lintian checks it).
execute_process(
  COMMAND gzip -9nc "${mp_debian_dir}/changelog"
  OUTPUT_FILE "${mp_changelog_gz}"
  RESULT_VARIABLE mp_gzip_result)
if (NOT mp_gzip_result EQUAL 0)
  message(FATAL_ERROR "gzip of Packaging/debian/changelog failed: ${mp_gzip_result}")
endif ()
install(FILES "${mp_debian_dir}/copyright" "${mp_changelog_gz}"
  DESTINATION "${mp_doc_dest}")

# ---- The documentation: README.md and docs/ side by side, links kept -------
install(FILES "${PROJECT_SOURCE_DIR}/README.md" DESTINATION "${mp_doc_dest}")
install(DIRECTORY "${PROJECT_SOURCE_DIR}/docs/"
  DESTINATION "${mp_doc_dest}/docs"
  FILES_MATCHING PATTERN "*.md" PATTERN "*.png")

# ---- The ParaView packages it was built against: Depends on those versions -
# A plugin loads only into the ParaView (and its bundled VTK) it was compiled
# against, so the package names their exact versions, read from dpkg at
# configure time; apt then refuses it next to another ParaView.
set(MESHPROJECTION_DEB_PARAVIEW_PACKAGES "paraview;python3-paraview" CACHE STRING
  "Debian packages of the ParaView (with its VTK) the build uses: the package Depends on their exact versions")
set(MESHPROJECTION_DEB_PARAVIEW_SUGGESTS "paraview-dev" CACHE STRING
  "Debian packages needed only to build C++ against MeshProjection: Suggests, exact versions")
function (mp_exact_versions out packages)
  set(relations)
  foreach (pkg IN LISTS packages)
    execute_process(
      COMMAND dpkg-query -W "-f=\${Version}" "${pkg}"
      OUTPUT_VARIABLE version
      RESULT_VARIABLE result
      ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
    if (NOT result EQUAL 0 OR version STREQUAL "")
      message(FATAL_ERROR "The Debian package `${pkg}` is not installed: the .deb names the version it is built against.")
    endif ()
    list(APPEND relations "${pkg} (= ${version})")
  endforeach ()
  list(JOIN relations ", " relations)
  set("${out}" "${relations}" PARENT_SCOPE)
endfunction ()
mp_exact_versions(mp_deb_depends "${MESHPROJECTION_DEB_PARAVIEW_PACKAGES}")
mp_exact_versions(mp_deb_suggests "${MESHPROJECTION_DEB_PARAVIEW_SUGGESTS}")

# ---- The maintainer scripts, with this build's installed paths --------------
set(mp_deb_plugin_xml "${CMAKE_INSTALL_FULL_LIBDIR}/paraview-5.11/plugins/MeshProjection.plugins.xml")
set(mp_deb_python_package "${CMAKE_INSTALL_PREFIX}/${mp_python_dest}/meshprojection")
foreach (script IN ITEMS postinst prerm postrm)
  configure_file("${mp_debian_dir}/${script}.in" "${CMAKE_BINARY_DIR}/Packaging/${script}" @ONLY)
endforeach ()

# ---- The Python the package's extension module is built for -----------------
# The wrapped module is for one minor version of CPython (Debian's python3,
# the one of python3-paraview).
execute_process(
  COMMAND "${Python3_EXECUTABLE}" -c "import sys; print('%d.%d' % sys.version_info[:2])"
  OUTPUT_VARIABLE mp_python_version
  RESULT_VARIABLE mp_python_result
  OUTPUT_STRIP_TRAILING_WHITESPACE)
if (NOT mp_python_result EQUAL 0)
  message(FATAL_ERROR "${Python3_EXECUTABLE} does not run: the package's Python dependency is unknown.")
endif ()
string(REGEX REPLACE "^([0-9]+)\\.([0-9]+)$" "\\2" mp_python_minor "${mp_python_version}")
math(EXPR mp_python_next_minor "${mp_python_minor} + 1")
set(mp_deb_python_depends "python3 (>= ${mp_python_version}~), python3 (<< 3.${mp_python_next_minor})")
string(APPEND mp_deb_depends ", ${mp_deb_python_depends}")

# ---- CPack --------------------------------------------------------------------
set(CPACK_GENERATOR "DEB")
set(CPACK_PACKAGE_NAME "meshprojection")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_VENDOR "The MeshProjection contributors")
set(CPACK_PACKAGE_CONTACT "MeshProjection maintainers <maintainers@users.noreply.h-seed-c214f040.example>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "mortar L2 projection between non-matching meshes for ParaView and VTK")
# The extended description; CPack puts the summary above it and writes an
# empty line as " .".
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
  "MeshProjection transfers the point and cell data of a source mesh onto a
target mesh by mortar L2 projection: integrals over the common part are
conserved and linear fields reproduced exactly. It works on curves, 2D
meshes, surfaces and volumes of any VTK dataset type, serial, threaded or
on MPI processes.

This package holds the ParaView plugin MeshProjection (the filter Mesh
Projection in the GUI, pvpython and pvbatch), the VTK module with its
Python package meshprojection, and the C++ headers and CMake package
(find_package of MeshProjection). It is built for
Debian's ParaView 5.11 and depends on that exact version.")
set(CPACK_DEBIAN_FILE_NAME "DEB-DEFAULT")  # meshprojection_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION "science")
set(CPACK_DEBIAN_PACKAGE_PRIORITY "optional")
set(CPACK_DEBIAN_PACKAGE_DEPENDS "${mp_deb_depends}")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "${mp_deb_suggests}")
# The libraries' own dependencies (libc, libstdc++, MPI, ...) from dpkg-shlibdeps.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The shlibs file of libMeshProjectionFilters.so.1, for packages that link it.
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS_POLICY ">=")
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
  "${CMAKE_BINARY_DIR}/Packaging/postinst"
  "${CMAKE_BINARY_DIR}/Packaging/prerm"
  "${CMAKE_BINARY_DIR}/Packaging/postrm"
  "${mp_debian_dir}/triggers")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_PACKAGE_DIRECTORY "${CMAKE_BINARY_DIR}")
include(CPack)
