#!/usr/bin/env bash
# The area lights' one bounce against the ground truth's (issue 12, part 5):
# renders SCENE (default cornell-area) with its defaults, GI on and off, and
# the truth's one bounce (--reference --indirect-only, secondary visibility
# as VISIBILITY, default off: what reflective shadow maps assume), then
# prints the relative RMS of (on - off) against the truth per pixel and on
# 4x4 boxes and writes the pictures of Documentation/IndirectLight.md.
# Usage: Testing/Benchmarks/area_bounce.sh [OUTDIR] [SIZE] [PASSES] [VISIBILITY] [SCENE]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${MRGI_BUILD_DIR:-$root/build}"
out="${1:-$root/build/area-bounce}"
size="${2:-256}"
passes="${3:-64}"
visibility="${4:-off}"
scene="${5:-cornell-area}"
mkdir -p "$out"
cc -O2 -o "$out/area_bounce_error" "$root/Testing/Benchmarks/area_bounce_error.c" \
  -I"$root/Rendering/Core/Twins" -I"$root/Rendering/Core/IO" -L"$build/lib" \
  -lMRGICoreIO -lMRGICore -lm -Wl,-rpath,"$build/lib"
render="$build/bin/mrgi-render"
"$render" "$scene" --size "${size}x${size}" -q -o "$out/on.exr" -o "$out/on.png"
"$render" "$scene" --size "${size}x${size}" -q --gi off -o "$out/off.exr" -o "$out/off.png"
"$render" "$scene" --size "${size}x${size}" -q --reference --indirect-only \
  --reference-visibility "$visibility" --reference-error 0 --reference-passes "$passes" \
  -o "$out/truth-$visibility.exr"
"$out/area_bounce_error" "$out/on.exr" "$out/off.exr" "$out/truth-$visibility.exr" \
  "$out/$scene-bounce" 4
