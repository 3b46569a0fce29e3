#!/usr/bin/env bash
# Install MRGI from BUILD_DIR into a scratch prefix, build Examples/Cxx as a
# separate project with find_package(MRGI), and run it headless.
# Run by ctest as install.FindPackage.
# Usage: scripts/check-find-package.sh BUILD_DIR WORK_DIR
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:?usage: check-find-package.sh BUILD_DIR WORK_DIR}"
work="${2:?usage: check-find-package.sh BUILD_DIR WORK_DIR}"
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
cmake -S "$root/Examples/Cxx" -B "$work/examples" -G Ninja \
  -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/examples" > "$work/build.log"
cd "$work"
LD_LIBRARY_PATH="$work/prefix/lib:${LD_LIBRARY_PATH:-}" "$work/examples/CornellBoxHeadless"
test -s "$work/cornell.exr"
echo "check-find-package: installed MRGI found, example built and rendered cornell.exr"
