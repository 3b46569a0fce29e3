"""Point clouds as surfels, measured: the same surface as a mesh and as a cloud
sampled from it, and the cost of a cloud as it grows.

mesh-vs-cloud: the object (the Stanford bunny from ../shared/data, or a
sphere made here) on the floor of the Cornell box lit by the spot, drawn once
as its mesh (flat triangles) and once as a cloud of N points sampled from the
mesh (vtkMRGIMeshSampler, uniform by area, the triangle's normal) drawn as
surfels (vtkMRGISurfels). Reports
  - indirect: the relative RMS error of the cloud's indirect light against the
    mesh's, both averaged over 4x4-pixel boxes (C core metrics, mrgi-compare);
  - silhouette: the object alone, coverage from the depth buffer; the boundary
    of a mask is its covered pixels with an uncovered 4-neighbour; each
    boundary pixel's distance to the other mask's boundary, both ways
    (symmetric): the maximum (Hausdorff distance, pixels), the mean, and the
    pixels covered by one mask only.
With --check REL,PIXELS it exits 1 unless indirect <= REL (over the image and
over the boxes near the object) and silhouette max <= PIXELS (the ctest
python.PointCloudMeshVsCloud).

truth: the CPU ground truth (vtkMRGIReferenceRenderer, Embree) of the mesh
and of the cloud as surfels, direct and indirect light compared on 4x4 boxes
(--check REL: the ctest python.PointCloudGroundTruth).

scaling: the same scene with clouds of 1e5, 1e6, 1e7 points at the same screen
coverage; per count: surfel build (ms), first frame (upload and first draw),
and medians over repeats of the frame with GI off, with GI on in steady state
(nothing changed: the RSM is reused) and cold (the light moved: the RSM is
drawn again), the GPU stage times "scene" and "rsm", and ms per million points.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Testing/Benchmarks/point_cloud.py mesh-vs-cloud --object bunny --size 256 --points 1000000
    ... point_cloud.py scaling --counts 100000,1000000,10000000 --size 256
    ... point_cloud.py pictures --out Documentation/images
"""
import argparse
import os
import shutil
import statistics
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import mrgi_bench as mb  # noqa: E402

from vtkmodules.vtkCommonCore import vtkFloatArray  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402
from vtkmodules.vtkFiltersSources import vtkSphereSource  # noqa: E402
from vtkmodules.vtkIOPLY import vtkPLYReader  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper  # noqa: E402

import mrgi  # noqa: E402

COMPARE = os.environ.get("MRGI_COMPARE", os.path.join(mb.ROOT, "build", "bin", "mrgi-compare"))


def object_source(name):
    """(algorithm giving the mesh in its own units, description); None when the file is absent."""
    if name == "bunny":
        path = os.path.join(mb.SHARED_DATA, "bunny.ply")
        if not os.path.exists(path):
            return None
        reader = vtkPLYReader()
        reader.SetFileName(path)
        return reader, "the Stanford bunny (69,451 triangles)"
    sphere = vtkSphereSource()
    sphere.SetRadius(0.1)
    sphere.SetThetaResolution(48)
    sphere.SetPhiResolution(48)
    sphere.GenerateNormalsOff()  # flat triangles, as the cloud's normals are
    return sphere, "a sphere (4,416 flat triangles)"


def place(actor, bounds):
    """Metres to the box's millimetres, standing on the floor in front of the tall block."""
    actor.SetScale(1000.0)
    actor.SetPosition(430.0 - 1000.0 * 0.5 * (bounds[0] + bounds[1]), -1000.0 * bounds[2],
                      130.0 - 1000.0 * 0.5 * (bounds[4] + bounds[5]))
    prop = actor.GetProperty()
    prop.SetColor(0.725, 0.71, 0.68)
    prop.SetAmbient(0.0)
    prop.SetDiffuse(1.0)
    prop.SetSpecular(0.0)


def object_actor(source, points=0, surfels=True, seed=1, radius_scale=1.0, max_surfels=0):
    """The mesh (points = 0) or a cloud of `points` samples as surfels (or as pixels)."""
    source.Update()
    bounds = source.GetOutput().GetBounds()
    mapper = vtkPolyDataMapper()
    mapper.ScalarVisibilityOff()
    info = {}
    if points:
        sampler = mrgi.vtkMRGIMeshSampler()
        sampler.SetInputConnection(source.GetOutputPort())
        sampler.SetNumberOfPoints(points)
        sampler.SetSeed(seed)
        sampler.Update()
        info["radius"] = sampler.GetSampledRadius()
        if surfels:
            filt = mrgi.vtkMRGISurfels()
            filt.SetInputConnection(sampler.GetOutputPort())
            filt.SetRadiusScale(radius_scale)
            filt.SetMaximumNumberOfSurfels(max_surfels)
            start = time.perf_counter()
            filt.Update()
            info["build_ms"] = (time.perf_counter() - start) * 1e3
            output = filt.GetOutput()
            info["bytes"] = output.GetActualMemorySize() * 1024
            mapper.SetInputData(output)
        else:
            mapper.SetInputData(sampler.GetOutput())
    else:
        mapper.SetInputConnection(source.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    place(actor, bounds)
    return actor, info


SCENE = "cornell-spot"  # the built-in scene the object stands in (--scene)


def scene(size, actor, gi=True):
    window, renderer = mb.make_window(size, size)
    assert mb.build_scene(renderer, SCENE)
    renderer.AddActor(actor)
    gi_pass = mb.install_pass(renderer, IndirectMode=2 if gi else 0)
    return window, renderer, gi_pass


def indirect(window, gi_pass):
    window.Render()
    image = vtkImageData()
    assert gi_pass.GetIndirectBuffer(window, image)
    return mb.to_numpy(image)[..., :3]


def coverage(size, actor):
    """The object alone, no MRGI: covered pixels from the depth buffer (rows top-down)."""
    window, renderer = mb.make_window(size, size)
    assert mb.build_scene(renderer, SCENE)  # the same camera as the lit scene
    for prop in list(renderer.GetViewProps()):
        renderer.RemoveViewProp(prop)
    renderer.AddActor(actor)
    window.Render()
    depth = vtkFloatArray()
    window.GetZbufferData(0, 0, size - 1, size - 1, depth)
    z = np.frombuffer(memoryview(depth), dtype=np.float32).reshape(size, size)[::-1]
    renderer.RemoveActor(actor)
    return z < 1.0


def boundary(mask):
    padded = np.pad(mask, 1, constant_values=False)
    inner = padded[1:-1, 1:-1] & padded[:-2, 1:-1] & padded[2:, 1:-1] & padded[1:-1, :-2] & padded[1:-1, 2:]
    return np.argwhere(mask & ~inner).astype(np.float64)


def nearest(a, b):
    """Distance from each point of a to the nearest of b (chunked brute force)."""
    out = np.empty(len(a))
    for i in range(0, len(a), 512):
        d = ((a[i:i + 512, None, :] - b[None, :, :]) ** 2).sum(axis=2)
        out[i:i + 512] = np.sqrt(d.min(axis=1))
    return out


def silhouette(mask_mesh, mask_cloud):
    a, b = boundary(mask_mesh), boundary(mask_cloud)
    if len(a) == 0 or len(b) == 0:
        return {"max": float("inf"), "mean": float("inf"), "xor": int((mask_mesh ^ mask_cloud).sum())}
    d = np.concatenate([nearest(a, b), nearest(b, a)])
    return {"max": float(d.max()), "mean": float(d.mean()), "p99": float(np.percentile(d, 99)),
            "xor": int((mask_mesh ^ mask_cloud).sum()), "covered": int(mask_mesh.sum())}


def view_budget(source, size, surfels_per_pixel):
    """vtkMRGISurfels.SuggestMaximumNumberOfSurfels for the object in the scene's view (0: none)."""
    if not surfels_per_pixel:
        return 0
    mesh, _ = object_actor(source)
    window, renderer, gi = scene(size, mesh, gi=False)
    window.Render()
    return mrgi.vtkMRGISurfels.SuggestMaximumNumberOfSurfels(renderer, mesh, surfels_per_pixel)


def mesh_vs_cloud(args):
    made = object_source(args.object)
    if made is None:
        print("mesh-vs-cloud: %s is not in %s: skipped" % (args.object, mb.SHARED_DATA))
        return 0
    source, description = made
    tmp = tempfile.mkdtemp(prefix="mrgi-point-cloud-")
    results = {}
    for size in args.sizes:
        mesh, _ = object_actor(source)
        budget = view_budget(source, size, args.surfels_per_pixel) or args.max_surfels
        if budget:
            print("surfel budget %d" % budget)
        cloud, info = object_actor(source, args.points, radius_scale=args.radius_scale,
                                   max_surfels=budget)
        window, renderer, gi = scene(size, mesh)
        e_mesh = indirect(window, gi)
        renderer.RemoveActor(mesh)
        renderer.AddActor(cloud)
        e_cloud = indirect(window, gi)
        mb.write(mb.boxes(e_mesh), os.path.join(tmp, "mesh.exr"))
        mb.write(mb.boxes(e_cloud), os.path.join(tmp, "cloud.exr"))
        metrics = mb.compare(COMPARE, os.path.join(tmp, "cloud.exr"), os.path.join(tmp, "mesh.exr"))
        assert np.isfinite(e_cloud).all(), "NaN in the cloud's indirect light"
        mask_mesh = coverage(size, mesh)
        sil = silhouette(mask_mesh, coverage(size, cloud))
        # The same error on the boxes within 16 pixels of the object's bounding box only,
        # where the object's own indirect light and its bounce onto the floor are.
        rows, cols = np.nonzero(mask_mesh)
        y0, y1 = max(rows.min() - 16, 0) // 4, (rows.max() + 16) // 4 + 1
        x0, x1 = max(cols.min() - 16, 0) // 4, (cols.max() + 16) // 4 + 1
        near_mesh, near_cloud = mb.boxes(e_mesh)[y0:y1, x0:x1], mb.boxes(e_cloud)[y0:y1, x0:x1]
        near = float(np.sqrt(((near_cloud - near_mesh) ** 2).sum() / (near_mesh ** 2).sum()))
        results[size] = (max(metrics["relative_rms"], near), sil)
        print("mesh-vs-cloud %dx%d, %s, %d points (radius %.3g, scale %.2g): indirect light on 4x4 "
              "boxes relative RMS %.4f (%.4f near the object); silhouette max %.2f px, mean %.3f px, "
              "p99 %.2f px, %d of %d covered pixels differ; surfels built in %.0f ms, %.1f MB"
              % (size, size, description, args.points, info["radius"], args.radius_scale,
                 metrics["relative_rms"], near,
                 sil["max"], sil["mean"], sil.get("p99", 0), sil["xor"], sil.get("covered", 0),
                 info["build_ms"], info["bytes"] / 1e6))
    shutil.rmtree(tmp, ignore_errors=True)
    if args.check:
        limit_rel, limit_px = (float(v) for v in args.check.split(","))
        failed = [s for s, (rel, sil) in results.items() if not (rel <= limit_rel and sil["max"] <= limit_px)]
        if failed:
            print("FAILED: indirect relative RMS above %g or silhouette above %g px at %s"
                  % (limit_rel, limit_px, failed))
            return 1
        print("passed: indirect relative RMS <= %g and silhouette <= %g px" % (limit_rel, limit_px))
    return 0


CPU_MS = []  # process CPU time of each frame_ms() call, in order


def frame_ms(window):
    """Wall ms of one frame; its process CPU ms (llvmpipe's threads included) go to CPU_MS."""
    start, cpu = time.perf_counter(), time.process_time()
    window.Render()
    window.GetPixelData(0, 0, 0, 0, 0, 0)  # waits for the frame
    CPU_MS.append((time.process_time() - cpu) * 1e3)
    return (time.perf_counter() - start) * 1e3


def stage_times(window, gi):
    return {gi.GetStageName(i): gi.GetStageTimeMilliseconds(i) for i in range(gi.FetchStageTimings(window, True))}


def scaling(args):
    made = object_source(args.object)
    source, description = made if made else object_source("sphere")
    budget = view_budget(source, args.size, args.surfels_per_pixel) or args.max_surfels
    print("scaling: %s on the Cornell floor, %dx%d, medians of %d repeats (ms), surfel budget %s%s"
          % (description, args.size, args.size, args.repeats, budget or "none",
             " (%g surfels per pixel of the object's box, SuggestMaximumNumberOfSurfels)"
             % args.surfels_per_pixel if args.surfels_per_pixel else ""))
    header = ("points,build_ms,first_frame_ms,off_ms,steady_ms,cold_ms,overhead_steady_ms,overhead_cold_ms,"
              "scene_ms,rsm_ms,bytes,min_off_ms,min_steady_ms,min_cold_ms,cpu_off_ms,cpu_steady_ms,cpu_cold_ms")
    print(header)
    rows = []
    for count in args.counts:
        actor, info = object_actor(source, count, max_surfels=budget)
        window, renderer, gi = scene(args.size, actor)
        gi.SetStageTimingEnabled(True)
        window.GetRenderTimer().SetLoggingEnabled(True)
        first = frame_ms(window)
        light = renderer.GetLights().GetItemAsObject(0)
        off, steady, cold, scene_ms, rsm_ms = [], [], [], [], []
        cpu_off, cpu_steady, cpu_cold = [], [], []
        frame_ms(window)
        for r in range(args.repeats):
            gi.SetIndirectMode(0)
            off.append(frame_ms(window))
            cpu_off.append(CPU_MS[-1])
            stage_times(window, gi)
            gi.SetIndirectMode(2)
            frame_ms(window)  # the first frame back re-renders what GI off skipped
            stage_times(window, gi)
            steady.append(frame_ms(window))
            cpu_steady.append(CPU_MS[-1])
            scene_ms.append(stage_times(window, gi).get("scene", 0.0))
            light.SetIntensity(light.GetIntensity() * (1.0001 if r % 2 else 0.9999))  # the RSM is drawn again
            cold.append(frame_ms(window))
            cpu_cold.append(CPU_MS[-1])
            rsm_ms.append(stage_times(window, gi).get("rsm", 0.0))
        row = [count, info["build_ms"], first, statistics.median(off), statistics.median(steady),
               statistics.median(cold), statistics.median(steady) - statistics.median(off),
               statistics.median(cold) - statistics.median(off), statistics.median(scene_ms),
               statistics.median(rsm_ms), info["bytes"], min(off), min(steady), min(cold),
               statistics.median(cpu_off), statistics.median(cpu_steady), statistics.median(cpu_cold)]
        rows.append(row)
        print(",".join("%.6g" % v for v in row))
        renderer.RemoveAllViewProps()
        del window, renderer, gi, actor
    print("per million points (ms): " + "; ".join(
        "%d: build %.1f, first frame %.1f, scene %.1f, rsm %.1f" % (r[0], r[1] / r[0] * 1e6, r[2] / r[0] * 1e6,
                                                                   r[8] / r[0] * 1e6, r[9] / r[0] * 1e6) for r in rows))
    if len(rows) > 1:
        # Medians as asked; minima too: on a shared machine the least disturbed frame is the
        # better estimate of the work itself.
        for name, first, last in (("steady, medians", rows[0][6], rows[-1][6]),
                                  ("cold, medians", rows[0][7], rows[-1][7]),
                                  ("steady, minima", rows[0][12] - rows[0][11], rows[-1][12] - rows[-1][11]),
                                  ("cold, minima", rows[0][13] - rows[0][11], rows[-1][13] - rows[-1][11]),
                                  ("steady, CPU ms", rows[0][15] - rows[0][14], rows[-1][15] - rows[-1][14]),
                                  ("cold, CPU ms", rows[0][16] - rows[0][14], rows[-1][16] - rows[-1][14])):
            growth = last / first if first > 0 else float("inf")
            print("GI overhead (%s) from %d to %d points: %.1f -> %.1f ms, x%.2f (target <= 1.5)"
                  % (name, rows[0][0], rows[-1][0], first, last, growth))
    print("load average at the end: %.2f %.2f %.2f" % os.getloadavg())
    return 0


def pictures(args):
    made = object_source(args.object)
    source, description = made if made else object_source("sphere")
    for name, points, surfels in (("mesh", 0, True), ("pixels", args.points, False), ("surfels", args.points, True)):
        actor, _ = object_actor(source, points, surfels)
        window, renderer, gi = scene(args.size, actor, gi=not args.gi_off)
        if args.zoom > 1.0:
            # Closer to the object, so a pixel is smaller than the points' spacing.
            bounds = actor.GetBounds()
            camera = renderer.GetActiveCamera()
            camera.SetFocalPoint(0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
                                 0.5 * (bounds[4] + bounds[5]))
            camera.Zoom(args.zoom)
        window.Render()
        image = vtkImageData()
        assert gi.GetColorBuffer(window, image)
        path = os.path.join(args.out, "point-cloud-%s%s.png" % (name, "-direct" if args.gi_off else ""))
        mb.write_display(mb.to_numpy(image), path, 1.0)
        print("wrote", path)
    return 0


def truth(args):
    """The CPU ground truth (Embree) of the mesh and of the cloud as surfels, compared."""
    made = object_source(args.object)
    source, description = made if made else object_source("sphere")
    images = {}
    for name, points in (("mesh", 0), ("cloud", args.points)):
        actor, info = object_actor(source, points, radius_scale=args.radius_scale)
        window, renderer, gi = scene(args.size, actor, gi=False)
        window.Render()
        reference = mrgi.vtkMRGIReferenceRenderer()
        reference.SetTargetRelativeError(0.0)
        reference.SetMaxPasses(args.passes)
        start = time.perf_counter()
        assert reference.Render(renderer), reference.GetLastErrorMessage()
        seconds = time.perf_counter() - start
        images[name] = [mb.to_numpy(reference.GetDirectImage())[..., :3],
                        mb.to_numpy(reference.GetIndirectImage())[..., :3]]
        print("ground truth of the %s: %d triangles, %d passes, %.1f s" % (name, reference.GetTriangleCount(),
                                                                          reference.GetPasses(), seconds))
    worst = 0.0
    for k, what in ((0, "direct"), (1, "indirect")):
        a, b = mb.boxes(images["cloud"][k]), mb.boxes(images["mesh"][k])
        assert np.isfinite(a).all(), "NaN in the ground truth of the cloud"
        rel = float(np.sqrt(((a - b) ** 2).sum() / (b ** 2).sum()))
        worst = max(worst, rel)
        print("ground truth %dx%d, %s, %d points: %s light of the cloud against the mesh's, 4x4 boxes: "
              "relative RMS %.4f" % (args.size, args.size, description, args.points, what, rel))
    if args.check is not None:
        if worst > args.check:
            print("FAILED: relative RMS %.4f above %g" % (worst, args.check))
            return 1
        print("passed: relative RMS <= %g" % args.check)
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    a = sub.add_parser("mesh-vs-cloud")
    a.add_argument("--object", default="bunny", choices=("bunny", "sphere"))
    a.add_argument("--sizes", type=lambda s: [int(v) for v in s.split(",")], default=[256, 512])
    a.add_argument("--points", type=int, default=1000000)
    a.add_argument("--check", help="REL,PIXELS: fail above these")
    a.add_argument("--scene", default="cornell-spot", help="cornell-spot (spot) or cornell (point light: cube-face RSMs)")
    a.add_argument("--radius-scale", type=float, default=1.0,
                   help="surfel radius times this (below 1 opens holes: shows that --check can fail)")
    a.add_argument("--max-surfels", type=int, default=0, help="vtkMRGISurfels' level of detail (0: off)")
    a.add_argument("--surfels-per-pixel", type=float, default=0.0,
                   help="the budget from the view (SuggestMaximumNumberOfSurfels); overrides --max-surfels")
    b = sub.add_parser("scaling")
    b.add_argument("--object", default="bunny", choices=("bunny", "sphere"))
    b.add_argument("--counts", type=lambda s: [int(float(v)) for v in s.split(",")], default=[100000, 1000000, 10000000])
    b.add_argument("--size", type=int, default=256)
    b.add_argument("--repeats", type=int, default=3)
    b.add_argument("--max-surfels", type=int, default=0, help="vtkMRGISurfels' level of detail (0: off)")
    b.add_argument("--surfels-per-pixel", type=float, default=0.0,
                   help="the budget from the view (SuggestMaximumNumberOfSurfels); overrides --max-surfels")
    c = sub.add_parser("pictures")
    c.add_argument("--object", default="bunny", choices=("bunny", "sphere"))
    c.add_argument("--points", type=int, default=200000)
    c.add_argument("--size", type=int, default=256)
    c.add_argument("--zoom", type=float, default=1.0)
    c.add_argument("--gi-off", action="store_true")
    c.add_argument("--out", default=os.path.join(mb.ROOT, "build", "Testing", "Temporary"))
    d = sub.add_parser("truth")
    d.add_argument("--object", default="bunny", choices=("bunny", "sphere"))
    d.add_argument("--points", type=int, default=200000)
    d.add_argument("--size", type=int, default=128)
    d.add_argument("--passes", type=int, default=4)
    d.add_argument("--radius-scale", type=float, default=1.0)
    d.add_argument("--check", type=float, help="fail above this relative RMS (direct or indirect)")
    args = parser.parse_args()
    global SCENE
    SCENE = getattr(args, "scene", SCENE)
    return {"mesh-vs-cloud": mesh_vs_cloud, "scaling": scaling, "pictures": pictures,
            "truth": truth}[args.command](args)


if __name__ == "__main__":
    sys.exit(main())
