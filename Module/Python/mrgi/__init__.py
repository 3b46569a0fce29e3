"""MRGI: multiresolution one-bounce indirect light and area lighting for VTK.

Usage (the same three lines as vtkSSAOPass)::

    from vtkmodules.vtkRenderingOpenGL2 import vtkRenderStepsPass
    import mrgi
    steps = vtkRenderStepsPass()
    gi = mrgi.vtkMRGIPass()
    gi.SetDelegatePass(steps)
    renderer.SetPass(gi)

Headless rendering without X: ``mrgi.vtkMRGIRenderWindowFactory.CreateHeadlessRenderWindow()``.
"""

# Before any compiled module of MRGI loads: under another VTK's vtkmodules
# (e.g. ParaView's in pvbatch) MRGI's libraries would bring a second VTK into
# the process, which crashes; fail with an ImportError that says so instead.
from . import _build_info, _vtk_check

_vtk_check.check(_build_info)

# VTK's OpenGL object factories must be registered before any window exists.
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkInteractionStyle  # noqa: F401

_vtk_check.check_loaded_libraries(_build_info)

from .MRGIRendering import *  # noqa: F401,F403
from .MRGIRenderingHeadless import *  # noqa: F401,F403
from .MRGIRenderingIO import *  # noqa: F401,F403
from .MRGIRenderingValidation import *  # noqa: F401,F403
from .MRGIRenderingParallel import *  # noqa: F401,F403
# PCD files and PCL normals (the VTK 9.1 build only): importing the module
# registers its overrides of vtkMRGIPCDReader and vtkMRGIPointCloudNormals.
import importlib.util as _importlib_util

if _importlib_util.find_spec(__name__ + ".MRGIRenderingPCL") is not None:
    from .MRGIRenderingPCL import *  # noqa: F401,F403
