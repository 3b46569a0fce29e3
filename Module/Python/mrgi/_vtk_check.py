"""Refuses to load MRGI's compiled modules under a VTK they were not built for.

MRGI's extension modules link one VTK's libraries (e.g. Debian's
``libvtkCommonCore-9.1.so.1``) and its ``libvtkWrappingPythonCore``. Under
another VTK's ``vtkmodules`` (ParaView 5.11's VTK 9.2 in pvbatch) the
process ends up with two copies of VTK: the second ``vtkWrappingPythonCore``
was never initialized by its own ``vtkmodules.vtkCommonCore``, so the first
wrapped MRGI class dereferences its NULL type map and the interpreter dies
of SIGSEGV (``vtkPythonUtil::AddSpecialTypeToMap``). A Python exception
instead needs a check before any of MRGI's libraries is loaded, from what
costs nothing to read: ``vtkmodules.__version__`` (pure Python) and the
libraries already mapped into the process (``/proc/self/maps``).

Contract: ``check(build_info)`` returns None when the running ``vtkmodules``
is the VTK recorded in ``build_info`` (``VTK_VERSION``, the exact version
string VTK's CMake package reported) and no other VTK's CommonCore library
is loaded; otherwise it raises ImportError naming both VTKs and what to do.
It imports only the ``vtkmodules`` package itself (no compiled module) when
that package has ``__version__``.
"""

import os
import re

_DOC = "Documentation/ParaView-Python.md"
_COMMON_CORE = re.compile(r"(libvtkCommonCore-[^/\s]*?\.so)(\.[0-9.]+)?$")


def _paraview_beside(vtkmodules_dir):
    """ParaView's version when a `paraview` package sits beside vtkmodules."""
    init = os.path.join(os.path.dirname(vtkmodules_dir), "paraview", "__init__.py")
    try:
        with open(init, encoding="utf-8") as f:
            text = f.read(8192)
    except OSError:
        return None
    m = re.search(r"^__version__\s*=\s*['\"]([^'\"]+)['\"]", text, re.M)
    return m.group(1) if m else "?"


def _running_vtk():
    """(version, description) of the vtkmodules this interpreter imports."""
    try:
        import vtkmodules
    except ImportError as e:
        raise ImportError(
            "mrgi needs VTK's Python package `vtkmodules` (Debian: python3-vtk9), "
            "and this Python cannot import it: %s" % e) from None
    version = getattr(vtkmodules, "__version__", None)
    if version is None:
        # Older VTKs: the compiled vtkCommonCore of the running VTK itself.
        from vtkmodules.vtkCommonCore import vtkVersion
        version = vtkVersion.GetVTKVersion()
    where = os.path.dirname(os.path.abspath(vtkmodules.__file__))
    paraview = _paraview_beside(where)
    owner = "ParaView %s's, " % paraview if paraview else ""
    return str(version), "%s%s" % (owner, where)


def _loaded_common_cores(maps="/proc/self/maps"):
    """Paths of the libvtkCommonCore libraries mapped into this process."""
    found = set()
    try:
        with open(maps, encoding="utf-8", errors="replace") as f:
            for line in f:
                path = line.rstrip("\n").split(None, 5)[-1]
                if "libvtkCommonCore-" in path and _COMMON_CORE.search(path):
                    found.add(path)
    except OSError:
        pass  # not Linux: the version check alone
    return sorted(found)


def _advice(build_info):
    if build_info.PARAVIEW_VERSION:
        return ("use this mrgi under ParaView %s's Python (pvbatch or python3 with "
                "ParaView's vtkmodules first on PYTHONPATH), or the mrgi "
                "built against Debian's VTK under /usr/bin/python3; see %s"
                % (build_info.PARAVIEW_VERSION, _DOC))
    return ("use the mrgi built against ParaView's VTK "
            "(scripts/check-paraview-vtk.sh builds it), or run Debian's /usr/bin/python3 "
            "without ParaView's vtkmodules on PYTHONPATH; see %s" % _DOC)


def _built_for(build_info):
    if build_info.PARAVIEW_VERSION:
        return "VTK %s (ParaView %s's)" % (build_info.VTK_VERSION, build_info.PARAVIEW_VERSION)
    return "VTK %s" % build_info.VTK_VERSION


def check_loaded_libraries(build_info, maps="/proc/self/maps"):
    """Raises ImportError when another VTK's CommonCore is in the process."""
    ours = build_info.VTK_COMMON_CORE_SONAME  # e.g. libvtkCommonCore-9.1.so.1
    stem = _COMMON_CORE.search(ours)
    if not stem:
        return
    foreign = [p for p in _loaded_common_cores(maps)
               if _COMMON_CORE.search(os.path.basename(p)).group(1) != stem.group(1)]
    if foreign:
        raise ImportError(
            "mrgi: this mrgi was built for %s (%s); this process has already loaded "
            "another VTK's %s, and a second VTK in one process crashes: %s"
            % (_built_for(build_info), ours, ", ".join(foreign), _advice(build_info)))


def check(build_info):
    """Raises ImportError unless the running VTK is the one mrgi was built for."""
    running, where = _running_vtk()
    if running != build_info.VTK_VERSION:
        raise ImportError(
            "mrgi: this mrgi was built for %s; the running vtkmodules is VTK %s (%s). "
            "Loading it would put two VTKs in one process and crash: %s"
            % (_built_for(build_info), running, where, _advice(build_info)))
    check_loaded_libraries(build_info)
