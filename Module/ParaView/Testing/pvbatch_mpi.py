"""pvbatch under MPI: the Cornell box split across ranks, IceT compositing.

usage: mpirun -np N pvbatch --disable-xdisplay-test pvbatch_mpi.py OUT.png [SIZE] [--indirect full]
The plugin comes from PV_PLUGIN_PATH (every rank must load it). Each mesh of
the scene is one MRGIScene source whose mesh lives on rank (index mod N):
the data is partitioned, each rank renders and lights its piece, and IceT
composites by depth. Prints the ranks and the bytes this rank (0) sent
compositing the reflective shadow maps.
"""
import os
import sys

from paraview import servermanager, simple

out = sys.argv[1]
size = int(sys.argv[2]) if len(sys.argv) > 2 and sys.argv[2].isdigit() else 256
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mrgi_paraview_scene import show_mrgi_scene  # noqa: E402

view = simple.CreateView("MRGIRenderView")
view.ViewSize = [size, size]
view.UseFXAA = 0
if "--indirect" in sys.argv and sys.argv[sys.argv.index("--indirect") + 1] == "full":
    view.IndirectMode = 1
show_mrgi_scene(view, "cornell")
simple.Render(view)
simple.SaveScreenshot(out, view, ImageResolution=[size, size])
view.UpdatePropertyInformation()
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
sent = view.SMProxy.GetProperty("RSMCompositeBytes").GetElement(0)
print("pvbatch_mpi: ranks=%d rsm_composite_bytes=%d wrote %s" % (ranks, sent, out))
