#!/usr/bin/env bash
# The tests: install what is missing, build, run the whole suite with ctest
# (C core, C++ passes, Python, CLI, install and Debian package, a sanitizer
# build with fuzzing in build/sanitize, and a build against ParaView 5.11's
# VTK 9.2). Exits non-zero on any failure. .ci/run runs exactly this.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install-deps.sh"
# Warnings are errors here (CI); a plain build.sh leaves them warnings.
bash "$root/scripts/build.sh" -DMRGI_WARNINGS_AS_ERRORS=ON
cd "${MRGI_BUILD_DIR:-$root/build}"
ctest --output-on-failure --timeout 1200 -j "${MRGI_TEST_JOBS:-2}" "$@"
