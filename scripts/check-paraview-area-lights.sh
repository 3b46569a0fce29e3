#!/usr/bin/env bash
# MRGI Area Lights in ParaView: pvbatch with no X server renders the Cornell
# box lit by an "MRGI Area Light" placed as cornell-area's light (read from
# the MRGI Scene source), against mrgi-render's image of cornell-area; the
# light hidden, textured by a pipeline image (Wavelet), shown again; and
# invalid lights, which must give errors naming the problem and no light.
# Run by ctest as paraview.AreaLights after compat.ParaViewVTK built the
# ParaView tree.
# Usage: scripts/check-paraview-area-lights.sh PARAVIEW_BUILD_DIR MAIN_BIN_DIR
#   PARAVIEW_BUILD_DIR  the tree scripts/check-paraview-vtk.sh built
#   MAIN_BIN_DIR        the main (VTK 9.1) build's bin/ (mrgi-render, mrgi-compare)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
usage="usage: check-paraview-area-lights.sh PARAVIEW_BUILD_DIR MAIN_BIN_DIR"
build="$(cd "${1:?$usage}" && pwd)"
bin="$(cd "${2:?$usage}" && pwd)"
tests="$root/Module/ParaView/Testing"
plugin="$build/lib/paraview-5.11/plugins/MRGIRenderView/MRGIRenderView.so"
fail() { echo "check-paraview-area-lights: FAIL: $*" >&2; exit 1; }
command -v pvbatch > /dev/null || fail "pvbatch not found (install paraview: scripts/install-deps.sh)"
[ -f "$plugin" ] || fail "no plugin at $plugin (build the ParaView tree: scripts/check-paraview-vtk.sh)"
work="$build/area-light-check"
rm -rf "$work"
mkdir -p "$work"
export PYTHONPATH="$build/paraview-python/usr/lib/python3/dist-packages"
log="$work/pvbatch.log"
pvbatch_headless() {
  env -u DISPLAY timeout 300 pvbatch "$@" > "$log" 2>&1 || { cat "$log" >&2; fail "pvbatch $*"; }
}
# field VALUE_NAME IMAGE REFERENCE: one value of mrgi-compare's line.
field() { "$bin/mrgi-compare" "$2" "$3" | sed -n "s/^.*\<$1=\([^ ]*\).*/\1/p"; }
at_most() { awk -v r="$1" -v t="$2" 'BEGIN { exit !(r != "" && r <= t) }'; }
at_least() { awk -v r="$1" -v t="$2" 'BEGIN { exit !(r != "" && r >= t) }'; }

# 1. The untextured light where cornell-area has it, against mrgi-render.
size=256
pvbatch_headless "$tests/pvbatch_area_lights.py" "$plugin" "$work" "$size"
if grep -E ' ERR\| ' "$log"; then
  fail "pvbatch reported errors (above)"
fi
"$bin/mrgi-render" cornell-area -o "$work/mrgi-render-cornell-area.png" --size "${size}x${size}" \
  --exposure 0 --aa off -q
rms="$(field relative_rms "$work/area.png" "$work/mrgi-render-cornell-area.png")"
echo "check-paraview-area-lights: MRGI Area Light vs mrgi-render cornell-area ${size}x${size}: relative RMS $rms"
at_most "$rms" 0.01 || fail "relative RMS $rms > 0.01"

# 2. The view's Area Lights properties: a coarser voxel buffer moves the
#    shadows a little, no shadows move them much more.
coarse="$(field relative_rms "$work/voxels.png" "$work/area.png")"
unshadowed="$(field relative_rms "$work/unshadowed.png" "$work/area.png")"
echo "check-paraview-area-lights: voxel side 64 / no shadows vs defaults: relative RMS $coarse / $unshadowed"
at_least "$coarse" 0.002 || fail "AreaLightVoxelSide 64 did not change the shadows ($coarse)"
at_least "$unshadowed" 0.05 || fail "AreaLightVisibility off left the shadows ($unshadowed)"
awk -v c="$coarse" -v u="$unshadowed" 'BEGIN { exit !(u > 2 * c) }' ||
  fail "no shadows ($unshadowed) differ less than twice a coarser voxel buffer ($coarse)"

# 3. Moved (the display's Position): the light moves with its rectangle.
moved="$(field relative_rms "$work/moved.png" "$work/area.png")"
echo "check-paraview-area-lights: display moved 150 down vs in place: relative RMS $moved"
at_least "$moved" 0.05 || fail "moving the light's display did not move the light ($moved)"

# 4. Hidden: no light at all (the scene has no other light), so the image
#    is (nearly) black and far from the lit one.
off="$(field relative_rms "$work/hidden.png" "$work/area.png")"
echo "check-paraview-area-lights: light hidden vs shown: relative RMS $off"
at_least "$off" 0.9 || fail "hiding the light left the image lit ($off)"

# 5. Textured by the Wavelet: another image, not black.
tex="$(field relative_rms "$work/textured.png" "$work/area.png")"
lit="$(field rms "$work/textured.png" "$work/hidden.png")"
echo "check-paraview-area-lights: textured vs untextured: relative RMS $tex; textured vs dark: RMS $lit"
at_least "$tex" 0.05 || fail "the textured light looks like the untextured one ($tex)"
at_least "$lit" 0.02 || fail "the textured light leaves the scene dark (RMS $lit from black)"

# 6. Deleted and shown again: the same image as the first.
again="$(field relative_rms "$work/reloaded.png" "$work/area.png")"
echo "check-paraview-area-lights: shown again vs first: relative RMS $again"
at_most "$again" 0.001 || fail "the light shown again renders differently ($again)"

# 7. The output's layout (corners, colours, mark, pictures), then invalid
#    lights: an error naming the problem, no light, no crash.
pvbatch_headless "$tests/pvbatch_area_lights.py" "$plugin" "$work" 64 --checks
grep -q "layout: quad corners" "$log" || { cat "$log" >&2; fail "the layout checks did not run"; }
grep -q "MRGI Area Light: invalid parameters: .*parallel" "$log" ||
  { cat "$log" >&2; fail "no error named the parallel edges"; }
grep -q "MRGI Textured Area Light: the input image's texel .* (a picture needs finite values >= 0)" "$log" ||
  { cat "$log" >&2; fail "no error named the negative texel"; }
echo "check-paraview-area-lights: invalid lights reported and left out"
echo "check-paraview-area-lights: all checks passed"
