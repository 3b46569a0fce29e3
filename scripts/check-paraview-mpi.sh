#!/usr/bin/env bash
# ParaView's own distributed rendering with the MRGI view: `mpirun -np 2
# pvbatch`, the Cornell box partitioned across the ranks (whole meshes),
# IceT compositing, the reflective shadow maps composited across ranks so
# that both gather from the same VPLs. The 2-rank image must be within 1%
# relative RMS of the 1-rank image (multiresolution gather), and equal to
# it with the full-resolution gather. Run by ctest as paraview.MPI.
# Usage: scripts/check-paraview-mpi.sh PARAVIEW_BUILD_DIR MAIN_BIN_DIR
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(cd "${1:?usage: check-paraview-mpi.sh PARAVIEW_BUILD_DIR MAIN_BIN_DIR}" && pwd)"
bin="$(cd "${2:?usage: check-paraview-mpi.sh PARAVIEW_BUILD_DIR MAIN_BIN_DIR}" && pwd)"
fail() { echo "check-paraview-mpi: FAIL: $*" >&2; exit 1; }
for tool in pvbatch mpirun; do
  command -v "$tool" > /dev/null || fail "$tool not found (scripts/install-deps.sh installs paraview and openmpi-bin)"
done
work="$build/mpi-check"
rm -rf "$work"
mkdir -p "$work"
prefix="$work/prefix"
cmake --install "$build" --prefix "$prefix" > "$work/install.log"
plugin_dir="$prefix/lib/paraview-5.11/plugins/MRGIRenderView"
[ -f "$plugin_dir/MRGIRenderView.so" ] || fail "the install has no plugin in $plugin_dir"
export PYTHONPATH="$build/paraview-python/usr/lib/python3/dist-packages"
export PV_PLUGIN_PATH="$plugin_dir"
script="$root/Module/ParaView/Testing/pvbatch_mpi.py"

# Every rank loads the plugin (PV_PLUGIN_PATH). No X server: the plugin
# supplies MRGI's EGL window; --disable-xdisplay-test tells ParaView that
# this process can render although no X display opens (its own test knows
# only X, and without it the ranks disagree on where to render and hang).
run() {
  local ranks="$1" out="$2"
  shift 2
  env -u DISPLAY timeout 600 mpirun --allow-run-as-root --oversubscribe \
    -x PYTHONPATH -x PV_PLUGIN_PATH -np "$ranks" \
    pvbatch --disable-xdisplay-test "$script" "$out" 256 "$@" > "$work/run.log" 2>&1 ||
    { cat "$work/run.log" >&2; fail "mpirun -np $ranks pvbatch $*"; }
  if grep -E ' ERR\| ' "$work/run.log"; then
    fail "pvbatch reported errors (above)"
  fi
  grep '^pvbatch_mpi:' "$work/run.log"
}
compare() { "$bin/mrgi-compare" "$1" "$2" | sed -n 's/^relative_rms=\([^ ]*\).*/\1/p'; }

run 1 "$work/ranks-1.png"
run 2 "$work/ranks-2.png" | tee "$work/ranks-2.txt"
grep -q 'ranks=2 ' "$work/ranks-2.txt" || fail "pvbatch did not run on 2 ranks"
bytes="$(sed -n 's/.*rsm_composite_bytes=\([0-9]*\).*/\1/p' "$work/ranks-2.txt")"
[ "${bytes:-0}" -gt 0 ] || fail "the reflective shadow maps were not composited across ranks"
rms="$(compare "$work/ranks-2.png" "$work/ranks-1.png")"
echo "check-paraview-mpi: 2 ranks vs 1, multiresolution: relative RMS $rms ($bytes bytes sent by rank 0)"
awk -v r="$rms" 'BEGIN { exit !(r != "" && r <= 0.01) }' || fail "relative RMS $rms > 0.01"

run 1 "$work/full-1.png" --indirect full
run 2 "$work/full-2.png" --indirect full
full="$(compare "$work/full-2.png" "$work/full-1.png")"
echo "check-paraview-mpi: 2 ranks vs 1, full-resolution gather: relative RMS $full"
awk -v r="$full" 'BEGIN { exit !(r != "" && r <= 0.001) }' || fail "full gather: relative RMS $full > 0.001"
# Without --disable-xdisplay-test, ParaView's X-only capability test makes
# the ranks wait on each other forever: the plugin must say so, naming the
# option, before that happens (the run is then stopped).
env -u DISPLAY timeout -k 5 20 mpirun --allow-run-as-root --oversubscribe \
  -x PYTHONPATH -x PV_PLUGIN_PATH -np 2 \
  pvbatch "$script" "$work/no-flag.png" 64 > "$work/no-flag.log" 2>&1 || true
grep -q 'ERR| MRGI plugin: 2 MPI ranks and no X display.*--disable-xdisplay-test' "$work/no-flag.log" ||
  { cat "$work/no-flag.log" >&2; fail "no clear error without --disable-xdisplay-test"; }
echo "check-paraview-mpi: without --disable-xdisplay-test the plugin names the option"
echo "check-paraview-mpi: all checks passed"
