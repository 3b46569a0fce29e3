#!/usr/bin/env bash
# Turns the Python wrapping of ParaView's VTK back on in the configuration
# shim that scripts/check-paraview-vtk.sh writes, so that MRGI's modules are
# wrapped for ParaView's Python too (the `mrgi` package that pvbatch imports;
# Documentation/ParaView-Python.md).
#
# Debian's paraview-dev declares VTK's Python targets
# (VTKPython-targets*.cmake: vtkmodules/*.so under /usr/lib/python3/dist-packages)
# and its module properties name class hierarchy files
# (/usr/lib/x86_64-linux-gnu/vtk/hierarchy/ParaView), but only python3-paraview
# ships those files, and installing it removes Debian's VTK 9.1. With the
# package unpacked (never installed) by scripts/fetch-paraview-python.sh, this
# writes copies of those two CMake files into the shim with the paths pointed
# into the unpacked tree, and makes the shim's vtk-config.cmake include them.
# Everything else still comes from the original directory.
#
# Usage: scripts/paraview-vtk-python-shim.sh SHIM_DIR VTK_DIR PARAVIEW_PYTHON_DIR
#   SHIM_DIR             the folder holding the shim's vtk-config.cmake
#   VTK_DIR              ParaView's VTK CMake folder (.../cmake/paraview-5.11/vtk)
#   PARAVIEW_PYTHON_DIR  where fetch-paraview-python.sh unpacked python3-paraview
set -euo pipefail
shim="${1:?usage: paraview-vtk-python-shim.sh SHIM_DIR VTK_DIR PARAVIEW_PYTHON_DIR}"
vtk_dir="${2:?usage: paraview-vtk-python-shim.sh SHIM_DIR VTK_DIR PARAVIEW_PYTHON_DIR}"
pv_python="$(cd "${3:?usage: paraview-vtk-python-shim.sh SHIM_DIR VTK_DIR PARAVIEW_PYTHON_DIR}" && pwd)"
site="$pv_python/usr/lib/python3/dist-packages"
hierarchy="$pv_python/usr/lib/x86_64-linux-gnu/vtk/hierarchy"
for f in "$shim/vtk-config.cmake" "$vtk_dir/VTKPython-targets.cmake" \
         "$vtk_dir/VTK-vtk-module-properties.cmake" "$site/vtkmodules/vtkCommonCore.so" \
         "$hierarchy/ParaView/vtkCommonCore-hierarchy.txt"; do
  if [ ! -f "$f" ]; then
    echo "paraview-vtk-python-shim: $f is missing (paraview-dev installed? python3-paraview unpacked?)" >&2
    exit 1
  fi
done

# VTK's Python targets: the prefix computed from the file's own place (five
# folders up from .../cmake/paraview-5.11/vtk) is taken from the original
# folder, and the vtkmodules paths point into the unpacked site directory.
sed -e "s|get_filename_component(_IMPORT_PREFIX \"\${CMAKE_CURRENT_LIST_FILE}\" PATH)|set(_IMPORT_PREFIX \"$vtk_dir\")|" \
    -e "s|\${_IMPORT_PREFIX}/lib/python3/dist-packages|$site|g" \
    "$vtk_dir/VTKPython-targets.cmake" > "$shim/VTKPython-targets.cmake"
for f in "$vtk_dir"/VTKPython-targets-*.cmake; do
  sed -e "s|\${_IMPORT_PREFIX}/lib/python3/dist-packages|$site|g" "$f" > "$shim/$(basename "$f")"
done
# The modules' hierarchy files (the wrappers read them for every dependency).
sed -e "s|\${CMAKE_CURRENT_LIST_DIR}|$vtk_dir|g" \
    -e "s|\${_vtk_module_import_prefix}/lib/x86_64-linux-gnu/vtk/hierarchy|$hierarchy|g" \
    "$vtk_dir/VTK-vtk-module-properties.cmake" > "$shim/VTK-vtk-module-properties.cmake"
# The shim's vtk-config.cmake: wrapping on, the two copies above included.
sed -i \
    -e 's|set("\${CMAKE_FIND_PACKAGE_NAME}_WRAP_PYTHON" "OFF")|set("${CMAKE_FIND_PACKAGE_NAME}_WRAP_PYTHON" "ON")|' \
    -e "s|$vtk_dir/VTKPython-targets.cmake|$shim/VTKPython-targets.cmake|" \
    -e "s|$vtk_dir/\${CMAKE_FIND_PACKAGE_NAME}-vtk-module-properties.cmake|$shim/VTK-vtk-module-properties.cmake|" \
    "$shim/vtk-config.cmake"
for include in "$shim/VTKPython-targets.cmake" "$shim/VTK-vtk-module-properties.cmake"; do
  if ! grep -qF "include(\"$include\")" "$shim/vtk-config.cmake"; then
    echo "paraview-vtk-python-shim: $shim/vtk-config.cmake does not include $include" >&2
    exit 1
  fi
done
echo "paraview-vtk-python-shim: ParaView's VTK Python wrapping on, from $pv_python"
