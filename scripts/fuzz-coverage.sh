#!/usr/bin/env bash
# Line and branch coverage of the C readers reached by fuzz corpora (llvm-cov).
# Builds each C harness with its reader's sources, clang's source-based
# coverage and the replay driver (no sanitizers), replays the corpus
# directories given, and prints llvm-cov's report for the reader's files.
# Usage: scripts/fuzz-coverage.sh WORK_DIR NAME=DIR[,DIR...]...
#   e.g. scripts/fuzz-coverage.sh /tmp/cov PNG=/tmp/fz/PNG/corpus,Testing/Fuzz/Seeds/PNG
# Harnesses: PLYCheck PNG EXR Parse (RenderOptions links VTK: not here).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work="${1:?usage: fuzz-coverage.sh WORK_DIR NAME=DIR[,DIR...]...}"
shift
mkdir -p "$work"
core="$root/Rendering/Core"
includes=(-I "$root/Testing/Fuzz" -I "$core/Twins" -I "$core/IO" -I "$core/Scenes")
twins=("$core/Twins/mrgi_error.c" "$core/Twins/mrgi_image.c" "$core/Twins/mrgi_parse.c")
for spec in "$@"; do
  name="${spec%%=*}"
  dirs="${spec#*=}"
  case "$name" in
    PLYCheck) sources=("$core/Scenes/mrgi_ply_check.c"); libs=(); shown=("$core/Scenes/mrgi_ply_check.c") ;;
    PNG) sources=("$core/IO/mrgi_png.c" "$core/IO/mrgi_atomic_file.c"); libs=(-lpng -lz)
         shown=("$core/IO/mrgi_png.c") ;;
    EXR) sources=("$core/IO/mrgi_exr.c" "$core/IO/mrgi_atomic_file.c")
         read -r -a libs <<<"$(pkg-config --libs OpenEXR)"; shown=("$core/IO/mrgi_exr.c")
         read -r -a exr_flags <<<"$(pkg-config --cflags OpenEXR)"; includes+=("${exr_flags[@]}") ;;
    Parse) sources=(); libs=(); shown=("$core/Twins/mrgi_parse.c") ;;
    *) echo "fuzz-coverage: no coverage build for '$name'" >&2; exit 2 ;;
  esac
  program="$work/Cover$name"
  clang -std=c11 -O0 -fprofile-instr-generate -fcoverage-mapping "${includes[@]}" \
    "$root/Testing/Fuzz/Fuzz$name.c" "$root/Testing/Fuzz/mrgi_fuzz_replay.c" \
    "${sources[@]}" "${twins[@]}" "${libs[@]}" -lm -o "$program"
  IFS=',' read -r -a inputs <<<"$dirs"
  LLVM_PROFILE_FILE="$work/$name.profraw" "$program" "${inputs[@]}" > "$work/$name.replay.log" 2>&1 ||
    { tail -n 5 "$work/$name.replay.log"; echo "fuzz-coverage: replay of $name failed" >&2; exit 1; }
  llvm-profdata merge -o "$work/$name.profdata" "$work/$name.profraw"
  echo "== $name: $(tail -n 1 "$work/$name.replay.log")"
  # Per function: the EXR and PNG files hold the writers too, which no harness calls.
  llvm-cov report -show-functions "$program" -instr-profile="$work/$name.profdata" "${shown[@]}"
done
