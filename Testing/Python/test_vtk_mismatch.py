"""`import mrgi` under a VTK it was not built for is an ImportError that names
both VTKs, never a crash (Documentation/ParaView-Python.md).

Each case imports mrgi in a child process and requires exit status 1 (an
uncaught ImportError), not a signal, with the message naming the VTK mrgi
was built for and the one that runs:

1. a `vtkmodules` package of another version first on PYTHONPATH (a stand-in
   written here: the version check needs nothing else);
2. ParaView 5.11's real `vtkmodules` (python3-paraview, unpacked, never
   installed) first on PYTHONPATH: before the check this was SIGSEGV;
3. Debian's own vtkmodules, but ParaView's libvtkCommonCore already loaded
   in the process (what pvbatch looks like when its PYTHONPATH misses
   ParaView's vtkmodules);
4. pvbatch itself (when installed), with ParaView's vtkmodules;
and, the other way round, the check accepts the VTK mrgi was built for, and
refuses Debian's VTK for an mrgi built against ParaView's.

Environment: PYTHONPATH holds this build's mrgi; MRGI_PARAVIEW_PYTHON is
the folder where scripts/fetch-paraview-python.sh unpacks python3-paraview
(cases 2 and 4 fetch it there; they are skipped, with a line saying so,
only when the paraview package is not installed).
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
MRGI_PATH = os.environ["PYTHONPATH"]
failures = []


def check(condition, what):
    print(("ok: " if condition else "FAILED: ") + what)
    if not condition:
        failures.append(what)


def build_info():
    """The VTK this mrgi records, read as text (no import of mrgi here)."""
    for folder in MRGI_PATH.split(os.pathsep):
        path = os.path.join(folder, "mrgi", "_build_info.py")
        if os.path.isfile(path):
            with open(path, encoding="utf-8") as f:
                text = f.read()
            return dict(re.findall(r'^(\w+) = "([^"]*)"', text, re.M))
    sys.exit("test_vtk_mismatch: no mrgi/_build_info.py on PYTHONPATH=%s" % MRGI_PATH)


def run(argv, pythonpath, what, timeout=120):
    env = dict(os.environ, PYTHONPATH=pythonpath)
    env.pop("DISPLAY", None)
    proc = subprocess.run(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          timeout=timeout, check=False)
    out = proc.stdout.decode("utf-8", "replace")
    print("--- %s: exit status %d" % (what, proc.returncode))
    print("\n".join(out.strip().splitlines()[-3:]))
    return proc.returncode, out


def expect_refusal(argv, pythonpath, what, names):
    code, out = run(argv, pythonpath, what)
    check(code > 0, "%s: exits with a status, not a signal (got %d)" % (what, code))
    check("ImportError: mrgi: this mrgi was built for" in out, "%s: ImportError from mrgi" % what)
    for name in names:
        check(name in out, "%s: the message names %r" % (what, name))
    check("Documentation/ParaView-Python.md" in out, "%s: the message says where to read on" % what)


def paraview_python():
    """ParaView's site directory (python3-paraview unpacked), or None."""
    if shutil.which("pvbatch") is None:
        print("skip: paraview is not installed (pvbatch absent): no ParaView vtkmodules")
        return None
    dest = os.environ["MRGI_PARAVIEW_PYTHON"]
    subprocess.run(["bash", os.path.join(ROOT, "scripts", "fetch-paraview-python.sh"), dest],
                   check=True)
    return os.path.join(dest, "usr", "lib", "python3", "dist-packages")


def paraview_vtk_version(site):
    with open(os.path.join(site, "vtkmodules", "__init__.py"), encoding="utf-8") as f:
        return re.search(r'^__version__ = "([^"]+)"', f.read(), re.M).group(1)


def main():
    info = build_info()
    built = info["VTK_VERSION"]
    python = sys.executable
    print("mrgi built for VTK %s (%s)" % (built, info["VTK_COMMON_CORE_SONAME"]))

    # The right VTK: accepted.
    code, _ = run([python, "-c", "import mrgi; mrgi.vtkMRGIPass()"], MRGI_PATH, "same VTK")
    check(code == 0, "same VTK: import mrgi succeeds")

    # 1. Another vtkmodules version (a stand-in package).
    with tempfile.TemporaryDirectory() as fake:
        os.mkdir(os.path.join(fake, "vtkmodules"))
        with open(os.path.join(fake, "vtkmodules", "__init__.py"), "w", encoding="utf-8") as f:
            f.write('__version__ = "8.2.0"\n')
        expect_refusal([python, "-c", "import mrgi"], fake + os.pathsep + MRGI_PATH,
                       "stand-in vtkmodules 8.2.0", ["VTK " + built, "VTK 8.2.0"])

    # The reverse: an mrgi built against ParaView's VTK, under this VTK.
    code, out = run([python, "-c", (
        "import types\n"
        "from mrgi import _vtk_check\n"
        "_vtk_check.check(types.SimpleNamespace(VTK_VERSION='9.2.20230111',\n"
        "    VTK_COMMON_CORE_SONAME='libvtkCommonCore-pv5.11.so.1', PARAVIEW_VERSION='5.11'))\n")],
        MRGI_PATH, "ParaView-built mrgi under VTK %s" % built)
    check(code == 1 and "built for VTK 9.2.20230111 (ParaView 5.11's)" in out
          and "running vtkmodules is VTK %s" % built in out,
          "ParaView-built mrgi under VTK %s: refused, naming both" % built)

    site = paraview_python()
    if site is not None and "pv" not in info["VTK_COMMON_CORE_SONAME"]:
        pv_vtk = paraview_vtk_version(site)
        # 2. ParaView's vtkmodules first on PYTHONPATH (was SIGSEGV).
        expect_refusal([python, "-c", "import mrgi"], site + os.pathsep + MRGI_PATH,
                       "ParaView's vtkmodules", ["VTK " + built, "VTK " + pv_vtk, "ParaView"])
        # 3. ParaView's CommonCore already in the process, Debian's vtkmodules.
        expect_refusal([python, "-c", "import ctypes; ctypes.CDLL('libvtkCommonCore-pv5.11.so.1');"
                        " import mrgi"], MRGI_PATH, "ParaView's libvtkCommonCore loaded",
                       ["VTK " + built, "libvtkCommonCore-pv5.11"])
        # 4. pvbatch: importing needs no render window, so no X server either.
        with tempfile.TemporaryDirectory() as tmp:
            script = os.path.join(tmp, "import_mrgi.py")
            with open(script, "w", encoding="utf-8") as f:
                f.write("import mrgi\n")
            expect_refusal(["pvbatch", script], site + os.pathsep + MRGI_PATH,
                           "pvbatch", ["VTK " + built, "VTK " + pv_vtk])

    if failures:
        print("%d check(s) failed" % len(failures), file=sys.stderr)
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
