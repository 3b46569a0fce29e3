#!/usr/bin/env bash
# Installs every Debian 12 package MRGI needs to build, test and run headless.
# Idempotent: packages already present are skipped; `apt-get update` runs at
# most once per invocation, and only when something is missing.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libvtk9-dev python3-vtk9 vtk9
  # The ParaView plugin (Module/ParaView): ParaView 5.11 and its headers,
  # pvbatch under MPI, Xvfb for the GUI test (xvfb-run needs xauth).
  paraview paraview-dev openmpi-bin xvfb xauth
  libopenexr-dev libembree-dev libpng-dev zlib1g-dev
  libegl-dev libegl-mesa0 libgl1-mesa-dri libgl-dev libglew-dev
  libosmesa6 # vtkMRGIOSMesaRenderWindow dlopens libOSMesa.so.8; no header needed
  python3 python3-numpy
  # The sanitizer and fuzzing tree (sanitize.*, fuzz.*): clang, libFuzzer and
  # the sanitizer runtimes, llvm-symbolizer for readable reports.
  clang libclang-rt-14-dev llvm-14
  # install.DebPackage: cpack -G DEB computes Depends with dpkg-shlibdeps,
  # which CPack runs only when `file` is there.
  dpkg-dev file
  # MRGI::RenderingPCL (Rendering/PCL, VTK 9.1 build only): PCD files and
  # normals through the Point Cloud Library 1.13.
  libpcl-dev
)
# `install-deps.sh --benchmarks` adds what Testing/Benchmarks needs (plots).
if [ "${1:-}" = "--benchmarks" ]; then
  PACKAGES+=(python3-matplotlib)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
