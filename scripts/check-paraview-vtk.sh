#!/usr/bin/env bash
# Configure and build the module, its C core and mrgi-render against ParaView
# 5.11's VTK 9.2 (package paraview-dev), so that compatibility with the VTK
# that ParaView users run cannot rot. Run by ctest as compat.ParaViewVTK.
# Usage: scripts/check-paraview-vtk.sh BUILD_DIR
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:?usage: check-paraview-vtk.sh BUILD_DIR}"
vtk_dir="${MRGI_PARAVIEW_VTK_DIR:-/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11/vtk}"
if [ ! -f "$vtk_dir/vtk-config.cmake" ]; then
  echo "check-paraview-vtk: no ParaView VTK at $vtk_dir (install paraview-dev)" >&2
  exit 1
fi

# Debian's paraview-dev declares Python targets (vtkmodules/*.so) whose files
# no Debian package installs, and its vtk-config.cmake aborts on them. MRGI's
# C++ build needs none of them: configure through a copy of vtk-config.cmake
# with ParaView's Python wrapping off, which includes everything else from the
# original directory (so imported paths stay right).
shim="$build/paraview-vtk-config"
mkdir -p "$shim"
sed -e "s|\${CMAKE_CURRENT_LIST_DIR}|$vtk_dir|g" \
    -e 's|set("\${CMAKE_FIND_PACKAGE_NAME}_WRAP_PYTHON" "ON")|set("${CMAKE_FIND_PACKAGE_NAME}_WRAP_PYTHON" "OFF")|' \
    "$vtk_dir/vtk-config.cmake" > "$shim/vtk-config.cmake"
cp "$vtk_dir/vtk-config-version.cmake" "$shim/"
# MRGI's Python package for ParaView's Python (pvbatch): the wrapping of
# ParaView's VTK back on, its files taken from python3-paraview, unpacked
# (never installed) into the build tree.
bash "$root/scripts/fetch-paraview-python.sh" "$build/paraview-python"
bash "$root/scripts/paraview-vtk-python-shim.sh" "$shim" "$vtk_dir" "$build/paraview-python"

# The same for ParaView's own config (the plugin, Module/ParaView): it finds
# VTK through the shim above, leaves ParaView's Python targets out (their
# files are python3-paraview's, which must not be installed: it removes
# Debian's VTK 9.1), and skips ParaViewTools-targets.cmake, which names
# pvpython, also python3-paraview's.
pv_dir="$(dirname "$vtk_dir")"
pv_shim="$build/paraview-config"
mkdir -p "$pv_shim"
sed -e "s|\${CMAKE_CURRENT_LIST_DIR}/vtk\"|$shim\"|g" \
    -e "s|\${CMAKE_CURRENT_LIST_DIR}|$pv_dir|g" \
    -e 's|set(PARAVIEW_USE_PYTHON "ON")|set(PARAVIEW_USE_PYTHON "OFF")|' \
    -e 's|^if (ON) # PARAVIEW_USE_PYTHON|if (OFF) # PARAVIEW_USE_PYTHON (MRGI shim)|' \
    -e '/ParaViewTools-targets.cmake/d' \
    "$pv_dir/paraview-config.cmake" > "$pv_shim/paraview-config.cmake"
cp "$pv_dir/paraview-config-version.cmake" "$pv_shim/"

# The plugin's wrapping needs ParaView's class hierarchy files, which only
# python3-paraview ships: unpacked above.
pv_python="$build/paraview-python"

if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DVTK_DIR="$shim" -DParaView_DIR="$pv_shim" -DMRGI_BUILD_PARAVIEW_PLUGIN=ON -DMRGI_WARNINGS_AS_ERRORS=ON -DMRGI_ENABLE_PCL=OFF \
    -DPython3_EXECUTABLE=/usr/bin/python3 \
    -DMRGI_PARAVIEW_HIERARCHY_DIR="$pv_python/usr/lib/x86_64-linux-gnu/vtk/hierarchy/ParaView" \
    -DBUILD_TESTING=OFF -DMRGI_WRAP_PYTHON=ON -DMRGI_BUILD_EXAMPLES=OFF
elif grep -q '^MRGI_WRAP_PYTHON:BOOL=OFF$' "$build/CMakeCache.txt"; then
  # A tree configured before this script wrapped for Python.
  cmake -S "$root" -B "$build" -DMRGI_WRAP_PYTHON=ON -DPython3_EXECUTABLE=/usr/bin/python3
fi
cmake --build "$build" --parallel "${MRGI_JOBS:-2}"
# The build must really have used VTK 9.2: its libraries carry the pv5.11 suffix.
# (grep reads all of ldd's output: `grep -q` stops early, ldd then dies of
# SIGPIPE, and pipefail turned that into a false failure.)
if ! ldd "$build/bin/mrgi-render" | grep "pv5.11" > /dev/null; then
  echo "check-paraview-vtk: mrgi-render did not link ParaView's VTK" >&2
  exit 1
fi
echo "check-paraview-vtk: module, core and mrgi-render built against ParaView's VTK"
# And it renders headless with VTK 9.2 as well.
out="$build/paraview-vtk-cornell.png"
rm -f "$out"
"$build/bin/mrgi-render" cornell -o "$out" --size 64x64 -q
test -s "$out"
echo "check-paraview-vtk: mrgi-render (VTK 9.2) rendered $out"
