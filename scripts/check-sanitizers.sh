#!/usr/bin/env bash
# The sanitizer tree: MRGI built with clang, -fsanitize=address,undefined and
# libFuzzer coverage, in its own build directory. Run by ctest (sanitize.*,
# Testing/Fuzz/CMakeLists.txt); see Documentation/reliability/fuzzing.md.
# Usage: scripts/check-sanitizers.sh build DIR [cmake arguments]
#          configure DIR and build what the tests below and fuzz.* run
#        scripts/check-sanitizers.sh core DIR
#          the C core's tests (and the C replays) with ASan, UBSan and LSan
#        scripts/check-sanitizers.sh cli DIR
#          mrgi-render on bad input (python.test_cli's bad-input cases,
#          crafted scene files, ctest labels badinput and fuzzreplay) with
#          ASan and UBSan, leak checks off
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
what="${1:?usage: check-sanitizers.sh build|core|cli DIR}"
dir="${2:?usage: check-sanitizers.sh build|core|cli DIR}"
shift 2
# Symbolized stack traces in sanitizer reports (llvm-14, scripts/install-deps.sh).
if [ -z "${ASAN_SYMBOLIZER_PATH:-}" ] && [ -x /usr/lib/llvm-14/bin/llvm-symbolizer ]; then
  export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer
fi
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
unset DISPLAY

case "$what" in
  build)
    start=$(date +%s)
    # -O1: sanitizer reports keep their stack traces readable; no -Werror
    # (warnings are the gcc build's job, clang warns differently). No PCL
    # module: uninstrumented PCL and OpenMP would only add noise; the PCD
    # structure check it relies on is in the C core, sanitized here.
    cmake -S "$root" -B "$dir" -G Ninja \
      -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS_RELEASE=-O1 -DCMAKE_CXX_FLAGS_RELEASE=-O1 \
      -DMRGI_SANITIZE=address,undefined -DMRGI_FUZZ=ON -DMRGI_WARNINGS_AS_ERRORS=OFF \
      -DMRGI_WRAP_PYTHON=OFF -DMRGI_BUILD_EXAMPLES=OFF -DMRGI_ENABLE_PCL=OFF "$@" > "$dir.configure.log" 2>&1 ||
      { cat "$dir.configure.log"; exit 1; }
    cmake --build "$dir" --target mrgi_sanitize_all --parallel "${MRGI_JOBS:-$(nproc)}"
    echo "check-sanitizers: sanitizer tree built in $(( $(date +%s) - start )) s"
    ;;
  core)
    # Leak detection on: the C core owns all of its memory.
    export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1"
    ctest --test-dir "$dir" -L core --output-on-failure --no-tests=error
    ;;
  cli)
    # VTK and Mesa (llvmpipe) keep allocations until exit that LSan would
    # report; they are not MRGI's, so leak detection is off for programs that
    # load them. Everything else (overflows, use after free, UB) still aborts.
    # Reports go to files too: a report after the program printed its error
    # line must fail this test even where a caller only checks that line.
    tmp="$dir/Testing/Temporary/sanitize-cli"
    rm -rf "$tmp"
    mkdir -p "$tmp/reports"
    export ASAN_OPTIONS="detect_leaks=0:exitcode=86:log_path=$tmp/reports/asan"
    export UBSAN_OPTIONS="$UBSAN_OPTIONS:exitcode=86:log_path=$tmp/reports/ubsan"
    render="$dir/bin/mrgi-render"
    MRGI_RENDER="$render" MRGI_TEST_TMP="$tmp" \
      /usr/bin/python3 "$root/Testing/Python/test_cli.py" --bad-input
    # Crafted scene files of the formats MRGI guards (PLY) and others VTK
    # reads: each must end in one error line and status 1 (a bad input file), no crash.
    printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n0\n1\n2\n' \
      > "$tmp/no-y-z.ply"
    printf 'ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\nproperty float y\nproperty float z\nend_header\nabc' \
      > "$tmp/truncated.ply"
    printf 'ply\nformat binary_big_endian 1.0\nelement vertex 2147483646\nproperty double x\nproperty double y\nproperty double z\nelement face 2147483646\nproperty list uint int vertex_indices\nend_header\n' \
      > "$tmp/huge-counts.ply"
    printf 'v 1 2\nv 0 0 0\nf 1 2 3 4 5\nf -7 9\n' > "$tmp/bad-faces.obj"
    printf '<VTKFile type="PolyData"><PolyData><Piece NumberOfPoints="5" NumberOfPolys="1"><Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">0 0</DataArray></Points></Piece></PolyData></VTKFile>' \
      > "$tmp/short-points.vtp"
    for scene in no-y-z.ply truncated.ply huge-counts.ply bad-faces.obj short-points.vtp; do
      status=0
      "$render" "$tmp/$scene" -o "$tmp/out.png" --size 16x16 -q > "$tmp/$scene.log" 2>&1 || status=$?
      if [ "$status" -ne 1 ] || [ "$(grep -c '^mrgi-render: error:' "$tmp/$scene.log")" -ne 1 ]; then
        cat "$tmp/$scene.log"
        echo "check-sanitizers: $scene: status $status, expected 1 and one error line" >&2
        exit 1
      fi
      echo "check-sanitizers: $scene: $(grep '^mrgi-render: error:' "$tmp/$scene.log")"
    done
    # Tests labelled badinput (crafted files fed to the programs) when the
    # tree has them, and the fuzz replays (fuzz.ReplayRenderOptions loads VTK).
    ctest --test-dir "$dir" -L 'badinput|fuzzreplay' --output-on-failure
    if [ -n "$(ls -A "$tmp/reports")" ]; then
      cat "$tmp"/reports/*
      echo "check-sanitizers: sanitizer reports above (in $tmp/reports)" >&2
      exit 1
    fi
    echo "check-sanitizers: mrgi-render's bad-input cases ran sanitized without a report"
    ;;
  *)
    echo "check-sanitizers: unknown step '$what' (build, core or cli)" >&2
    exit 2
    ;;
esac
