#!/usr/bin/env bash
# Install MRGI from BUILD_DIR into a scratch prefix, build Examples/Cxx as a
# separate project with find_package(MRGI), and run it headless; then run
# the installed mrgi-render and import the installed Python package. Nothing
# is given LD_LIBRARY_PATH: installed things find their libraries themselves.
# Run by ctest as install.FindPackage.
# Usage: scripts/check-find-package.sh BUILD_DIR WORK_DIR [PYTHON SITE_DIR]
#   PYTHON, SITE_DIR: the interpreter with vtkmodules, and where `mrgi` is
#   installed relative to the prefix (given when MRGI wraps Python).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:?usage: check-find-package.sh BUILD_DIR WORK_DIR [PYTHON SITE_DIR]}"
work="${2:?usage: check-find-package.sh BUILD_DIR WORK_DIR [PYTHON SITE_DIR]}"
python="${3:-}"
python_site="${4:-}"
rm -rf "$work"
mkdir -p "$work"
prefix="$work/prefix"
cmake --install "$build" --prefix "$prefix" > "$work/install.log"
cmake -S "$root/Examples/Cxx" -B "$work/examples" -G Ninja \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/examples" > "$work/build.log"
cd "$work"
unset LD_LIBRARY_PATH
"$work/examples/CornellBoxHeadless"
test -s "$work/cornell.exr"
echo "check-find-package: installed MRGI found, example built and rendered cornell.exr"

"$prefix/bin/mrgi-render" cornell -o "$work/cornell-cli.png" --size 64x64 -q
test -s "$work/cornell-cli.png"
echo "check-find-package: installed mrgi-render rendered cornell-cli.png"

# The installed `mrgi` package holds every exported class of the installed
# headers (`class MRGI..._EXPORT vtkMRGI...`).
if [ -n "$python" ]; then
  PYTHONPATH="$prefix/$python_site" "$python" - "$prefix" <<'PY'
import pathlib
import re
import sys

import mrgi

# The prefix's package, not another one on the path (an installed .deb).
where = pathlib.Path(mrgi.__file__).resolve()
if pathlib.Path(sys.argv[1]).resolve() not in where.parents:
    sys.exit(f"check-find-package: import mrgi found {where}, outside the prefix {sys.argv[1]}")

declared = re.compile(r"^class\s+\w+_EXPORT\s+(vtkMRGI\w+)", re.M)
classes = sorted(
    c for h in pathlib.Path(sys.argv[1]).rglob("vtkMRGI*.h") for c in declared.findall(h.read_text())
)
missing = [c for c in classes if not hasattr(mrgi, c)]
if not classes or missing:
    sys.exit(f"check-find-package: installed mrgi lacks {missing or 'every class'}")
print(f"check-find-package: installed mrgi imports, with all {len(classes)} classes")
PY
fi
