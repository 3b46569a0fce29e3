#!/usr/bin/env bash
# Build the Debian package from BUILD_DIR (cpack -G DEB), check its files and
# run paths, install it with apt-get, run the installed mrgi-render and
# `import mrgi` from a neutral directory, and purge it again. Any failed
# step fails the script; the package is purged on every exit once installed.
# Run by ctest as install.DebPackage. Needs root or sudo (CI runs as root).
# Usage: scripts/check-deb-package.sh BUILD_DIR WORK_DIR
set -euo pipefail
build="${1:?usage: check-deb-package.sh BUILD_DIR WORK_DIR}"
work="${2:?usage: check-deb-package.sh BUILD_DIR WORK_DIR}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
fail() { echo "check-deb-package: $*" >&2; exit 1; }

if dpkg-query -W -f='${Status}' mrgi 2>/dev/null | grep -q "install ok installed"; then
  fail "a package 'mrgi' is already installed; remove it first (apt-get remove mrgi)"
fi
rm -rf "$work"
mkdir -p "$work/neutral"
(cd "$build" && cpack -G DEB -B "$work" > "$work/cpack.log" 2>&1) ||
  { cat "$work/cpack.log"; fail "cpack -G DEB failed"; }
deb="$(ls "$work"/mrgi_*_amd64.deb 2>/dev/null | head -n 1)"
[ -n "$deb" ] || { cat "$work/cpack.log"; fail "no mrgi_*_amd64.deb in $work"; }
echo "check-deb-package: built $(basename "$deb") ($(du -k "$deb" | cut -f1) KiB)"

# The control fields: Depends from dpkg-shlibdeps (VTK's libraries) plus python3-vtk9.
depends="$(dpkg-deb -f "$deb" Depends)"
echo "check-deb-package: Depends: $depends"
grep -q "python3-vtk9" <<<"$depends" || fail "Depends lacks python3-vtk9"
grep -q "libvtk9" <<<"$depends" || fail "Depends lacks VTK's libraries (dpkg-shlibdeps did not run?)"

# The files: where Debian finds them, and run paths relative to themselves.
dpkg-deb -x "$deb" "$work/root"
for f in usr/bin/mrgi-render usr/bin/mrgi-compare usr/lib/python3/dist-packages/mrgi/__init__.py \
         usr/lib/cmake/MRGI/MRGIConfig.cmake usr/include/mrgi/mrgi_error.h; do
  [ -e "$work/root/$f" ] || fail "the package lacks /$f"
done
elves=0
while IFS= read -r -d '' f; do
  if [ "$(head -c 4 "$f" | od -An -c | tr -d ' ')" = "177ELF" ]; then
    elves=$((elves + 1))
    runpath="$(readelf -d "$f" | sed -n 's/.*(RUNPATH).*\[\(.*\)\]/\1/p')"
    if readelf -d "$f" | grep -q "(RPATH)"; then fail "${f#"$work/root"} has an RPATH (not RUNPATH)"; fi
    case "$runpath" in
      *"$build"* | *"$(cd "$build" && pwd -P)"*) fail "${f#"$work/root"} has a run path into the build tree: $runpath" ;;
    esac
    if readelf -d "$f" | grep -q "NEEDED.*libMRGI" && [[ "$runpath" != *'$ORIGIN'* ]]; then
      fail "${f#"$work/root"} needs MRGI libraries but has no \$ORIGIN run path ($runpath)"
    fi
  fi
done < <(find "$work/root" -type f -print0)
[ "$elves" -ge 10 ] || fail "only $elves ELF files in the package"
echo "check-deb-package: $elves ELF files, none with a run path into the build tree"

# apt's plan: installing must not remove (or downgrade) any package.
export DEBIAN_FRONTEND=noninteractive
apt_opts=(-o DPkg::Lock::Timeout=600 -o APT::Get::Show-Versions=false)
plan="$($SUDO apt-get install -s --no-install-recommends "${apt_opts[@]}" "$deb" 2>&1)" ||
  { echo "$plan"; fail "apt-get cannot install the package (simulated)"; }
if grep -qE "^(Remv|The following packages will be REMOVED|The following packages will be DOWNGRADED)" <<<"$plan"; then
  echo "$plan"
  fail "installing the package would remove or downgrade other packages"
fi
installed=0
cleanup() {
  if [ "$installed" -eq 1 ]; then
    # purge, not remove: nothing of the package is left, not even dpkg's
    # record of its maintainer scripts (state "rc").
    $SUDO apt-get purge -y -qq "${apt_opts[@]}" mrgi > "$work/remove.log" 2>&1 ||
      { cat "$work/remove.log" >&2; echo "check-deb-package: apt-get purge mrgi failed" >&2; exit 1; }
  fi
}
trap cleanup EXIT
installed=1
$SUDO apt-get install -y -qq --no-install-recommends "${apt_opts[@]}" "$deb" > "$work/install.log" 2>&1 ||
  { cat "$work/install.log"; fail "apt-get install $deb failed"; }
echo "check-deb-package: installed with apt-get"

# Run what was installed, from a neutral directory, with nothing pointing
# into the build tree.
cd "$work/neutral"
env -u LD_LIBRARY_PATH -u PYTHONPATH -u DISPLAY /usr/bin/mrgi-render cornell -o x.png --size 64x64 -q
[ -s x.png ] || fail "the installed mrgi-render wrote no x.png"
echo "check-deb-package: /usr/bin/mrgi-render rendered x.png"
where="$(env -u LD_LIBRARY_PATH -u PYTHONPATH -u DISPLAY /usr/bin/python3 -c \
  'import mrgi; print(mrgi.__file__); assert hasattr(mrgi, "vtkMRGIPass")')"
[ "$where" = "/usr/lib/python3/dist-packages/mrgi/__init__.py" ] ||
  fail "import mrgi found $where, not the package's /usr/lib/python3/dist-packages/mrgi"
echo "check-deb-package: python3 -c 'import mrgi' loads $where"

# Remove it again (also on failure, by the trap), and check it is gone.
cleanup
installed=0
trap - EXIT
left="$(dpkg-query -W -f='${db:Status-Status}' mrgi 2>/dev/null || true)"
if [ -n "$left" ] && [ "$left" != "not-installed" ]; then
  fail "dpkg still lists mrgi after apt-get purge (state $left)"
fi
[ ! -e /usr/bin/mrgi-render ] || fail "/usr/bin/mrgi-render is left after apt-get purge"
echo "check-deb-package: purged with apt-get purge mrgi"
