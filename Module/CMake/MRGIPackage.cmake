# `cpack -G DEB` in the build tree: mrgi_<version>_amd64.deb for Debian 12,
# installed under /usr. Everything `cmake --install` installs goes in one
# package: programs, libraries, headers, CMake files, and the Python package
# in lib/python3/dist-packages, where Debian's python3 finds it (the default
# configuration; a prefix of /usr at configure time would move libraries to
# lib/x86_64-linux-gnu, so the package is made from the default tree with
# CPACK_PACKAGING_INSTALL_PREFIX). Installed files find MRGI's libraries
# through their $ORIGIN run paths. Checked by ctest install.DebPackage
# (scripts/check-deb-package.sh).
set(CPACK_PACKAGE_NAME "mrgi")
set(CPACK_PACKAGE_VENDOR "MRGI")
set(CPACK_PACKAGE_CONTACT "MRGI developers")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "Multiresolution one-bounce indirect light and area lights for VTK")
set(CPACK_PACKAGE_DESCRIPTION
  "VTK render passes (vtkMRGIPass) that add interactive one-bounce indirect light and textured area lights, a headless EGL window, the mrgi-render command line and the Python package mrgi.")
set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
set(CPACK_GENERATOR "DEB")
set(CPACK_DEBIAN_FILE_NAME "DEB-DEFAULT") # mrgi_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION "graphics")
# Depends: what dpkg-shlibdeps finds the ELF files need (VTK, OpenEXR,
# libpng, Embree, EGL, ...), plus the Python side `import mrgi` needs.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3, python3-vtk9")
include(CPack)
