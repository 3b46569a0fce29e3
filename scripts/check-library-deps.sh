#!/usr/bin/env bash
# Check the libraries a shared library loads: everything ldd resolves for it,
# its own NEEDED entries and theirs, so a boundary crossed anywhere below it
# shows. Run by ctest as deps.*.
# Usage: scripts/check-library-deps.sh LIBRARY --forbid REGEX
#        scripts/check-library-deps.sh LIBRARY --only REGEX
#   --forbid  fails if a loaded library's file name matches REGEX
#   --only    fails if a loaded library's file name does not match REGEX
# (REGEX: grep -E, case-insensitive.)
set -euo pipefail
usage="usage: check-library-deps.sh LIBRARY --forbid|--only REGEX"
lib="${1:?$usage}"
mode="${2:?$usage}"
regex="${3:?$usage}"
case "$mode" in
  --forbid) select=() ;;
  --only) select=(-v) ;;
  *) echo "$usage" >&2; exit 2 ;;
esac

# ldd lines: "libfoo.so.1 => /path/libfoo.so.1 (0x...)", "/lib64/ld-linux-x86-64.so.2 (0x...)",
# "linux-vdso.so.1 (0x...)" or "libfoo.so.1 => not found".
loaded="$(ldd "$lib")"
if grep "not found" <<< "$loaded"; then
  echo "check-library-deps: $lib: unresolved libraries, cannot judge" >&2
  exit 1
fi
names="$(awk '{ print $1 }' <<< "$loaded" | xargs -n 1 basename | sort -u)"
echo "check-library-deps: $(basename "$lib") loads:" $names
if bad="$(grep -Ei "${select[@]}" -e "$regex" <<< "$names")"; then
  echo "check-library-deps: $(basename "$lib") must not load:" $bad >&2
  exit 1
fi
echo "check-library-deps: $(basename "$lib"): none outside the rule ($mode '$regex')"
