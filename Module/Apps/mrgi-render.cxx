// mrgi-render: render a built-in MRGI scene or a data file, headless, to PNG
// and/or OpenEXR, printing GPU time per stage on request.
//
// The command line is a contract users script against: options are only ever
// added, never renamed. Run `mrgi-render --help` for the list; it is printed
// from the same table (mrgiRenderOptions.cxx) that the parser reads.

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIEGLRenderWindow.h"
#include "vtkMRGIImageIO.h"
#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkProperty.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIAreaLightStage.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIUpsample.h"
#include "vtkMRGIVisibilityPyramid.h"
#include "vtkMRGIVoxelization.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReferenceRenderer.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMRGIRenderWindowFactory.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkRenderStepsPass.h"
#include "vtkDataArray.h"
#include "vtkRenderTimerLog.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkPointData.h"

#include "mrgi_box_filter.h"
#include "mrgi_error.h"
#include "mrgi_area_light.h"
#include "mrgi_voxel.h"
#include "mrgi_multires.h"
#include "mrgi_parse.h"

#include "mrgiRenderOptions.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <strings.h>
#include <utility>
#include <vector>

#ifndef MRGI_VERSION_STRING
#define MRGI_VERSION_STRING "unknown"
#endif

using namespace mrgirender;

namespace
{
double Median(std::vector<double> v)
{
  if (v.empty())
  {
    return 0;
  }
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// --aa ssaa:N: the N x N blocks of `image` (any scalar type, rows in
// either order) averaged into one pixel each (mrgi_box_downsample); 8-bit
// images are rounded back to 8 bits. False with `why` on failure.
bool Downsample(vtkImageData* image, int factor, std::string& why)
{
  if (factor <= 1)
  {
    return true;
  }
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  const int channels = scalars->GetNumberOfComponents();
  mrgi_image full, small;
  mrgi_error err;
  if (mrgi_image_create(&full, dims[0], dims[1], channels, &err) != MRGI_OK)
  {
    why = std::string("supersampling: ") + err.message;
    return false;
  }
  const vtkIdType values = scalars->GetNumberOfValues();
  for (vtkIdType i = 0; i < values; ++i)
  {
    full.pixels[i] = static_cast<float>(scalars->GetVariantValue(i).ToDouble());
  }
  const mrgi_status status = mrgi_box_downsample(&full, factor, &small, &err);
  mrgi_image_destroy(&full);
  if (status != MRGI_OK)
  {
    why = std::string("supersampling: ") + err.message;
    return false;
  }
  vtkSmartPointer<vtkDataArray> out = vtkSmartPointer<vtkDataArray>::Take(scalars->NewInstance());
  out->SetNumberOfComponents(channels);
  out->SetNumberOfTuples(static_cast<vtkIdType>(small.width) * small.height);
  out->SetName(scalars->GetName());
  const bool bytes = scalars->GetDataType() == VTK_UNSIGNED_CHAR;
  for (vtkIdType i = 0; i < out->GetNumberOfValues(); ++i)
  {
    const double v = small.pixels[i];
    out->SetVariantValue(i,
      bytes ? vtkVariant(static_cast<unsigned char>(std::lround(std::min(std::max(v, 0.0), 255.0))))
            : vtkVariant(v));
  }
  image->SetDimensions(small.width, small.height, 1);
  image->GetPointData()->SetScalars(out);
  mrgi_image_destroy(&small);
  return true;
}

void Progress(const Options& o, const std::string& line)
{
  if (!o.Quiet)
  {
    std::fprintf(stderr, "mrgi-render: %s\n", line.c_str());
  }
}
}

int main(int argc, char* argv[])
{
  Options o;
  const int parsed = ParseArguments(argc, argv, o);
  if (parsed >= 0)
  {
    return parsed;
  }
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a) {
    return std::chrono::duration<double>(Clock::now() - a).count();
  };

  // Errors are reported once, as one line, by this program; VTK's own error
  // output would repeat them with file/line noise.
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();

  std::string why;
  vtkSmartPointer<vtkRenderWindow> window = vtkSmartPointer<vtkRenderWindow>::Take(
    vtkMRGIRenderWindowFactory::CreateRenderWindow(o.Interactive
        ? vtkMRGIRenderWindowFactory::Interactive
        : vtkMRGIRenderWindowFactory::Headless,
      &why));
  if (!window)
  {
    return Fail("no render window: " + why);
  }
  // Supersampling renders every pixel N x N times; the outputs are averaged back.
  const int ssaa = o.AntiAliasing == Options::AASSAA ? o.SSAAFactor : 1;
  window->SetSize(o.Width * ssaa, o.Height * ssaa);
  // MRGI's buffers are single-sample (vtkMRGIPass refuses MSAA); FXAA is --aa's.
  window->SetMultiSamples(0);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(o.Background);
  renderer->SetUseFXAA(o.AntiAliasing == Options::AAFXAA);
  window->AddRenderer(renderer);

  const Clock::time_point buildStart = Clock::now();
  Progress(o, "building scene '" + o.Scene + "'");
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene(o.Scene.c_str());
  builder->SetTriangleCount(static_cast<vtkIdType>(o.Triangles));
  builder->SetObjectCount(static_cast<int>(o.Objects));
  builder->SetSeed(static_cast<vtkTypeUInt64>(o.Seed));
  if (!builder->Build(renderer))
  {
    return Fail(builder->GetLastErrorMessage());
  }
  char line[256];
  std::snprintf(line, sizeof(line), "scene ready: %lld triangles in %.2f s",
    static_cast<long long>(builder->GetBuiltTriangleCount()), seconds(buildStart));
  Progress(o, line);

  if (!o.Lights.empty())
  {
    renderer->RemoveAllLights();
    renderer->AutomaticLightCreationOff();
    for (const std::string& spec : o.Lights)
    {
      vtkSmartPointer<vtkLight> light;
      if (!ParseLight(spec, light, why))
      {
        return Fail(why);
      }
      renderer->AddLight(light);
    }
  }
  if (o.HasLightIntensity)
  {
    if (renderer->GetLights()->GetNumberOfItems() == 0)
    {
      // VTK would make its headlight at first render; make it now to scale it.
      renderer->CreateLight();
    }
    vtkLightCollection* lights = renderer->GetLights();
    lights->InitTraversal();
    while (vtkLight* light = lights->GetNextItem())
    {
      light->SetIntensity(light->GetIntensity() * o.LightIntensity);
    }
  }

  vtkCamera* camera = renderer->GetActiveCamera();
  if (o.HasPosition)
    camera->SetPosition(o.Position);
  if (o.HasFocal)
    camera->SetFocalPoint(o.Focal);
  if (o.HasUp)
    camera->SetViewUp(o.Up);
  if (o.HasAngle)
    camera->SetViewAngle(o.Angle);
  camera->SetParallelProjection(o.Parallel);
  if (o.AutoCamera)
  {
    renderer->ResetCamera();
  }
  renderer->ResetCameraClippingRange();

  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> mrgi;
  mrgi->SetDelegatePass(steps);
  mrgi->SetStageTimingEnabled(o.Timings);
  // Per-level statistics wait for the GPU once per frame: with --timings only.
  mrgi->GetGather()->SetCollectStatistics(o.Timings);
  mrgi->GetAreaLightStage()->GetGather()->SetCollectStatistics(o.Timings);
  mrgi->SetIndirectMode(!o.GI ? vtkMRGIPass::IndirectOff
      : o.Multires             ? vtkMRGIPass::IndirectMultires
                               : vtkMRGIPass::IndirectFull);
  // The preset first, then every knob given explicitly.
  mrgi->GetMultiresolution()->SetPreset(static_cast<int>(o.Preset));
  if (!std::isnan(o.DepthThreshold))
    mrgi->GetMultiresolution()->SetDepthThreshold(o.DepthThreshold);
  if (!std::isnan(o.NormalThreshold))
    mrgi->GetMultiresolution()->SetNormalThreshold(o.NormalThreshold);
  if (o.FinestLevel >= 0)
    mrgi->GetMultiresolution()->SetFinestLevel(static_cast<int>(o.FinestLevel));
  mrgi->SetSurfaceDetail(o.SurfaceDetail);
  mrgi->SetAreaLightVisibility(o.AreaLightVisibility);
  mrgi->SetAreaLightSpecular(o.AreaLightSpecular);
  mrgi->SetAreaLightSpecularResolution(o.AreaLightSpecularResolution);
  mrgi->GetVisibilityPyramid()->SetInterleave(o.VisibilityInterleave);
  mrgi->GetAreaLightStage()->SetIncrementalStencil(o.IncrementalStencil);
  // Repeated frames of one view would reuse the area lights' light: with
  // --frames the timings measure its computation instead.
  mrgi->SetAreaLightReuse(o.Frames <= 1);
  if (o.HasSpecular)
  {
    vtkActorCollection* actors = renderer->GetActors();
    actors->InitTraversal();
    while (vtkActor* actor = actors->GetNextActor())
    {
      if (actor->GetProperty()->GetOpacity() >= 1.0 && actor->GetProperty()->GetAmbient() == 0.0)
      {
        actor->GetProperty()->SetSpecular(o.SpecularCoefficient);
        actor->GetProperty()->SetSpecularPower(o.SpecularPower);
      }
    }
  }
  mrgi->GetVoxelization()->SetVoxelSide(static_cast<int>(o.VoxelSize));
  if (o.AreaLightsOn)
  {
    for (int l = 0; l < builder->GetNumberOfAreaLights(); ++l)
    {
      mrgi->AddAreaLight(builder->GetAreaLight(l));
    }
    for (const std::string& spec : o.AreaLights)
    {
      vtkNew<vtkMRGIAreaLight> light;
      if (!ParseAreaLight(spec, light, why))
      {
        return Fail(why);
      }
      renderer->AddActor(light->GetGeometryActor());
      mrgi->AddAreaLight(light);
    }
    for (int l = 0; l < mrgi->GetNumberOfAreaLights(); ++l)
    {
      mrgi->GetAreaLight(l)->SetNumberOfSamples(static_cast<int>(o.AreaLightSamples));
      mrgi->GetAreaLight(l)->SetTwoSided(mrgi->GetAreaLight(l)->GetTwoSided() || o.AreaLightTwoSided);
    }
  }
  mrgi->GetGather()->SetGatherMode(
    o.Splatting ? vtkMRGIGather::GatherSplatting : vtkMRGIGather::GatherStenciled);
  mrgi->SetUpsampleMode(
    o.MaskUpsampling ? vtkMRGIUpsample::UpsampleMaskWeighted : vtkMRGIUpsample::UpsampleTent);
  mrgi->SetNumberOfVPLs(static_cast<int>(o.VPLs));
  mrgi->SetVPLSelectionMode(o.ImportanceVPLs ? vtkMRGIVPLSelection::FluxImportance : vtkMRGIVPLSelection::Grid);
  mrgi->SetRSMResolution(static_cast<int>(o.RSMSize));
  mrgi->SetIndirectStrength(o.IndirectStrength);
  mrgi->SetToneMapping(o.ToneMapping);
  mrgi->SetAutoExposure(o.AutoExposure);
  mrgi->SetAutoExposureKey(o.ExposureKey);
  mrgi->SetExposure(o.Exposure);
  if (o.IndirectOnly && !o.GI && !o.Reference)
  {
    return Fail("--indirect-only needs indirect light (--gi full) or --reference");
  }
  if (o.Timings)
  {
    // Logging must be on before the window opens the first frame.
    window->GetRenderTimer()->SetLoggingEnabled(true);
  }
  renderer->SetPass(mrgi);

  std::map<std::string, std::vector<double>> stageTimes;
  std::vector<std::string> stageOrder;
  std::vector<double> frameTimes;
  for (long long f = 0; f < o.Frames; ++f)
  {
    const Clock::time_point frameStart = Clock::now();
    window->Render();
    if (o.Timings)
    {
      const int n = mrgi->FetchStageTimings(window, true);
      for (int s = 0; s < n; ++s)
      {
        const std::string name = mrgi->GetStageName(s);
        if (stageTimes.find(name) == stageTimes.end())
        {
          stageOrder.push_back(name);
        }
        stageTimes[name].push_back(mrgi->GetStageTimeMilliseconds(s));
      }
    }
    frameTimes.push_back(seconds(frameStart) * 1e3);
    if (o.Frames > 1 && (f + 1) % 10 == 0)
    {
      std::snprintf(line, sizeof(line), "frame %lld/%lld", f + 1, o.Frames);
      Progress(o, line);
    }
  }
  if (mrgi->GetBufferSize()[0] < 1)
  {
    return Fail("nothing was rendered (is the window size valid and an OpenGL context available?)");
  }
  std::snprintf(line, sizeof(line), "exposure %+.2f EV (%s)%s%s", mrgi->GetLastExposure(),
    o.AutoExposure ? "auto" : "fixed", o.ToneMapping ? ", tone mapped" : "",
    o.AntiAliasing == Options::AAFXAA ? ", FXAA"
      : ssaa > 1 ? (", SSAA " + std::to_string(ssaa) + "x" + std::to_string(ssaa)).c_str()
                 : "");
  Progress(o, line);

  // Ground truth: the CPU reference of the same scene (lights as placed by
  // the frame just rendered), instead of the GPU image.
  vtkNew<vtkMRGIReferenceRenderer> reference;
  vtkNew<vtkImageData> referenceImage;
  if (o.Reference)
  {
    reference->SetWidth(o.Width);
    reference->SetHeight(o.Height);
    reference->SetSecondaryVisibility(o.ReferenceVisibility);
    reference->SetShadows(o.ReferenceShadows);
    reference->SetTargetRelativeError(o.ReferenceError);
    reference->SetMaxPasses(static_cast<int>(o.ReferencePasses));
    for (int l = 0; l < mrgi->GetNumberOfAreaLights(); ++l)
    {
      reference->AddAreaLight(mrgi->GetAreaLight(l));
    }
    reference->SetAreaLightSamples(static_cast<int>(std::min<long long>(o.AreaLightSamples, 64)));
    Progress(o, "rendering the ground truth (CPU)");
    if (!reference->Render(renderer))
    {
      return Fail(std::string("ground truth: ") + reference->GetLastErrorMessage());
    }
    std::snprintf(line, sizeof(line),
      "ground truth: %d passes, relative error %.4f, %.1f s, %lld triangles", reference->GetPasses(),
      reference->GetRelativeError(), reference->GetSeconds(),
      static_cast<long long>(reference->GetTriangleCount()));
    Progress(o, line);
    referenceImage->DeepCopy(reference->GetIndirectImage());
    if (!o.IndirectOnly)
    {
      vtkDataArray* sum = referenceImage->GetPointData()->GetScalars();
      vtkDataArray* direct = reference->GetDirectImage()->GetPointData()->GetScalars();
      for (vtkIdType i = 0; i < sum->GetNumberOfValues(); ++i)
      {
        sum->SetVariantValue(i, sum->GetVariantValue(i).ToDouble() + direct->GetVariantValue(i).ToDouble());
      }
    }
  }

  why.clear();
  for (const std::string& path : o.Outputs)
  {
    vtkNew<vtkImageData> image;
    vtkNew<vtkMRGIImageIO> io;
    io->SetHalfFloat(o.Half);
    bool ok = false;
    if (o.Reference)
    {
      ok = io->Write(referenceImage, path.c_str());
    }
    else if (o.IndirectOnly)
    {
      ok = mrgi->GetIndirectBuffer(window, image) && Downsample(image, ssaa, why) &&
        io->Write(image, path.c_str());
    }
    else if (EndsWith(path, ".exr"))
    {
      ok = mrgi->GetColorBuffer(window, image) && Downsample(image, ssaa, why) &&
        io->WriteEXR(image, path.c_str());
    }
    else
    {
      vtkNew<vtkUnsignedCharArray> pixels;
      window->GetRGBACharPixelData(0, 0, o.Width * ssaa - 1, o.Height * ssaa - 1, 0, pixels);
      pixels->SetNumberOfComponents(4);
      vtkNew<vtkUnsignedCharArray> rgb;
      rgb->SetNumberOfComponents(3);
      rgb->SetNumberOfTuples(pixels->GetNumberOfTuples());
      for (vtkIdType p = 0; p < pixels->GetNumberOfTuples(); ++p)
      {
        for (int c = 0; c < 3; ++c)
        {
          rgb->SetValue(3 * p + c, pixels->GetValue(4 * p + c));
        }
      }
      image->SetDimensions(o.Width * ssaa, o.Height * ssaa, 1);
      image->GetPointData()->SetScalars(rgb);
      ok = Downsample(image, ssaa, why) && io->WritePNG(image, path.c_str());
    }
    if (!ok)
    {
      return Fail(std::string("cannot write '") + path + "': " +
        (io->GetLastErrorMessage()[0] ? io->GetLastErrorMessage()
            : !why.empty()            ? why.c_str()
                                      : "reading the image back failed"));
    }
    Progress(o, "wrote " + path);
  }

  if (o.Timings)
  {
    std::printf("%-24s %12s\n", "stage", "GPU ms");
    double total = 0;
    for (const std::string& name : stageOrder)
    {
      const double ms = Median(stageTimes[name]);
      // "stage.step" names are parts of their stage, indented, not added again.
      const bool step = name.find('.') != std::string::npos;
      total += step ? 0.0 : ms;
      std::printf("%s%-*s %12.3f\n", step ? "  " : "", step ? 22 : 24, name.c_str(), ms);
    }
    std::printf("%-24s %12.3f\n", "total (GPU)", total);
    vtkMRGIMultiresolution* mr = mrgi->GetMultiresolution();
    // The indirect light's gather, or else the area lights' (the last light's).
    vtkMRGIGather* gather = mrgi->GetGather()->GetGatherWorkFraction() >= 0
      ? mrgi->GetGather()
      : mrgi->GetAreaLightStage()->GetGather();
    if (o.GI && o.Multires && gather->GetGatherWorkFraction() >= 0)
    {
      // nichols-shopf-wyman-2009 table 1: where the gather's work went (last frame).
      std::printf("%-6s %-11s %16s\n", "level", "size", "texels gathered");
      for (int i = 0; i < mr->GetNumberOfLevels(); ++i)
      {
        int size[2] = { 0, 0 };
        mr->GetLevelSize(i, size);
        std::snprintf(line, sizeof(line), "%dx%d", size[0], size[1]);
        std::printf("%-6d %-11s %16lld\n", i, line,
          static_cast<long long>(gather->GetNumberOfGatheredTexels(i)));
      }
      std::printf("gathered / valid pixels: %.4f (of %lld valid pixels)\n",
        gather->GetGatherWorkFraction(), static_cast<long long>(gather->GetNumberOfValidPixels()));
    }
    std::printf("%-24s %12.3f\n", "frame (wall)", Median(frameTimes));
    if (stageOrder.empty())
    {
      std::printf("(this OpenGL offers no timer queries: GPU stage times unavailable)\n");
    }
    std::fflush(stdout);
  }

  if (o.Interactive)
  {
    vtkNew<vtkRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(window);
    interactor->Initialize();
    interactor->Start();
  }
  renderer->SetPass(nullptr);
  mrgi->ReleaseGraphicsResources(window);
  return 0;
}
