#!/usr/bin/env bash
# The main job: install what is missing, build, and render the built-in
# Cornell box headless to out/cornell.png and out/cornell.exr, printing the
# GPU time of each stage.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
mkdir -p "$root/out"
"${MRGI_BUILD_DIR:-$root/build}/bin/mrgi-render" cornell \
  -o "$root/out/cornell.png" -o "$root/out/cornell.exr" \
  --size 512x512 --timings --frames 5 "$@"
