// mrgi-render: render a built-in MRGI scene or a data file, headless, to PNG
// and/or OpenEXR, printing GPU time per stage on request.
//
// The command line is a contract users script against: options are only ever
// added, never renamed. Run `mrgi-render --help` for the list; it is printed
// from the same table (mrgiRenderOptionTable.cxx) that the parser reads.

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIAreaLightStage.h"
#include "vtkMRGIEGLRenderWindow.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIImageIO.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIImperfectShadowMaps.h"
#include "vtkMRGIIncrementalStencil.h"
#include "vtkMRGIIndirectLight.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReferenceRenderer.h"
#include "vtkMRGIResourceStatistics.h"
#include "vtkMRGIRenderWindowFactory.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMRGIStaging.h"
#include "vtkMRGIUpsample.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMRGIVisibilityPyramid.h"
#include "vtkMRGIVoxelization.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkLogger.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderPass.h"
#include "vtkRenderStepsPass.h"
#include "vtkDataArray.h"
#include "vtkRenderTimerLog.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtk_glew.h"
#include "vtkMath.h"

#include "mrgi_error.h"
#include "mrgi_area_light.h"
#include "mrgi_voxel.h"
#include "mrgi_multires.h"
#include "mrgi_parse.h"
#include "mrgi_vpl_tree_gather.h"

#include "mrgiRenderColdStart.h"
#include "mrgiRenderFrameBudget.h"
#include "mrgiRenderImageLimits.h"
#include "mrgiRenderImages.h"
#include "mrgiRenderOptions.h"
#include "mrgiRenderOutputWindow.h"
#include "mrgiRenderOutputs.h"

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
#include <unistd.h> // isatty

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

// Detaches the passes and frees their GL resources (the outermost pass
// releases its delegates' too): by Now(), or on any return from main, so
// that a pass is never destroyed holding them (which VTK reports as an
// error after the program's own error line).
struct PassRelease
{
  vtkRenderer* Renderer;
  vtkRenderWindow* Window;
  vtkRenderPass* Outermost;
  void Now()
  {
    if (this->Outermost)
    {
      this->Renderer->SetPass(nullptr);
      this->Outermost->ReleaseGraphicsResources(this->Window);
      this->Outermost = nullptr;
    }
  }
  ~PassRelease() { this->Now(); }
};

// An error in the input (the scene file, an empty picture): exit status 1,
// apart from the command-line errors' 2.
int FailInput(const std::string& message)
{
  Fail(message);
  return 1;
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
  using Clock = std::chrono::steady_clock;
  const Clock::time_point processStart = Clock::now(); // after the loader, before VTK
  Options o;
  const int parsed = ParseArguments(argc, argv, o);
  if (parsed >= 0)
  {
    return parsed;
  }
  auto seconds = [](Clock::time_point a) {
    return std::chrono::duration<double>(Clock::now() - a).count();
  };

  // VTK's messages come through the CLI: plain lines (none with -q), and an
  // error VTK reports fails the run instead of being lost in the log.
  mrgiRenderOutputWindow* messages = mrgiRenderOutputWindow::Install(o.Quiet);
  auto vtkFailed = [messages](const std::string& what) {
    return Fail(what + ": " + messages->GetFirstError());
  };

  // Every output is checked before the (possibly long) render; the images
  // are written only when all of them can be, and none is left otherwise.
  std::string why;
  Outputs outputs;
  if (!outputs.Check(o.Outputs, why))
  {
    return Fail(why);
  }
  vtkSmartPointer<vtkRenderWindow> window =
    vtkSmartPointer<vtkRenderWindow>::Take(vtkMRGIRenderWindowFactory::CreateRenderWindow(
      o.Interactive ? vtkMRGIRenderWindowFactory::Interactive
                    : vtkMRGIRenderWindowFactory::Headless,
      o.Backend.c_str(), &why));
  if (!window)
  {
    return Fail("no render window: " + why);
  }
  const double windowSeconds = seconds(processStart); // VTK's start-up and the GL context
  Progress(o, "render window: " + vtkMRGIRenderWindowFactory::DescribeRenderWindow(window));
  // Supersampling renders every pixel N x N times; the outputs are averaged back.
  const int ssaa = o.AntiAliasing == Options::AASSAA ? o.SSAAFactor : 1;
  window->SetSize(o.Width * ssaa, o.Height * ssaa);
  // MRGI's buffers are single-sample (vtkMRGIPass refuses MSAA); FXAA is --aa's.
  window->SetMultiSamples(0);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(o.Background);
  const bool display = ShowsDisplayImage(o);
  renderer->SetUseFXAA(display && o.AntiAliasing == Options::AAFXAA);
  window->AddRenderer(renderer);

  const Clock::time_point buildStart = Clock::now();
  Progress(o, "building scene '" + o.Scene + "'");
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene(o.Scene.c_str());
  builder->SetTriangleCount(static_cast<vtkIdType>(o.Triangles));
  builder->SetObjectCount(static_cast<int>(o.Objects));
  builder->SetSeed(static_cast<vtkTypeUInt64>(o.Seed));
  vtkNew<vtkMRGIStaging> stager;
  stager->SetUp(o.StageUp);
  stager->SetGround(o.StageGround);
  stager->SetKeyLight(o.StageKeyLight);
  stager->SetFillFraction(o.StageFill);
  stager->SetAutomaticIsoValue(!o.HasIso);
  stager->SetIsoValue(o.Iso);
  if (o.Stage)
  {
    builder->SetStaging(stager); // used for data files only
  }
  if (!builder->Build(renderer))
  {
    return FailInput(builder->GetLastErrorMessage());
  }
  char line[256];
  if (builder->GetBuiltPointCount() > 0)
  {
    std::snprintf(line, sizeof(line), "scene ready: a point cloud of %lld points in %.2f s",
      static_cast<long long>(builder->GetBuiltPointCount()), seconds(buildStart));
  }
  else
  {
    std::snprintf(line, sizeof(line), "scene ready: %lld triangles in %.2f s",
      static_cast<long long>(builder->GetBuiltTriangleCount()), seconds(buildStart));
  }
  Progress(o, line);
  const double sceneSeconds = seconds(buildStart);
  const bool builtIn = vtkMRGISceneBuilder::IsBuiltInScene(o.Scene.c_str());
  if (!o.StagingOptions.empty() && (!o.Stage || builtIn))
  {
    Progress(o,
      "note: " + o.StagingOptions +
        " ignored: " + (builtIn ? "built-in scenes are not staged" : "--stage off"));
  }
  if (o.Stage && !builtIn)
  {
    std::snprintf(line, sizeof(line), "staged: up %s (%s)%s",
      vtkMRGIStaging::GetUpAxisName(stager->GetDetectedUp()), stager->GetUpReason(),
      std::isnan(stager->GetLastIsoValue())
        ? ""
        : (", volume as the iso-surface at " + std::to_string(stager->GetLastIsoValue())).c_str());
    Progress(o, line);
  }

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
  if (o.Parallel)
  {
    // VTK's parallel scale (half the view height in world units) defaults
    // to 1 whatever the scene's size: frame what the perspective view shows
    // at the focal point instead (ResetCamera() below sets it too).
    camera->SetParallelScale(
      camera->GetDistance() * std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) / 2.0));
  }
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
  // Shadows come with the indirect light unless asked otherwise: --gi off
  // stays VTK's own direct light, and --indirect-only writes no direct
  // light (the shadows would cost a first frame its largest stage for nothing).
  mrgi->SetDirectShadows(o.DirectShadows >= 0 ? o.DirectShadows
      : o.GI && !o.IndirectOnly               ? vtkMRGIPass::DirectShadowsSoft
                                              : vtkMRGIPass::DirectShadowsOff);
  // The screen-space preset first, then every knob given explicitly (all
  // of them without a preset: their defaults are Balanced's values).
  const bool screenPreset = o.ScreenSpacePreset >= 0;
  if (screenPreset && !mrgi->SetScreenSpacePreset(static_cast<int>(o.ScreenSpacePreset)))
  {
    return Fail("--screen-space-preset could not be applied");
  }
  if (!screenPreset || o.HasShadowKernel)
    mrgi->SetSoftShadowKernelSize(static_cast<int>(o.ShadowKernel));
  mrgi->SetShadowLightRadius(o.ShadowLightRadius);
  if (!screenPreset || o.HasShadowResolution)
    mrgi->SetShadowResolution(
      o.ShadowMultires ? vtkMRGIPass::ResolutionMultiresolution : vtkMRGIPass::ResolutionFull);
  // The preset first, then every knob given explicitly.
  mrgi->GetMultiresolution()->SetPreset(static_cast<int>(o.Preset));
  // A threshold given on the command line selects for the indirect light
  // and the area lights alike.
  if (!std::isnan(o.DepthThreshold))
  {
    mrgi->GetMultiresolution()->SetDepthThreshold(o.DepthThreshold);
    mrgi->GetMultiresolution()->SetAreaLightDepthThreshold(o.DepthThreshold);
  }
  if (!std::isnan(o.NormalThreshold))
  {
    mrgi->GetMultiresolution()->SetNormalThreshold(o.NormalThreshold);
    mrgi->GetMultiresolution()->SetAreaLightNormalThreshold(o.NormalThreshold);
  }
  if (o.FinestLevel >= 0)
    mrgi->GetMultiresolution()->SetFinestLevel(static_cast<int>(o.FinestLevel));
  mrgi->SetSurfaceDetail(o.SurfaceDetail);
  // The screen-space effects' radius: the one given, else `fraction` of
  // the scene's bounding-box diagonal (vtkSSAOPass's radius 0.5 and bias
  // are world units that suit only scenes of about unit size), else `value`.
  auto sceneRadius = [&renderer](bool given, double value, double fraction) {
    double bounds[6];
    renderer->ComputeVisiblePropBounds(bounds);
    const double dx = bounds[1] - bounds[0], dy = bounds[3] - bounds[2], dz = bounds[5] - bounds[4];
    const double diagonal = std::sqrt(dx * dx + dy * dy + dz * dz);
    return given || !(std::isfinite(diagonal) && diagonal > 0) ? value : fraction * diagonal;
  };
  mrgi->SetSSAO(o.SSAO);
  if (o.SSAO)
  {
    const double radius = sceneRadius(o.HasSSAORadius, o.SSAORadius, 0.02);
    mrgi->SetSSAORadius(radius);
    mrgi->SetSSAOBias(o.HasSSAOBias ? o.SSAOBias : radius / 50.0);
    if (!screenPreset || o.HasSSAOSamples)
      mrgi->SetSSAOKernelSize(static_cast<int>(o.SSAOSamples));
    mrgi->SetSSAOBlur(o.SSAOBlur);
    if (!screenPreset || o.HasSSAOResolution)
      mrgi->SetSSAOResolution(
        o.SSAOMultires ? vtkMRGIPass::ResolutionMultiresolution : vtkMRGIPass::ResolutionFull);
  }
  mrgi->SetSSGI(o.SSGI);
  if (o.SSGI)
  {
    const double radius = sceneRadius(o.HasSSGIRadius, o.SSGIRadius, 0.1);
    mrgi->SetSSGIRadius(radius);
    mrgi->SetSSGIBias(radius / 50.0);
    if (!screenPreset || o.HasSSGISamples)
      mrgi->SetSSGISamples(static_cast<int>(o.SSGISamples));
    if (!screenPreset || o.HasSSGIResolution)
      mrgi->SetSSGIResolution(
        o.SSGIMultires ? vtkMRGIPass::ResolutionMultiresolution : vtkMRGIPass::ResolutionFull);
  }
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
  mrgi->GetVoxelization()->SetOffsetAlongRay(o.VoxelOffset);
  if (o.VoxelSlices > 0)
  {
    mrgi->GetVoxelization()->SetNumberOfSlices(o.VoxelSlices);
  }
  if (o.VoxelSize > 0)
  {
    mrgi->GetVoxelization()->SetVoxelSide(static_cast<int>(o.VoxelSize));
  }
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
  if (o.Splatting && o.Refinement == vtkMRGIMultiresolution::RefinementIllumination)
  {
    return Fail("--gather splat gathers the geometric selection: it has no step between levels "
                "for --refinement illumination (use --gather stencil)");
  }
  mrgi->GetGather()->SetGatherMode(
    o.Splatting ? vtkMRGIGather::GatherSplatting : vtkMRGIGather::GatherStenciled);
  mrgi->SetUpsampleMode(
    o.MaskUpsampling ? vtkMRGIUpsample::UpsampleMaskWeighted : vtkMRGIUpsample::UpsampleTent);
  mrgi->SetNumberOfVPLs(static_cast<int>(o.VPLs));
  mrgi->SetVPLSelectionMode(o.VPLSelection);
  if (!std::isnan(o.ClusterDepthThreshold))
    mrgi->SetClusterDepthThreshold(o.ClusterDepthThreshold);
  if (!std::isnan(o.ClusterNormalThreshold))
    mrgi->SetClusterNormalThreshold(o.ClusterNormalThreshold);
  if (!std::isnan(o.TreeThreshold))
    mrgi->SetTreeThreshold(o.TreeThreshold);
  if (o.VPLSelection == vtkMRGIVPLSelection::Tree && o.RSMSize > MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE)
  {
    return Fail("--vpl-selection tree takes --rsm-size up to " +
      std::to_string(MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE) + " (the tree gather's limit), not " +
      std::to_string(o.RSMSize));
  }
  mrgi->SetRSMResolution(static_cast<int>(o.RSMSize));
  if ((o.ISMTileSize & (o.ISMTileSize - 1)) != 0)
  {
    return Fail("--ism-tile takes a power of two (the maps' push-pull halves it), not " +
      std::to_string(o.ISMTileSize));
  }
  mrgi->SetIndirectVisibility(o.IndirectVisibility);
  if (o.Refinement >= 0)
    mrgi->SetRefinement(o.Refinement);
  if (!std::isnan(o.IlluminationThreshold))
    mrgi->SetIlluminationThreshold(o.IlluminationThreshold);
  if (o.IlluminationMetric >= 0)
    mrgi->GetIndirectLightStage()->GetIlluminationStencil()->SetIlluminationMetric(
      o.IlluminationMetric);
  mrgi->SetISMPointsPerVPL(static_cast<int>(o.ISMPointsPerVPL));
  mrgi->SetISMTileSize(static_cast<int>(o.ISMTileSize));
  mrgi->SetISMPointMode(o.ISMPointMode);
  mrgi->SetISMLazyFrames(static_cast<int>(o.ISMLazyFrames));
  if (!std::isnan(o.ISMBias))
    mrgi->GetIndirectLightStage()->SetISMRelativeBias(o.ISMBias);
  mrgi->GetIndirectLightStage()->SetISMFiltering(o.ISMFiltering);
  if (!std::isnan(o.ISMTexelBias))
    mrgi->GetIndirectLightStage()->SetISMTexelBias(o.ISMTexelBias);
  if (!std::isnan(o.ISMMaxTexelAngle))
    mrgi->GetIndirectLightStage()->SetISMMaxTexelAngle(o.ISMMaxTexelAngle);
  mrgi->GetIndirectLightStage()->GetImperfectShadowMaps()->SetPushPullLevels(
    static_cast<int>(o.ISMPushPullLevels));
  mrgi->SetIndirectStrength(o.IndirectStrength);
  mrgi->SetToneMapping(display && o.ToneMapping);
  mrgi->SetAutoExposure(display && o.AutoExposure);
  mrgi->SetAutoExposureKey(o.ExposureKey);
  mrgi->SetExposure(o.Exposure);
  if (o.IndirectOnly && !o.GI && !o.Reference)
  {
    return Fail("--indirect-only needs indirect light (--gi full) or --reference");
  }
  if (o.IndirectOnly && o.SSGI && !o.Reference)
  {
    // SSGI replaces the VPL gather and is composited into the colour only.
    return Fail("--indirect-only writes the VPL gather's indirect light, which --ssgi on "
                "replaces; use --ssgi off, or write the composited image");
  }
  if (o.Timings)
  {
    // Logging must be on before the window opens the first frame.
    window->GetRenderTimer()->SetLoggingEnabled(true);
  }
  renderer->SetPass(mrgi);
  PassRelease release{ renderer, window, mrgi };

  if (!CheckImageLimits(window, o, mrgi, why))
  {
    return Fail(why);
  }
  std::string budgetNote;
  if (!SetUpFrameBudget(o, window, mrgi, budgetNote, why))
  {
    return Fail(why);
  }
  if (!budgetNote.empty())
  {
    Progress(o, budgetNote.c_str());
  }
  // VTK errors while the scene was built did not stop the builder (it fails
  // by itself when they matter) and were shown; from here on one fails the run.
  messages->ResetErrors();

  std::map<std::string, std::vector<double>> stageTimes;
  std::vector<std::string> stageOrder;
  std::vector<double> frameTimes;
  // Texture allocations per frame: the first frame's, and all later ones'.
  std::vector<vtkTypeInt64> allocations, allocatedBytes;
  const double setupSeconds = seconds(processStart);
  for (long long f = 0; f < o.Frames; ++f)
  {
    const Clock::time_point frameStart = Clock::now();
    const vtkTypeInt64 allocationsBefore = vtkMRGIResourceStatistics::GetNumberOfTextureAllocations();
    const vtkTypeInt64 bytesBefore = vtkMRGIResourceStatistics::GetTextureBytesAllocated();
    window->Render();
    allocations.push_back(vtkMRGIResourceStatistics::GetNumberOfTextureAllocations() - allocationsBefore);
    allocatedBytes.push_back(vtkMRGIResourceStatistics::GetTextureBytesAllocated() - bytesBefore);
    if (messages->GetNumberOfErrors() > 0)
    {
      return vtkFailed("rendering failed, nothing written");
    }
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
  // The image the emptiness check reads, kept for the outputs that write
  // it: the window's 8-bit colour when a display image is drawn, else the
  // HDR colour buffer.
  vtkSmartPointer<vtkImageData> checked;
  if (!o.AllowEmpty && !o.Reference)
  {
    // A picture of the background alone is a failure, not a result: say why.
    checked = vtkSmartPointer<vtkImageData>::New();
    const bool read = display ? ReadWindowRGB(window, o.Width * ssaa, o.Height * ssaa, checked)
                              : mrgi->GetColorBuffer(window, checked);
    if (!read || messages->GetNumberOfErrors() > 0)
    {
      return Fail("reading the image back failed" +
        (messages->GetNumberOfErrors() > 0 ? ": " + messages->GetFirstError() : std::string()));
    }
    if (OnlyBackground(checked, o.Background))
    {
      return FailInput("'" + o.Scene + "' renders an empty image (background only): " +
        WhyEmpty(renderer, builder->GetBuiltTriangleCount()) + "; --allow-empty accepts it");
    }
  }
  if (display)
  {
    std::snprintf(line, sizeof(line), "exposure %+.2f EV (%s)%s%s", mrgi->GetLastExposure(),
      o.AutoExposure ? "auto" : "fixed", o.ToneMapping ? ", tone mapped" : "",
      o.AntiAliasing == Options::AAFXAA ? ", FXAA"
        : ssaa > 1 ? (", SSAA " + std::to_string(ssaa) + "x" + std::to_string(ssaa)).c_str()
                   : "");
  }
  else
  {
    std::snprintf(line, sizeof(line), "no display image: every output is HDR, so exposure, tone "
                                      "mapping and FXAA did not run%s",
      ssaa > 1 ? (", SSAA " + std::to_string(ssaa) + "x" + std::to_string(ssaa)).c_str() : "");
  }
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
    reference->SetPixelFilter(o.ReferencePixel);
    reference->SetTargetRelativeError(o.ReferenceError);
    reference->SetTargetPercentile(o.ReferencePercentile);
    reference->SetSeed(static_cast<vtkTypeUInt64>(o.Seed));
    reference->SetMaxPasses(static_cast<int>(o.ReferencePasses));
    for (int l = 0; l < mrgi->GetNumberOfAreaLights(); ++l)
    {
      reference->AddAreaLight(mrgi->GetAreaLight(l));
    }
    reference->SetAreaLightSamples(static_cast<int>(std::min<long long>(o.AreaLightSamples, 64)));
    Progress(o, "rendering the ground truth (CPU)");
    // A progress line after the first pass, then at most one a second, and
    // after the last pass; only on a terminal or with --progress, so that CI
    // logs of long ground truths do not fill up.
    Clock::time_point lastLine = Clock::now();
    vtkNew<vtkCallbackCommand> progress;
    progress->SetCallback([](vtkObject* caller, unsigned long, void* clientData, void*) {
      auto* last = static_cast<Clock::time_point*>(clientData);
      auto* r = static_cast<vtkMRGIReferenceRenderer*>(caller);
      const double since = std::chrono::duration<double>(Clock::now() - *last).count();
      if (r->GetProgressPasses() > 1 && since < 1.0 && r->GetProgress() < 1.0)
      {
        return;
      }
      *last = Clock::now();
      char text[256];
      char error[32] = "unknown"; // after one pass
      if (std::isfinite(r->GetProgressPixelError()))
      {
        std::snprintf(error, sizeof(error), "%.4f", r->GetProgressPixelError());
      }
      std::snprintf(text, sizeof(text),
        "mrgi-render: ground truth: pass %d, %.0f%%, per-pixel error %s (target %g at the %g "
        "quantile), about %.0f s left\n",
        r->GetProgressPasses(), 100.0 * r->GetProgress(), error, r->GetTargetRelativeError(),
        r->GetTargetPercentile(), r->GetProgressSecondsLeft());
      std::fputs(text, stderr);
    });
    progress->SetClientData(&lastLine);
    if (!o.Quiet && (o.ReferenceProgress || isatty(fileno(stderr))))
    {
      reference->AddObserver(vtkCommand::ProgressEvent, progress);
    }
    if (!reference->Render(renderer))
    {
      return Fail(std::string("ground truth: ") + reference->GetLastErrorMessage());
    }
    std::snprintf(line, sizeof(line),
      "ground truth: %d passes, per-pixel error %.4f at the %g quantile (image mean %.5f), %.1f s, "
      "%lld triangles",
      reference->GetPasses(), reference->GetPixelError(), reference->GetTargetPercentile(),
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
    if (mrgi->GetGather()->GetMeanVPLsPerPixel() >= 0)
    {
      // The VPL tree (NSW09 3.5): nodes each gathered pixel used, last frame.
      std::printf("VPLs per pixel (tree): mean %.2f, max %.0f\n",
        mrgi->GetGather()->GetMeanVPLsPerPixel(), mrgi->GetGather()->GetMaxVPLsPerPixel());
    }
    // The voxel buffers used last frame: the area lights' ("voxels:") and the
    // VPLs' (--indirect-visibility voxel), each sized on its own.
    const auto printVoxels = [](const char* label, vtkMRGIVoxelization* voxelization) {
      int voxels[2] = { 0, 0 };
      voxelization->GetLastVoxelSize(voxels);
      if (voxels[0] > 0)
      {
        double range[2];
        voxelization->GetLastDepthRange(range);
        std::printf("%s %dx%d (%s) x %d slices over depth [%g, %g]\n", label, voxels[0], voxels[1],
          voxelization->GetAutomaticVoxelSize() ? "automatic" : "fixed",
          voxelization->GetLastNumberOfSlices(), range[0], range[1]);
      }
    };
    printVoxels("voxels:", mrgi->GetVoxelization());
    printVoxels("voxels (VPLs):", mrgi->GetIndirectLightStage()->GetVoxelization());
    std::printf("%-24s %12.3f\n", "frame (wall)", Median(frameTimes));
    if (mrgi->GetFrameBudgetTuner()->IsActive())
    {
      std::printf("%s\n", mrgi->GetFrameBudgetTuner()->GetSummary().c_str());
    }
    if (stageOrder.empty())
    {
      std::printf("(this OpenGL offers no timer queries: GPU stage times unavailable)\n");
    }
    PrintColdStart(stageOrder, stageTimes, frameTimes, allocations, allocatedBytes,
      { windowSeconds, sceneSeconds, setupSeconds });
    std::fflush(stdout);
  }

  // Read every image back, then (unless a window stays open) free the
  // pass's buffers before the images are converted and written, so that
  // the writers' copies do not add to the render's peak memory.
  vtkSmartPointer<vtkImageData> hdr, png;
  std::vector<vtkSmartPointer<vtkImageData>> images;
  for (const std::string& path : o.Outputs)
  {
    const bool exr = EndsWith(path, ".exr");
    vtkSmartPointer<vtkImageData>& shared = exr ? hdr : png;
    if (!shared)
    {
      shared = vtkSmartPointer<vtkImageData>::New();
      bool ok = true;
      if (o.Reference)
      {
        shared = referenceImage;
      }
      else if (o.IndirectOnly)
      {
        ok = mrgi->GetIndirectBuffer(window, shared);
      }
      else if (checked && exr != display)
      {
        shared = checked; // read for the emptiness check: the same pixels
      }
      else if (exr)
      {
        ok = mrgi->GetColorBuffer(window, shared);
      }
      else
      {
        ok = ReadWindowRGB(window, o.Width * ssaa, o.Height * ssaa, shared);
      }
      if (!ok || messages->GetNumberOfErrors() > 0)
      {
        return Fail("cannot write '" + path + "': reading the image back failed" +
          (messages->GetNumberOfErrors() > 0 ? ": " + messages->GetFirstError() : std::string()));
      }
      // --aa ssaa:N: the N x N blocks averaged back to the asked size.
      if (!o.Reference && !Downsample(shared, ssaa, why))
      {
        return Fail("cannot write '" + path + "': " + why);
      }
    }
    images.push_back(shared);
  }
  if (!o.Interactive)
  {
    release.Now();
  }
  for (size_t i = 0; i < o.Outputs.size(); ++i)
  {
    const std::string& path = o.Outputs[i];
    const std::string& staging = outputs.StagingPath(i);
    vtkNew<vtkMRGIImageIO> io;
    io->SetHalfFloat(o.Half);
    // Its errors come back in GetLastErrorMessage(), for the one error line.
    vtkNew<vtkCallbackCommand> ignore;
    io->AddObserver(vtkCommand::ErrorEvent, ignore);
    const bool ok = (o.Reference || o.IndirectOnly) ? io->Write(images[i], staging.c_str())
      : EndsWith(path, ".exr")                      ? io->WriteEXR(images[i], staging.c_str())
                                                    : io->WritePNG(images[i], staging.c_str());
    if (!ok)
    {
      // ~Outputs removes what was staged: no output of this run is left.
      return Fail(std::string("cannot write '") + path + "': " + io->GetLastErrorMessage());
    }
    images[i] = nullptr; // the last holder of a shared image frees it now
  }
  if (!outputs.Commit(why))
  {
    return Fail(why + " (no output of this run is left)");
  }
  for (const std::string& path : o.Outputs)
  {
    Progress(o, "wrote " + path);
  }

  if (o.Interactive)
  {
    vtkNew<vtkRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(window);
    interactor->Initialize();
    interactor->Start();
  }
  release.Now();
  return 0;
}
