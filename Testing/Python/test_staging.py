"""vtkMRGIStaging from Python, as a user stages their own data: a z-up
pedestal gets the up axis, a camera above the front, a ground and a spot
key light; the area key light goes to vtkMRGIPass and lights the image;
the scene builder stages a file it reads; a volume becomes an iso-surface."""
import os
import sys

from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersCore import vtkAppendPolyData
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkSphereSource
from vtkmodules.vtkIOPLY import vtkPLYWriter
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer
from vtkmodules.vtkRenderingOpenGL2 import vtkRenderStepsPass
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factories)

import mrgi

TMP = os.environ.get("MRGI_TEST_TMP", "/tmp")


def check(condition, what):
    if not condition:
        print("check failed:", what, file=sys.stderr)
        sys.exit(1)


def pedestal_z_up():
    """A wide slab with a ball on it, turned from y-up to z-up."""
    slab = vtkCubeSource()
    slab.SetBounds(-1, 1, 0, 0.15, -1, 1)
    ball = vtkSphereSource()
    ball.SetCenter(0, 0.8, 0)
    ball.SetRadius(0.6)
    both = vtkAppendPolyData()
    both.AddInputConnection(slab.GetOutputPort())
    both.AddInputConnection(ball.GetOutputPort())
    turn = vtkTransform()
    turn.RotateX(90)
    moved = vtkTransformPolyDataFilter()
    moved.SetInputConnection(both.GetOutputPort())
    moved.SetTransform(turn)
    moved.Update()
    return moved.GetOutput()


def main():
    data = pedestal_z_up()
    window = mrgi.vtkMRGIRenderWindowFactory.CreateHeadlessRenderWindow()
    window.SetSize(96, 72)
    renderer = vtkRenderer()
    window.AddRenderer(renderer)
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(data)
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)

    staging = mrgi.vtkMRGIStaging()
    check(staging.Stage(renderer), "Stage: " + staging.GetLastErrorMessage())
    check(staging.GetDetectedUp() == mrgi.vtkMRGIStaging.UpPositiveZ,
          "up +z, got %s (%s)" % (staging.GetUpAxisName(staging.GetDetectedUp()), staging.GetUpReason()))
    camera = renderer.GetActiveCamera()
    check(camera.GetViewUp()[2] > 0.85, "the camera's view up leans to +z")
    check(camera.GetPosition()[2] > camera.GetFocalPoint()[2], "the camera looks down at the data")
    check(staging.GetGroundActor() is not None and staging.GetKeyLightObject() is not None,
          "ground and spot key light")
    check(renderer.GetLights().GetNumberOfItems() == 1 and not renderer.GetAutomaticLightCreation(),
          "the spot is the only light; no headlight")

    # The area key light, given to the pass, lights the image.
    staging.SetKeyLight(mrgi.vtkMRGIStaging.KeyLightArea)
    check(staging.Stage(renderer), "Stage with an area light")
    area = staging.GetAreaLight()
    check(area is not None, "an area light")
    gi = mrgi.vtkMRGIPass()
    gi.SetDelegatePass(vtkRenderStepsPass())
    gi.AddAreaLight(area)
    renderer.SetPass(gi)
    window.Render()
    image = vtkImageData()
    check(gi.GetAreaLightBuffer(window, image), "the area lights' buffer")
    lit = image.GetPointData().GetScalars().GetRange(0)[1]
    print("area light's brightest pixel: %.3f" % lit)
    check(lit > 0.1, "the area light lights the data")

    # The scene builder stages what it reads.
    path = os.path.join(TMP, "staging_pedestal.ply")
    writer = vtkPLYWriter()
    writer.SetInputData(data)
    writer.SetFileName(path)
    check(writer.Write() == 1, "write " + path)
    built = vtkRenderer()
    builder = mrgi.vtkMRGISceneBuilder()
    builder.SetScene(path)
    staged = mrgi.vtkMRGIStaging()
    builder.SetStaging(staged)
    check(builder.Build(built), "Build: " + builder.GetLastErrorMessage())
    check(staged.GetDetectedUp() == mrgi.vtkMRGIStaging.UpPositiveZ, "the builder's file is staged")
    # What was staged stays when the staging object and the builder go away
    # (a scene built in a function, rendered later).
    actors_staged = built.GetActors().GetNumberOfItems()
    lights_staged = built.GetLights().GetNumberOfItems()
    del builder, staged
    staged = mrgi.vtkMRGIStaging()
    check(built.GetActors().GetNumberOfItems() == actors_staged and actors_staged == 2,
          "the data and the ground stay after the staging object is gone")
    check(built.GetLights().GetNumberOfItems() == lights_staged and lights_staged >= 1,
          "the key light stays after the staging object is gone")
    check(built.GetActors().GetNumberOfItems() == 2, "the data and the ground")

    # A volume: a ball of 1s in 0s, contoured at 0.5 (Otsu's threshold).
    volume = vtkImageData()
    volume.SetDimensions(10, 10, 10)
    volume.AllocateScalars(10, 1)  # VTK_FLOAT
    scalars = volume.GetPointData().GetScalars()
    for i in range(1000):
        x, y, z = i % 10, (i // 10) % 10, i // 100
        scalars.SetValue(i, 1.0 if (x - 4.5) ** 2 + (y - 4.5) ** 2 + (z - 4.5) ** 2 < 9 else 0.0)
    check(mrgi.vtkMRGIStaging.IsVolume(volume), "IsVolume")
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    surface = vtkPolyData()
    check(staged.MakeIsoSurface(volume, surface), "MakeIsoSurface: " + staged.GetLastErrorMessage())
    check(staged.GetLastIsoValue() == 0.5 and surface.GetNumberOfPolys() > 50,
          "iso-surface at %s with %d triangles" % (staged.GetLastIsoValue(), surface.GetNumberOfPolys()))
    print("ok")


if __name__ == "__main__":
    main()
