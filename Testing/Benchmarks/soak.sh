#!/usr/bin/env bash
# The long soak: TestMRGISoak (Testing/Cxx/TestMRGISoak.cxx) over 10,000
# frames at 256x256, writing the memory curve (resident set, heap, GPU memory
# where the driver reports it) as CSV. CI runs the same program for 500
# frames (ctest cxx.TestMRGISoak).
#
#   bash Testing/Benchmarks/soak.sh [BUILD_DIR] [FRAMES] [CSV]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${1:-$root/build}"
frames="${2:-10000}"
csv="${3:-$build/soak-$frames.csv}"
program="$build/Testing/Cxx/TestMRGISoak"
if [ ! -x "$program" ]; then
  echo "soak: $program is not built (bash scripts/build.sh)" >&2
  exit 2
fi
env -u DISPLAY "$program" --frames "$frames" --csv "$csv"
echo "soak: memory curve in $csv"
