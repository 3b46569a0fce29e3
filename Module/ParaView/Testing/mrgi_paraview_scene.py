"""Helpers for ParaView scripts: show an MRGI scene as mrgi-render draws it.

show_mrgi_scene(view, "cornell") adds one "MRGI Scene" source per mesh of
the scene, with its material (diffuse albedo, or an emitter's radiance as
ambient colour) taken from the data, sets the view's camera to the scene's,
replaces ParaView's headlight and light kit by the scene's lights, and makes
the background black. The plugin must be loaded first (LoadPlugin
without `ns`, so that paraview.simple has MRGIScene). Everything comes from the MRGIScene source's
information properties: nothing here repeats the scene's numbers.

scene_area_lights("cornell-area") gives a scene's area lights as keyword
arguments of MRGIAreaLight; show_area_light(light, view) shows an MRGI
(Textured) Area Light as a self-luminous emitter; view_area_light_count(view)
is the number of area lights the view used in its last render,
view_area_light_updates(view) how often it read a light from changed data.
"""
from paraview import simple


def _info(proxy, name):
    """An information property's values (proxy: a source or a view)."""
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


AREA_LIGHT_FIELDS = 14  # vtkMRGISceneSource::GetAreaLightParameters()


def scene_area_lights(scene="cornell-area"):
    """The area lights of an MRGI scene as MRGIAreaLight keyword arguments.

    Read from the MRGIScene source's AreaLightParameters information property
    (what mrgi-render puts in the pass), one dict per light.
    """
    probe = simple.MRGIScene(Scene=scene)
    probe.UpdatePipelineInformation()
    values = _info(probe, "AreaLightParameters")
    simple.Delete(probe)
    lights = []
    for o in range(0, len(values), AREA_LIGHT_FIELDS):
        lights.append({
            "Center": values[o:o + 3],
            "EdgeU": values[o + 3:o + 6],
            "EdgeV": values[o + 6:o + 9],
            "Color": values[o + 9:o + 12],
            "Intensity": values[o + 12],
            "TwoSided": int(values[o + 13]),
        })
    return lights


def show_area_light(light, view):
    """Shows an MRGI (Textured) Area Light as an emitter: its Radiance as is.

    Self-luminous (ambient 1, diffuse 0: MRGI neither captures nor lights
    it) and coloured by the cell array DisplayColors with Map Scalars off,
    so the rectangle shows its colour (clamped to 1) or its picture (scaled
    to its peak), as vtkMRGIAreaLight's own emitter does.
    """
    display = simple.Show(light, view)
    display.ColorArrayName = ["CELLS", "DisplayColors"]
    display.MapScalars = 0
    display.Ambient = 1.0
    display.Diffuse = 0.0
    display.Specular = 0.0
    return display


def view_information(view, name):
    """One integer information property of the view (after a render)."""
    view.UpdatePropertyInformation()
    return int(_info(view, name)[0])


def view_area_light_count(view):
    """The view's NumberOfAreaLights information property (after a render)."""
    return view_information(view, "NumberOfAreaLights")


def view_area_light_updates(view):
    """The view's NumberOfAreaLightUpdates information property."""
    return view_information(view, "NumberOfAreaLightUpdates")
