#!/usr/bin/env bash
# The ParaView GUI test (issue 16, part 6): starts the real `paraview` under
# Xvfb with the MRGI plugin and Module/ParaView/Testing/paraview_gui_cornell.py,
# which puts an MRGI Render View in the layout, shows the Cornell box and
# saves the view at 256 x 256 with GI on and off; then compares those with
# `mrgi-render cornell --exposure 0 --aa off` (GI on and off) and fails when
# either differs by more than 1% relative RMS, or when GI on does not differ
# from GI off. Run by ctest as paraview.GUI.
#
# Usage: scripts/check-paraview-gui.sh BUILD_DIR OUT_DIR [--frames N [--timing-gi off]]
#                                      [--grab FILE.png]
#   BUILD_DIR   the main build (bin/mrgi-render, bin/mrgi-compare); the plugin
#               build is BUILD_DIR/paraview-vtk (compat.ParaViewVTK's tree),
#               or MRGI_PARAVIEW_BUILD
#   --frames N  also time N still renders at 512 x 512 in the GUI and in a
#               plain VTK window (vtk_cornell_frames.py under Xvfb, `import
#               mrgi` from BUILD_DIR) and print both medians and their ratio
#   --timing-gi off  time with GI off instead: ParaView's own render view
#               against the plain VTK window without vtkMRGIPass, i.e. what
#               ParaView adds around any frame
#   --grab F    also save the whole ParaView window as F (PNG, at most 800
#               pixels wide), as the script leaves it
# Environment: MRGI_GUI_TIMEOUT (seconds for one paraview run, default 300),
# MRGI_GUI_SCREEN (Xvfb's screen, default 1280x1024x24; ParaView's main
# window keeps its own size, about 1150x760, on a larger screen).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
usage="usage: check-paraview-gui.sh BUILD_DIR OUT_DIR [--frames N [--timing-gi off]] [--grab FILE.png]"
build="${1:?$usage}"
out="${2:?$usage}"
shift 2
frames=0
timing_gi=on
grab=""
while [ "$#" -gt 0 ]; do
  case "$1" in
    --frames) frames="${2:?--frames needs a count}"; shift 2 ;;
    --timing-gi) timing_gi="${2:?--timing-gi needs on or off}"; shift 2 ;;
    --grab) grab="${2:?--grab needs a file name}"; shift 2 ;;
    *) echo "check-paraview-gui: unknown option '$1'; $usage" >&2; exit 2 ;;
  esac
done
case "$timing_gi" in
  on|off) ;;
  *) echo "check-paraview-gui: --timing-gi '$timing_gi' is not on or off" >&2; exit 2 ;;
esac
case "$frames" in
  ''|*[!0-9]*) echo "check-paraview-gui: --frames '$frames' is not a count" >&2; exit 2 ;;
esac

fail() { echo "check-paraview-gui: $*" >&2; exit 1; }
pv_build="${MRGI_PARAVIEW_BUILD:-$build/paraview-vtk}"
if [ -d "$pv_build" ]; then pv_build="$(cd "$pv_build" && pwd)"; fi
plugin_dir="$pv_build/lib/paraview-5.11/plugins/MRGIRenderView"
pv_python="$pv_build/paraview-python/usr/lib/python3/dist-packages"
testing="$root/Module/ParaView/Testing"
gui_timeout="${MRGI_GUI_TIMEOUT:-300}"
screen="${MRGI_GUI_SCREEN:-1280x1024x24}"
for tool in paraview xvfb-run xauth timeout; do
  command -v "$tool" > /dev/null || fail "'$tool' not found (scripts/install-deps.sh installs it)"
done
[ -f "$plugin_dir/MRGIRenderView.so" ] ||
  fail "no plugin $plugin_dir/MRGIRenderView.so (scripts/check-paraview-vtk.sh $pv_build builds it)"
[ -f "$pv_python/paraview/simple.py" ] ||
  fail "no unpacked python3-paraview in $pv_python (scripts/check-paraview-vtk.sh unpacks it)"
for tool in mrgi-render mrgi-compare; do
  [ -x "$build/bin/$tool" ] || fail "no $build/bin/$tool (build the main tree first)"
done

mkdir -p "$out"
out="$(cd "$out" && pwd)"
rm -f "$out"/gui-*.png "$out"/gui-status.txt "$out"/gui-frames.txt "$out"/screen.xwd
rm -rf "$out/fb" "$out/xdg"
mkdir -p "$out/fb" "$out/xdg"
chmod 700 "$out/xdg"

# xvfb-run (a /bin/sh script) stops its Xvfb when the command ends, but not
# when it is killed itself: if this script is stopped (ctest's timeout),
# end the xvfb-run still running, its Xvfb and its command first.
xvfb_pid=""
cleanup() {
  if [ -n "$xvfb_pid" ] && kill -0 "$xvfb_pid" 2> /dev/null; then
    pkill -TERM -P "$xvfb_pid" 2> /dev/null || true
    kill -TERM "$xvfb_pid" 2> /dev/null || true
  fi
}
trap cleanup EXIT
trap 'exit 143' TERM INT

# Runs "$@" under a fresh Xvfb ($screen, its screen also kept in
# $out/fb/Xvfb_screen0), the command itself under a timeout: the GUI can hang.
under_xvfb() {
  local log="$1"
  shift
  xvfb-run -a -e "$out/xvfb-errors.log" -s "-screen 0 $screen -fbdir $out/fb" \
    timeout -k 10 "$gui_timeout" "$@" > "$log" 2>&1 &
  xvfb_pid=$!
  local status=0
  wait "$xvfb_pid" || status=$?
  xvfb_pid=""
  return "$status"
}

pv_version="$(dpkg-query -W -f='${Version}' paraview 2> /dev/null || echo '(version unknown)')"
echo "check-paraview-gui: paraview $pv_version with $plugin_dir"
start=$SECONDS
status=0
# --dr: no user settings. `--plugins` takes plugin names (a path there is
# silently ignored in 5.11), found through --plugin-search-paths.
XDG_RUNTIME_DIR="$out/xdg" PYTHONPATH="$pv_python" \
  MRGI_GUI_OUT="$out" MRGI_GUI_SCRIPT_DIR="$testing" MRGI_GUI_SIZE=256 \
  MRGI_GUI_FRAMES="$frames" MRGI_GUI_TIMING_SIZE=512 MRGI_GUI_TIMING_GI="$timing_gi" \
  MRGI_GUI_GRAB="${grab:+$out/screen.xwd}" MRGI_GUI_XWD="$out/fb/Xvfb_screen0" \
  under_xvfb "$out/paraview.log" \
  paraview --dr --plugin-search-paths="$plugin_dir" --plugins=MRGIRenderView \
  --script="$testing/paraview_gui_cornell.py" --exit || status=$?
echo "check-paraview-gui: paraview ran $((SECONDS - start)) s, exit status $status"
if [ "$status" -eq 124 ] || [ "$status" -eq 137 ]; then
  tail -n 30 "$out/paraview.log" >&2 || true
  fail "paraview did not finish within $gui_timeout s (MRGI_GUI_TIMEOUT); log: $out/paraview.log"
fi
grep "paraview_gui_cornell:" "$out/paraview.log" || true
if [ ! -f "$out/gui-status.txt" ]; then
  tail -n 30 "$out/paraview.log" >&2 || true
  fail "the GUI script did not finish (exit status $status); log: $out/paraview.log"
fi
if [ "$(head -1 "$out/gui-status.txt")" != "ok" ]; then
  cat "$out/gui-status.txt" >&2
  fail "the GUI script failed; log: $out/paraview.log"
fi
[ "$status" -eq 0 ] || fail "paraview exited with status $status; log: $out/paraview.log"

# mrgi-render's image of the same scene with the view's settings: fixed
# exposure 0 EV, no FXAA.
for gi in on off; do
  "$build/bin/mrgi-render" cornell --exposure 0 --aa off --gi "$gi" --size 256x256 \
    -o "$out/mrgi-render-gi-$gi.png" -q
done
relative_rms() {
  local line
  line="$("$build/bin/mrgi-compare" "$1" "$2")" || fail "mrgi-compare $1 $2 failed"
  echo "$line" | sed -n 's/.*relative_rms=\([0-9.eE+-]*\).*/\1/p'
}
ok=1
for gi in on off; do
  rms="$(relative_rms "$out/gui-gi-$gi.png" "$out/mrgi-render-gi-$gi.png")"
  echo "check-paraview-gui: GI $gi, GUI vs mrgi-render: relative RMS $rms (limit 0.01)"
  if ! awk -v r="$rms" 'BEGIN { exit !(r != "" && r <= 0.01) }'; then
    echo "check-paraview-gui: the GUI's GI-$gi image differs from mrgi-render's by more than 1%" >&2
    ok=0
  fi
done
# The indirect light must be there: on the Cornell box it changes the image
# by about 28% relative RMS; less than 5% means the pass did not run.
rms="$(relative_rms "$out/gui-gi-on.png" "$out/gui-gi-off.png")"
echo "check-paraview-gui: GUI, GI on vs off: relative RMS $rms (must exceed 0.05)"
if ! awk -v r="$rms" 'BEGIN { exit !(r != "" && r > 0.05) }'; then
  echo "check-paraview-gui: GI on looks like GI off in the GUI" >&2
  ok=0
fi
[ "$ok" -eq 1 ] || fail "images differ (in $out)"

if [ -n "$grab" ]; then
  [ -s "$out/screen.xwd" ] || fail "no screen grab in $out/screen.xwd"
  /usr/bin/python3 "$testing/xwd_to_png.py" "$out/screen.xwd" "$grab" --crop --max-width 800
fi

if [ "$frames" -gt 0 ]; then
  [ -f "$out/gui-frames.txt" ] || fail "the GUI script wrote no gui-frames.txt"
  under_xvfb "$out/vtk-frames.txt" env PYTHONPATH="$build/lib/python3/dist-packages" \
    /usr/bin/python3 "$testing/vtk_cornell_frames.py" --frames "$frames" --size 512 \
    --gi "$timing_gi" ||
    fail "vtk_cornell_frames.py failed: $out/vtk-frames.txt"
  # Medians of wall and CPU time per frame, GUI over plain VTK window.
  awk '
    FNR == 1 { file++ }
    /^[0-9.]+ [0-9.]+$/ { n[file]++; wall[file, n[file]] = $1; cpu[file, n[file]] = $2 }
    function median(kind, f,   i, j, k, v, t) {
      k = n[f]
      for (i = 1; i <= k; i++) v[i] = (kind == "wall") ? wall[f, i] : cpu[f, i]
      for (i = 1; i <= k; i++)
        for (j = i + 1; j <= k; j++)
          if (v[j] < v[i]) { t = v[i]; v[i] = v[j]; v[j] = t }
      return v[int(k / 2) + 1]
    }
    END {
      gw = median("wall", 1); gc = median("cpu", 1); pw = median("wall", 2); pc = median("cpu", 2)
      printf "check-paraview-gui: %d frames at 512x512, GI %s, medians: GUI %.1f ms wall, %.1f ms CPU; ", n[1], gi, gw, gc
      printf "plain VTK window %.1f ms wall, %.1f ms CPU; ratio %.2f wall, %.2f CPU\n", pw, pc, gw / pw, gc / pc
    }' gi="$timing_gi" "$out/gui-frames.txt" "$out/vtk-frames.txt"
fi
echo "check-paraview-gui: passed ($out)"
