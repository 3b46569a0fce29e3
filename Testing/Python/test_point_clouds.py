"""The `mrgi` package's point-cloud classes: with the PCL module (the VTK 9.1
build), `mrgi.vtkMRGIPCDReader()` is PCL's reader through the object
factory and reads a PCD file written here (colours, organized layout,
viewpoint); vtkMRGIPointCloudNormals adds Normals and Radius in a pipeline.
Without it, the reader refuses with a message naming the missing module."""
import math
import os
import sys

from vtkmodules.vtkCommonCore import vtkCommand

import mrgi


def check(condition, what):
    if not condition:
        print("check failed:", what, file=sys.stderr)
        sys.exit(1)


class Errors:
    def __init__(self):
        self.messages = []

    def __call__(self, obj, event, data=None):
        self.messages.append(str(data))

    __call__.CallDataType = "string0"


def write_pcd(path):
    """A 4 x 3 organized cloud, one NaN pixel, rgb, viewpoint (0, 0, 5)."""
    lines = [
        "VERSION 0.7", "FIELDS x y z rgb", "SIZE 4 4 4 4", "TYPE F F F U", "COUNT 1 1 1 1",
        "WIDTH 4", "HEIGHT 3", "VIEWPOINT 0 0 5 1 0 0 0", "POINTS 12", "DATA ascii",
    ]
    for v in range(3):
        for u in range(4):
            if (u, v) == (2, 1):
                lines.append("nan nan nan 0")
            else:
                lines.append("%g %g 0 %d" % (0.1 * u, 0.1 * v, (200 << 16) | (100 << 8) | 50))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    tmp = os.environ.get("MRGI_TEST_TMP", "/tmp")
    path = os.path.join(tmp, "test_point_clouds.pcd")
    write_pcd(path)
    reader = mrgi.vtkMRGIPCDReader()
    errors = Errors()
    reader.AddObserver(vtkCommand.ErrorEvent, errors)
    reader.SetFileName(path)
    reader.Update()
    if not hasattr(mrgi, "vtkMRGIPCLPCDReader"):
        check(reader.GetClassName() == "vtkMRGIPCDReader", "the base reader without PCL")
        check(any("MRGI::RenderingPCL" in m for m in errors.messages), "names the missing module")
        print("test_point_clouds: no PCL module in this build; the base reader refuses, as documented")
        return
    check(reader.GetClassName() == "vtkMRGIPCLPCDReader",
          "vtkMRGIPCDReader() is the PCL override, got " + reader.GetClassName())
    check(not errors.messages, "no error: %s" % errors.messages)
    out = reader.GetOutput()
    check(out.GetNumberOfPoints() == 11, "11 finite points of 12")
    check(out.GetNumberOfVerts() == 11, "one vertex each")
    rgb = out.GetPointData().GetScalars()
    check(rgb is not None and rgb.GetName() == "RGB", "RGB scalars")
    check(rgb.GetTuple3(0) == (200.0, 100.0, 50.0), "the packed colour: %s" % (rgb.GetTuple3(0),))
    dims = out.GetFieldData().GetArray("OrganizedDimensions")
    check(dims is not None and (dims.GetValue(0), dims.GetValue(1)) == (4, 3), "organized 4 x 3")
    origin = out.GetFieldData().GetArray("SensorOrigin")
    check(origin is not None and origin.GetTuple3(0) == (0.0, 0.0, 5.0), "the viewpoint")

    normals = mrgi.vtkMRGIPointCloudNormals()
    check(normals.GetClassName() == "vtkMRGIPCLPointCloudNormals", "the PCL normals")
    normals.SetInputConnection(reader.GetOutputPort())
    normals.Update()
    result = normals.GetOutput()
    n = result.GetPointData().GetNormals()
    r = result.GetPointData().GetArray("Radius")
    check(n is not None and r is not None, "Normals and Radius")
    for i in range(result.GetNumberOfPoints()):
        nz = n.GetTuple3(i)[2]
        check(abs(nz - 1.0) < 1e-3, "normal %d faces the viewpoint (+z): %s" % (i, n.GetTuple3(i)))
        check(0.0 < r.GetValue(i) < 1.0 and math.isfinite(r.GetValue(i)), "radius %d" % i)
    print("test_point_clouds: PCL reader and normals through the factory, from Python")


if __name__ == "__main__":
    main()
