#!/usr/bin/env bash
# The Debian package's checks (the second tier: Scripts/test-sanitizers.sh
# runs it last). Builds the package (Scripts/package.sh), then:
#
# 1. extracted with `dpkg-deb -x` into a throwaway root, with environment
#    variables that point into that root only (PV_PLUGIN_CONFIG_FILE,
#    PYTHONPATH, CMAKE_PREFIX_PATH): pvpython and pvbatch on 2 MPI processes
#    load the plugin by name and project the sample pair, /usr/bin/python3
#    imports `meshprojection` and projects it, a separate CMake project
#    (Examples/Cxx) finds the package with find_package(MeshProjection),
#    builds and runs; no file of the package names the build tree;
# 2. installed with `apt-get install ./meshprojection_<version>_amd64.deb`:
#    the same checks with no environment variable at all, the GUI's plugin
#    list (Tools > Manage Plugins) and its Auto Load ticked there (the
#    plugin loaded at the next start), then `apt-get remove` leaves no file of
#    the package (dpkg -L before removal) and /usr/bin/paraview.conf as it
#    was; `apt-get purge` then forgets it.
#
# Needs root or sudo (apt). Prints one line per check and `N passed,
# M failed` last; exits 1 when a check failed. The package is purged on
# exit whatever happens, so that it never shadows a build tree's plugin.
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [[ ${EUID} -eq 0 ]]; then SUDO=(); else SUDO=(sudo); fi

work="$(mktemp -d /tmp/meshprojection-package.XXXXXX)"
installed_by_us=0
cleanup() {
  if [[ ${installed_by_us} -eq 1 ]]; then
    "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get purge -y meshprojection >/dev/null 2>&1 || true
  fi
  rm -rf "${work}"
}
trap cleanup EXIT

passed=0
failed=0
# check NAME COMMAND...: runs COMMAND, its output in the work folder; prints
# PASS or FAIL and, on failure, the output's end.
check() {
  local name="$1"
  shift
  local log="${work}/log-${name//[^A-Za-z0-9]/_}.txt"
  if "$@" >"${log}" 2>&1; then
    echo "PASS ${name}"
    grep -a "^projected" "${log}" | tail -n 1 | sed 's/^/    /'
    passed=$((passed + 1))
  else
    echo "FAIL ${name}"
    tail -n 40 "${log}" | sed 's/^/    /'
    failed=$((failed + 1))
  fi
}

# ---- The package -------------------------------------------------------------
if ! deb="$(bash "${root}/Scripts/package.sh" 2>"${work}/package.log" | tail -n 1)" || [[ ! -f ${deb} ]]; then
  tail -n 60 "${work}/package.log"
  echo "FAIL package (Scripts/package.sh)"
  echo "0 passed, 1 failed"
  exit 1
fi
echo "package: ${deb}"
build_dir="$(dirname "${deb}")"

# The checks' inputs, copied out of the clone: the sample pair and the C++
# example project.
mkdir -p "${work}/data" "${work}/home"
cp "${root}/Data/lshape_target.vtu" "${root}/Data/lshape_source.vtu" "${work}/data/"
cp -r "${root}/Examples/Cxx" "${work}/example"

# pvpython / pvbatch: the plugin by name, the filter on the sample pair.
# argv: the folder the plugin must come from.
cat >"${work}/check_paraview.py" <<EOF
import sys
from paraview.simple import *
from paraview import servermanager

LoadDistributedPlugin("MeshProjection", ns=globals())
info = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager().GetLocalInformation()
files = [info.GetPluginFileName(i) for i in range(info.GetNumberOfPlugins())
         if info.GetPluginName(i) == "MeshProjection"]
assert files and files[0].startswith(sys.argv[1]), files
target = XMLUnstructuredGridReader(FileName=["${work}/data/lshape_target.vtu"])
source = XMLUnstructuredGridReader(FileName=["${work}/data/lshape_source.vtu"])
projection = MeshProjection(Input=target, Source=source)
result = servermanager.Fetch(projection)
if servermanager.vtkProcessModule.GetProcessModule().GetPartitionId() == 0:
    smooth = result.GetPointData().GetArray("Smooth")
    assert result.GetNumberOfPoints() == 1270 and smooth is not None, result
    print("projected onto %d points, Smooth in %s, plugin %s" % (result.GetNumberOfPoints(), smooth.GetRange(), files[0]))
EOF

# VTK Python: the package's module, the filter on the sample pair.
cat >"${work}/check_python.py" <<EOF
import sys
import meshprojection
from meshprojection import vtkMeshProjectionFilter
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

assert meshprojection.__file__.startswith(sys.argv[1]), meshprojection.__file__
target, source = vtkXMLUnstructuredGridReader(), vtkXMLUnstructuredGridReader()
target.SetFileName("${work}/data/lshape_target.vtu")
source.SetFileName("${work}/data/lshape_source.vtu")
f = vtkMeshProjectionFilter()
f.SetInputConnection(target.GetOutputPort())
f.SetSourceConnection(source.GetOutputPort())
f.Update()
smooth = f.GetOutput().GetPointData().GetArray("Smooth")
assert f.GetOutput().GetNumberOfPoints() == 1270 and smooth is not None
print("projected onto 1270 points, Smooth in %s, module %s" % (smooth.GetRange(), meshprojection.__file__))
EOF

# The GUI: its plugin manager's list (what Tools > Manage Plugins shows).
cat >"${work}/check_gui.py" <<EOF
from paraview import servermanager
info = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager().GetLocalInformation()
names = [info.GetPluginName(i) for i in range(info.GetNumberOfPlugins())]
with open("${work}/gui-plugins.txt", "w") as out:
    out.write("\n".join(names) + "\n")
EOF

# The GUI's Auto Load: recorded Qt events that open Tools > Manage Plugins,
# load MeshProjection, tick its Auto Load (the sixth row under it) and quit
# with File > Exit (the settings are saved); the next start must have it
# loaded before any script runs.
cat >"${work}/autoload.xml" <<'EOF_XML'
<?xml version="1.0" ?>
<pqevents>
  <pqevent object="pqClientMainWindow/menubar" command="activate" arguments="menuTools" />
  <pqevent object="pqClientMainWindow/menubar/menuTools" command="activate" arguments="actionManage_Plugins" />
  <pqevent object="pqClientMainWindow/PluginManagerDialog/splitter/localGroup/localPlugins" command="setCurrent" arguments="MeshProjection" />
  <pqevent object="pqClientMainWindow/PluginManagerDialog/splitter/localGroup/loadSelected_Local" command="activate" arguments="" />
  <pqevent object="pqClientMainWindow/PluginManagerDialog/splitter/localGroup/localPlugins" command="expand" arguments="1.0" />
  <pqevent object="pqClientMainWindow/PluginManagerDialog/splitter/localGroup/localPlugins" command="setCheckState" arguments="1.0.5.1,2" />
  <pqevent object="pqClientMainWindow/PluginManagerDialog/buttonBox/1QPushButton0" command="activate" arguments="" />
  <pqevent object="pqClientMainWindow/menubar" command="activate" arguments="menu_File" />
  <pqevent object="pqClientMainWindow/menubar/menu_File" command="activate" arguments="actionFileExit" />
</pqevents>
EOF_XML
echo "print('no-op')" >"${work}/noop.py"
cat >"${work}/check_autoload.py" <<EOF
from paraview import servermanager
info = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager().GetLocalInformation()
with open("${work}/gui-autoload.txt", "w") as out:
    for i in range(info.GetNumberOfPlugins()):
        out.write("%s loaded=%d auto_load=%d\n" % (info.GetPluginName(i), info.GetPluginLoaded(i), info.GetAutoLoad(i)))
EOF

# Run a command with only the given environment (and a fresh HOME, so that
# no ParaView settings of the user's take part).
clean_env() {
  env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME="${work}/home" "$@"
}

# The four checks of the issue against a prefix. $1: the label; $2: the
# plugin folder the plugin must come from; $3: the folder of the Python
# package; then NAME=VALUE environment settings.
run_checks() {
  local label="$1" plugin_dir="$2" python_dir="$3"
  shift 3
  local env_vars=("$@")
  check "${label}: pvpython LoadDistributedPlugin" \
    clean_env "${env_vars[@]}" timeout 300 xvfb-run -a -s "-screen 0 1280x1024x24" \
      pvpython "${work}/check_paraview.py" "${plugin_dir}"
  check "${label}: mpiexec -n 2 pvbatch --mpi" \
    clean_env "${env_vars[@]}" timeout 300 xvfb-run -a -s "-screen 0 1280x1024x24" \
      mpiexec --allow-run-as-root --oversubscribe -n 2 pvbatch --mpi "${work}/check_paraview.py" "${plugin_dir}"
  check "${label}: python3 imports meshprojection" \
    clean_env "${env_vars[@]}" timeout 300 /usr/bin/python3 "${work}/check_python.py" "${python_dir}"
  rm -rf "${work}/example-build"
  check "${label}: find_package(MeshProjection), build and run" \
    clean_env "${env_vars[@]}" timeout 600 bash -c '
      set -e
      cmake -S "$1/example" -B "$1/example-build" -G Ninja -DCMAKE_BUILD_TYPE=Release
      cmake --build "$1/example-build"
      "$1/example-build/ProjectMeshes" "$1/data/lshape_target.vtu" "$1/data/lshape_source.vtu" "$1/example-projected.vtu" \
        | tee /dev/stderr | grep -q "projected 5 point arrays onto 1270 points"' _ "${work}"
}

# ---- 1. Extracted into a throwaway root --------------------------------------
fakeroot="${work}/root"
dpkg-deb -x "${deb}" "${fakeroot}"
libdir="${fakeroot}/usr/lib/x86_64-linux-gnu"
run_checks "extracted" "${libdir}/paraview-5.11/plugins/MeshProjection" "${fakeroot}/usr/lib/python3/dist-packages" \
  "PV_PLUGIN_CONFIG_FILE=${libdir}/paraview-5.11/plugins/MeshProjection.plugins.xml" \
  "PYTHONPATH=${fakeroot}/usr/lib/python3/dist-packages" \
  "CMAKE_PREFIX_PATH=${fakeroot}/usr"
# No file (CMake package, plugin XML, Python, libraries) names the build
# tree or the clone, and the libraries find each other through \$ORIGIN only.
check "extracted: no path into the build tree or the clone" bash -c '
  if grep -rlF -e "$1" -e "$2" "$3"; then exit 1; fi
  bad=$(find "$3" -name "*.so*" -type f -exec readelf -d {} + \
        | sed -n "s/.*R\(UN\)\?PATH.*\[\(.*\)\]/\2/p" | tr ":" "\n" | grep -v "^\\\$ORIGIN")
  [[ -z $bad ]] || { echo "run paths: $bad"; exit 1; }' _ "${build_dir}" "${root}" "${fakeroot}"

# lintian: no errors (the warnings kept are listed in docs/building-against-paraview.md).
if command -v lintian >/dev/null 2>&1; then
  check "lintian: no errors" lintian --fail-on error "${deb}"
fi

# ---- 2. Installed with apt, then removed ---------------------------------------
conf=/usr/bin/paraview.conf
conf_before="$(cat "${conf}" 2>/dev/null || echo "(no file)")"
if "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y "${deb}" >"${work}/apt-install.log" 2>&1; then
  installed_by_us=1
  echo "PASS apt-get install ${deb##*/}"
  passed=$((passed + 1))
  libdir=/usr/lib/x86_64-linux-gnu
  run_checks "installed" "${libdir}/paraview-5.11/plugins/MeshProjection" /usr/lib/python3/dist-packages
  rm -f "${work}/gui-plugins.txt"
  check "installed: the GUI lists MeshProjection (Tools > Manage Plugins)" \
    bash -c 'clean_env() { env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME="$1/home" "${@:2}"; }
      clean_env "$1" timeout 300 xvfb-run -a -s "-screen 0 1280x1024x24" paraview --script="$1/check_gui.py" --exit
      cat "$1/gui-plugins.txt"; grep -qx MeshProjection "$1/gui-plugins.txt"' _ "${work}"
  rm -rf "${work}/gui-autoload.txt" "${work}/home" && mkdir "${work}/home"
  check "installed: GUI Auto Load ticked in Manage Plugins loads it at the next start" \
    bash -c 'clean_env() { env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME="$1/home" "${@:2}"; }
      clean_env "$1" timeout 300 xvfb-run -a -s "-screen 0 1280x1024x24" \
        paraview --script="$1/noop.py" --test-script="$1/autoload.xml"
      clean_env "$1" timeout 300 xvfb-run -a -s "-screen 0 1280x1024x24" \
        paraview --script="$1/check_autoload.py" --exit
      cat "$1/gui-autoload.txt"; grep -qx "MeshProjection loaded=1 auto_load=1" "$1/gui-autoload.txt"' _ "${work}"
  dpkg -L meshprojection >"${work}/files.txt"
  if "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get remove -y meshprojection >"${work}/apt-remove.log" 2>&1; then
    installed_by_us=0
  fi
  # Every file of the package gone; a folder left only when another package owns it.
  check "removed: no file of the package left" bash -c '
    left=0
    while read -r path; do
      if [[ -d $path && ! -L $path ]]; then
        dpkg -S "$path" >/dev/null 2>&1 || { echo "left: $path/"; left=1; }
      elif [[ -e $path || -L $path ]]; then
        echo "left: $path"; left=1
      fi
    done <"$1"
    exit $left' _ "${work}/files.txt"
  check "removed: /usr/bin/paraview.conf as before" \
    bash -c '[[ "$(cat "$1" 2>/dev/null || echo "(no file)")" == "$2" ]]' _ "${conf}" "${conf_before}"
  # dpkg keeps the removed package's postrm (state rc) until it is purged.
  check "purged: dpkg no longer knows meshprojection" bash -c '
    "$@" env DEBIAN_FRONTEND=noninteractive apt-get purge -y meshprojection
    ! dpkg -s meshprojection' _ "${SUDO[@]}"
else
  tail -n 40 "${work}/apt-install.log"
  echo "FAIL apt-get install ${deb##*/}"
  failed=$((failed + 1))
fi

echo "${passed} passed, ${failed} failed"
[[ ${failed} -eq 0 ]]
