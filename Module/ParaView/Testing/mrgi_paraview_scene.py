"""Helpers for ParaView scripts: show an MRGI scene as mrgi-render draws it.

show_mrgi_scene(view, "cornell") adds one "MRGI Scene" source per mesh of
the scene, with its material (diffuse albedo, or an emitter's radiance as
ambient colour) taken from the data, sets the view's camera to the scene's,
replaces ParaView's headlight and light kit by the scene's lights, and makes
the background black. The plugin must be loaded first (LoadPlugin
without `ns`, so that paraview.simple has MRGIScene). Everything comes from the MRGIScene source's
information properties: nothing here repeats the scene's numbers.
"""
from paraview import simple


def _info(proxy, name):
    prop = proxy.SMProxy.GetProperty(name)
    return [prop.GetElement(i) for i in range(prop.GetNumberOfElements())]


def _field_rgb(proxy, name):
    array = proxy.FieldData[name]
    return [array.GetRange(c)[0] for c in range(3)]


def show_mrgi_scene(view, scene="cornell"):
    """Shows `scene` in `view` as mrgi-render would draw it; returns the sources."""
    probe = simple.MRGIScene(Scene=scene)
    probe.UpdatePipelineInformation()
    mesh_count = int(_info(probe, "NumberOfMeshes")[0])
    if mesh_count < 1:
        raise RuntimeError("MRGI scene %r has no meshes (see the error above)" % scene)
    sources = []
    for index in range(mesh_count):
        source = simple.MRGIScene(Scene=scene, MeshIndex=index)
        source.UpdatePipeline()
        display = simple.Show(source, view)
        display.ColorArrayName = [None, ""]
        albedo = _field_rgb(source, "Albedo")
        emission = _field_rgb(source, "Emission")
        display.Specular = 0.0
        if max(emission) > 0.0:
            display.Ambient = 1.0
            display.Diffuse = 0.0
            display.AmbientColor = emission
            display.DiffuseColor = emission
        else:
            display.Ambient = 0.0
            display.Diffuse = 1.0
            display.AmbientColor = albedo
            display.DiffuseColor = albedo
        sources.append(source)

    view.CameraPosition = _info(probe, "CameraPosition")
    view.CameraFocalPoint = _info(probe, "CameraFocalPoint")
    view.CameraViewUp = _info(probe, "CameraViewUp")
    view.CameraViewAngle = _info(probe, "CameraViewAngle")[0]
    view.CameraParallelProjection = 0
    # paraview.simple resets the camera at a view's first render; keep the scene's.
    simple._DisableFirstRenderCameraReset()

    # Only the scene's lights: ParaView's light kit (its headlight included) off.
    view.UseLight = 0
    values = _info(probe, "LightParameters")
    for offset in range(0, len(values), 13):
        light = simple.AddLight(view=view)
        light.Coords = "Scene"
        light.Type = "Positional" if values[offset] else "Directional"
        light.Position = values[offset + 1:offset + 4]
        light.FocalPoint = values[offset + 4:offset + 7]
        light.DiffuseColor = values[offset + 7:offset + 10]
        light.Intensity = values[offset + 10]
        light.ConeAngle = values[offset + 11]

    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    return sources
