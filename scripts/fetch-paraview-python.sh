#!/usr/bin/env bash
# Unpacks Debian's python3-paraview (pvbatch's `paraview.simple`, ParaView's
# own `vtkmodules`) into a folder, WITHOUT installing it: installing it with
# apt removes libvtk9-dev and python3-vtk9 (it ships its own vtkmodules),
# after which MRGI's VTK 9.1 build and `import mrgi` break. pvbatch finds the
# unpacked files through PYTHONPATH (DEST_DIR/usr/lib/python3/dist-packages).
# The package's version must equal the installed paraview's; an unpacked
# copy of another version is replaced.
# Usage: scripts/fetch-paraview-python.sh DEST_DIR
set -euo pipefail
dest="${1:?usage: fetch-paraview-python.sh DEST_DIR}"
version="$(dpkg-query -W -f='${Version}' paraview 2>/dev/null || true)"
if [ -z "$version" ]; then
  echo "fetch-paraview-python: the paraview package is not installed (scripts/install-deps.sh)" >&2
  exit 1
fi
stamp="$dest/.python3-paraview-version"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$version" ] &&
   [ -f "$dest/usr/lib/python3/dist-packages/paraview/simple.py" ]; then
  exit 0
fi
rm -rf "$dest"
mkdir -p "$dest/deb"
# apt-get download works as any user; as root it warns that _apt cannot write
# the folder, which is harmless.
download() { (cd "$dest/deb" && apt-get download -q "python3-paraview=$version" 2>&1 | grep -v '^W: Download is performed unsandboxed' || true); }
download
if ! ls "$dest"/deb/python3-paraview_*.deb > /dev/null 2>&1; then
  # Fresh machines may have no package lists yet.
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update -qq
  download
fi
deb="$(ls "$dest"/deb/python3-paraview_*.deb 2>/dev/null | head -1 || true)"
if [ -z "$deb" ]; then
  echo "fetch-paraview-python: could not download python3-paraview=$version" >&2
  exit 1
fi
dpkg -x "$deb" "$dest"
rm -rf "$dest/deb"
echo "$version" > "$stamp"
echo "fetch-paraview-python: python3-paraview $version unpacked in $dest"
