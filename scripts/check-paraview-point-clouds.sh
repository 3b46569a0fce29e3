#!/usr/bin/env bash
# Point clouds in ParaView: pvbatch with no X server opens a LAS file the
# test writes (File > Open's reader choice), applies "MRGI Point Cloud
# Normals" and "MRGI Surfels", checks the surfels' layout and renders them
# in an MRGI Render View with GI off and on (Module/ParaView/Testing/
# pvbatch_point_clouds.py asserts coverage, no black pixel in the cloud, the
# indirect light); the same for the shared LAS tile when present; then a
# truncated LAS file, whose error must name the file, and bad filter
# settings, each reported once by the filter.
# Run by ctest as paraview.PointClouds after compat.ParaViewVTK built the
# ParaView tree.
# Usage: scripts/check-paraview-point-clouds.sh PARAVIEW_BUILD_DIR [SHARED_DATA_DIR]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
usage="usage: check-paraview-point-clouds.sh PARAVIEW_BUILD_DIR [SHARED_DATA_DIR]"
build="$(cd "${1:?$usage}" && pwd)"
shared="${2:-$root/../shared/data}"
script="$root/Module/ParaView/Testing/pvbatch_point_clouds.py"
plugin="$build/lib/paraview-5.11/plugins/MRGIRenderView/MRGIRenderView.so"
fail() { echo "check-paraview-point-clouds: FAIL: $*" >&2; exit 1; }
command -v pvbatch > /dev/null || fail "pvbatch not found (install paraview: scripts/install-deps.sh)"
[ -f "$plugin" ] || fail "no plugin at $plugin (build the ParaView tree: scripts/check-paraview-vtk.sh)"
work="$build/point-cloud-check"
rm -rf "$work"
mkdir -p "$work/valley" "$work/tile" "$work/bad"
export PYTHONPATH="$build/paraview-python/usr/lib/python3/dist-packages"
log="$work/pvbatch.log"
pvbatch_headless() {
  env -u DISPLAY timeout 300 pvbatch "$@" > "$log" 2>&1 || { cat "$log" >&2; fail "pvbatch $*"; }
  grep "^pvbatch_point_clouds:" "$log" || true
}
no_errors() {
  if grep -E ' ERR\| ' "$log"; then
    fail "pvbatch reported errors (above)"
  fi
}

pvbatch_headless "$script" "$plugin" "$work/valley" 256
no_errors
grep -q "pvbatch_point_clouds: all checks passed" "$log" || fail "the valley checks did not finish"

tile="$shared/file_with_both_wkt_and_geotiff_vlrs.las"
if [ -f "$tile" ]; then
  pvbatch_headless "$script" "$plugin" "$work/tile" 256 "$tile"
  no_errors
  grep -q "pvbatch_point_clouds: all checks passed" "$log" || fail "the shared tile's checks did not finish"
else
  echo "check-paraview-point-clouds: no shared LAS tile at $tile: skipped"
fi

pvbatch_headless "$script" "$plugin" "$work/bad" 64 --bad
grep -q "bad input checks done" "$log" || fail "the bad-input checks did not finish"
grep -q "ERR| vtkMRGILASReader.*'$work/bad/truncated.las'.*truncated" "$log" ||
  { cat "$log" >&2; fail "no error named the truncated file"; }
grep -q "ERR| vtkMRGISurfels.*has no normals" "$log" ||
  { cat "$log" >&2; fail "no error said the surfels' input has no normals"; }
grep -q "ERR| vtkMRGIPointCloudNormals.*RadiusScale = 0 must be finite and > 0" "$log" ||
  { cat "$log" >&2; fail "no error named the radius scale"; }
# Each problem is said once: the filters' executives add no generic error.
if grep "returned failure for request" "$log"; then
  fail "a generic executive error came with the filters' own (above)"
fi
echo "check-paraview-point-clouds: all checks passed"
