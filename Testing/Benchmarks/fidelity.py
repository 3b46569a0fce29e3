"""Fidelity of the full-resolution gather against the ground truth.

For each scene: the GPU's indirect light (vtkMRGIPass, full gather) and the
CPU ground truth's (vtkMRGIReferenceRenderer) with and without secondary
visibility; relative RMS error (C core metrics), images and difference
images, written to Documentation/images/fidelity-* and a Markdown table.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \
        Testing/Benchmarks/fidelity.py --build build --out Documentation
"""
import argparse
import csv
import os
import sys
import time

sys.path.insert(0, os.path.dirname(__file__))
import mrgi_bench as mb  # noqa: E402

import mrgi  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(mb.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(mb.ROOT, "Documentation"))
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--vpls", type=int, default=256)
    parser.add_argument("--passes", type=int, default=64, help="ground-truth passes (16 bounce rays each)")
    parser.add_argument("--scenes", default="cornell-spot,bunny-cornell")
    args = parser.parse_args()
    compare_tool, images, scratch = mb.folders(args.build, args.out)

    rows = []
    for name in args.scenes.split(","):
        window, renderer = mb.make_window(args.size, args.size)
        description = mb.build_scene(renderer, name)
        if description is None:
            print("skipping %s: its data is not in %s" % (name, mb.SHARED_DATA))
            continue
        gi = mb.install_pass(renderer, NumberOfVPLs=args.vpls)
        window.Render()
        from vtkmodules.vtkCommonDataModel import vtkImageData
        buffer = vtkImageData()
        assert gi.GetIndirectBuffer(window, buffer)
        gpu = mb.to_numpy(buffer)
        color = vtkImageData()
        assert gi.GetColorBuffer(window, color)
        gpu_color = mb.to_numpy(color)
        gpu_path = os.path.join(scratch, "fidelity-%s-gpu.exr" % name)
        mb.write(gpu, gpu_path)

        results = {"scene": name, "description": description, "vpls": gi.GetVPLSelection().GetVPLCount()}
        for visibility in (True, False):
            reference = mrgi.vtkMRGIReferenceRenderer()
            reference.SetSecondaryVisibility(visibility)
            reference.SetTargetRelativeError(0.0)
            reference.SetMaxPasses(args.passes)
            start = time.time()
            assert reference.Render(renderer), reference.GetLastErrorMessage()
            tag = "vis" if visibility else "novis"
            ref = mb.to_numpy(reference.GetIndirectImage())
            ref_path = os.path.join(scratch, "fidelity-%s-ref-%s.exr" % (name, tag))
            mb.write(ref, ref_path)
            diff_png = os.path.join(images, "fidelity-%s-diff-%s.png" % (name, tag))
            metrics = mb.compare(compare_tool, gpu_path, ref_path, diff_png, diff_scale=4.0)
            results["rel_rms_" + tag] = metrics["relative_rms"]
            results["ssim_" + tag] = metrics["ssim"]
            results["ref_noise_" + tag] = reference.GetRelativeError()
            results["ref_seconds_" + tag] = time.time() - start
            scale = 1.0 / max(1e-12, float(ref[..., :3].max()))
            mb.write_display(ref, os.path.join(images, "fidelity-%s-ref-%s.png" % (name, tag)), scale)
            print("%s: GPU full gather vs ground truth %s secondary visibility: relative RMS %.4f, "
                  "SSIM %.4f (ground truth: %d passes, relative error %.5f, %.1f s)"
                  % (name, "with" if visibility else "without", metrics["relative_rms"], metrics["ssim"],
                     reference.GetPasses(), reference.GetRelativeError(), time.time() - start))
        scale = 1.0 / max(1e-12, float(gpu[..., :3].max()))
        mb.write_display(gpu, os.path.join(images, "fidelity-%s-gpu.png" % name), scale)
        mb.write_display(gpu_color, os.path.join(images, "fidelity-%s-color.png" % name), 1.0)
        rows.append(results)
        renderer.SetPass(None)
        gi.ReleaseGraphicsResources(window)

    csv_path = os.path.join(scratch, "fidelity.csv")
    with open(csv_path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    print("wrote %s" % csv_path)
    print()
    print("| scene | VPLs | rel. RMS vs ground truth (visibility) | rel. RMS (no secondary visibility) | SSIM (vis / no vis) |")
    print("|---|---|---|---|---|")
    for r in rows:
        print("| %s | %d | %.3f | %.3f | %.3f / %.3f |" % (r["scene"], r["vpls"], r["rel_rms_vis"], r["rel_rms_novis"],
                                                        r["ssim_vis"], r["ssim_novis"]))


if __name__ == "__main__":
    main()
