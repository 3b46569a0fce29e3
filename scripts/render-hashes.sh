#!/usr/bin/env bash
# Renders a fixed set of configurations with mrgi-render (160x120) and prints the
# SHA-256 of each EXR (HDR floats) and PNG: run before and after a refactor,
# diff the two lists. Usage: render-hashes.sh BUILD_DIR OUT_DIR
set -euo pipefail
build="$1"; out="$2"; mkdir -p "$out"
bin="$build/bin/mrgi-render"
[ -x "$bin" ] || bin="$(find "$build" -name mrgi-render -type f -perm -u+x | head -1)"
run() { name="$1"; shift; "$bin" "$@" -o "$out/$name.exr" -q --size 160x120 > "$out/$name.log" 2>&1 || echo "FAIL $name"; "$bin" "$@" -o "$out/$name.png" -q --size 160x120 >> "$out/$name.log" 2>&1 || echo "FAIL png $name"; }
run cornell cornell
run cornell-full cornell --gi full
run cornell-fast cornell --preset fast
run cornell-accurate cornell --preset accurate
run cornell-splat cornell --gather splat
run cornell-mask cornell --upsample mask
run cornell-detail cornell --surface-detail 0.5
run cornell-spot cornell-spot
run cornell-spot-imp cornell-spot --vpl-selection importance --vpls 64
run cornell-area cornell-area
run cornell-area-naive cornell-area --area-light-visibility naive
run cornell-area-off cornell-area --area-light-visibility off
run cornell-area-nostencil cornell-area --incremental-stencil off
run cornell-area-spec cornell-area --specular 0.5:40
run cornell-area-spec-mr cornell-area --specular 0.5:40 --area-light-specular-resolution multires
run cornell-area-spec-naive cornell-area --specular 0.5:120 --area-light-visibility naive
run living living-room --specular 0.4:30
run living-mr living-room --specular 0.4:30 --area-light-specular-resolution multires
run living-inter living-room --visibility-interleave on
run scaling scaling --objects 20 --triangles 2000
( cd "$out" && sha256sum *.png *.exr 2>/dev/null )
