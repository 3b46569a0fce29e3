// mrgiRenderOptionTable: mrgi-render's options, one row each (names, value
// form, help text, handler), and the handler factories for the common kinds
// of values. mrgiRenderOptions.cxx builds the parser and --help from it.
#include "mrgiRenderOptionTable.h"

#include "mrgi_direct_shadow.h"
#include "mrgi_ism_visibility.h"

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
#include "vtkMRGIImperfectShadowMaps.h"
#include "vtkMRGIIndirectLight.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIUpsample.h"
#include "vtkMRGIVisibilityPyramid.h"
#include "vtkMRGIVoxelization.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReferenceRenderer.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMRGIRenderWindowFactory.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMRGIStaging.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkRenderStepsPass.h"
#include "vtkToneMappingPass.h"
#include "vtkDataArray.h"
#include "vtkRenderTimerLog.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkPointData.h"
#include "mrgi_ssao.h"
#include "mrgi_screen_space_preset.h"
#include "mrgi_ssgi.h"
#include "mrgi_error.h"
#include "mrgi_area_light.h"
#include "mrgi_box_filter.h"
#include "mrgi_exposure.h"
#include "mrgi_voxel.h"
#include "mrgi_multires.h"
#include "mrgi_parse.h"
#include "mrgi_vpl_tree_gather.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <strings.h>
#include <utility>
#include <vector>
#ifndef MRGI_VERSION_STRING
#define MRGI_VERSION_STRING "unknown"
#endif

// A default defined once in the core, spelled into help text: "0.02".
#define MRGI_OPTIONS_TEXT_(x) #x
#define MRGI_OPTIONS_TEXT(x) MRGI_OPTIONS_TEXT_(x)


namespace mrgirender
{
// ---- Handlers of the common kinds of values. ----

// A switch without a value: sets `field`.
OptionHandler Set(bool Options::*field)
{
  return [field](Options& o, const std::string&, const char*) {
    o.*field = true;
    return -1;
  };
}

// on | off.
OptionHandler OnOff(bool Options::*field)
{
  return [field](Options& o, const std::string& option, const char* v) {
    if (!ParseSwitch(v, "on", o.*field))
    {
      return Fail(option + " '" + v + "': expected on or off");
    }
    return -1;
  };
}

// A whole number in [lo, hi] (mrgi_parse_int64's message on failure).
OptionHandler Integer(long long Options::*field, int64_t lo, int64_t hi)
{
  return [field, lo, hi](Options& o, const std::string& option, const char* v) {
    int64_t value = 0;
    mrgi_error err;
    if (mrgi_parse_int64(v, lo, hi, &value, &err) != MRGI_OK)
    {
      return Fail(option + ": " + err.message);
    }
    o.*field = value;
    return -1;
  };
}

// A finite number that `accept` takes; `expected` ("expected ...") names the
// range in the error. `given`, when not null, is set too.
OptionHandler Number(double Options::*field, std::function<bool(double)> accept,
  const char* expected, bool Options::*given = nullptr)
{
  return [field, accept, expected, given](Options& o, const std::string& option, const char* v) {
    double value = 0;
    mrgi_error err;
    if (mrgi_parse_double(v, &value, &err) != MRGI_OK || !accept(value))
    {
      return Fail(option + " '" + v + "': " + expected);
    }
    o.*field = value;
    if (given)
    {
      o.*given = true;
    }
    return -1;
  };
}

// X,Y,Z (mrgi_parse_vec3's message on failure); `given`, when not null, is set too.
OptionHandler Vector(double (Options::*field)[3], bool Options::*given = nullptr)
{
  return [field, given](Options& o, const std::string& option, const char* v) {
    std::string why;
    if (!ParseVec3(option, v, o.*field, why))
    {
      return Fail(why);
    }
    if (given)
    {
      o.*given = true;
    }
    return -1;
  };
}

// One of a few words, each standing for a value of `field`.
template <typename T>
OptionHandler Choice(T Options::*field, std::vector<std::pair<std::string, T>> choices)
{
  std::string expected;
  for (size_t c = 0; c < choices.size(); ++c)
  {
    expected += (c == 0 ? "" : c + 1 == choices.size() ? " or " : ", ") + choices[c].first;
  }
  return [field, choices, expected](Options& o, const std::string& option, const char* v) {
    for (const auto& choice : choices)
    {
      if (choice.first == v)
      {
        o.*field = choice.second;
        return -1;
      }
    }
    return Fail(option + " '" + v + "': expected " + expected);
  };
}

// A staging option (--up, --ground, ...): `handler`, and noted as given, so
// that mrgi-render can say when no staging takes place to use it.
OptionHandler Staged(OptionHandler handler)
{
  return [handler](Options& o, const std::string& option, const char* v) {
    const int result = handler(o, option, v);
    if (result < 0)
    {
      o.StagingOptions += (o.StagingOptions.empty() ? "" : " ") + option;
    }
    return result;
  };
}

// --depth-threshold / --normal-threshold: a number >= 0, or inf (never
// refines; the pass takes -1 for it).
OptionHandler Threshold(double Options::*field)
{
  return [field](Options& o, const std::string& option, const char* v) {
    double value = 0;
    mrgi_error err;
    if (std::strcmp(v, "inf") == 0)
    {
      value = -1.0; // off
    }
    else if (mrgi_parse_double(v, &value, &err) != MRGI_OK || !(value >= 0) || !(value <= 1e30))
    {
      return Fail(option + " '" + v + "': expected a number in [0, 1e30] or inf");
    }
    o.*field = value;
    return -1;
  };
}

// The help of --tree-threshold states the default.
static_assert(MRGI_VPL_TREE_DEFAULT_THRESHOLD == 0.05, "update the --tree-threshold help");

// --cluster-depth-threshold / --cluster-normal-threshold / --tree-threshold:
// a number >= 0, or inf (never splits; the VPL selection takes +inf for it).
OptionHandler ClusterThreshold(double Options::*field)
{
  return [field](Options& o, const std::string& option, const char* v) {
    double value = 0;
    mrgi_error err;
    if (std::strcmp(v, "inf") == 0)
    {
      value = std::numeric_limits<double>::infinity();
    }
    else if (mrgi_parse_double(v, &value, &err) != MRGI_OK || !(value >= 0) || !(value <= 1e30))
    {
      return Fail(option + " '" + v + "': expected a number in [0, 1e30] or inf");
    }
    o.*field = value;
    return -1;
  };
}

// `handler`, and `given` set when it accepted the value (a knob that
// overrides a preset's).
OptionHandler Given(OptionHandler handler, bool Options::*given)
{
  return [handler, given](Options& o, const std::string& option, const char* v) {
    const int rc = handler(o, option, v);
    if (rc < 0)
    {
      o.*given = true;
    }
    return rc;
  };
}

std::vector<std::pair<std::string, long long>> ScreenSpacePresetChoices()
{
  std::vector<std::pair<std::string, long long>> choices;
  for (int p = 0; p < MRGI_SCREEN_SPACE_PRESET_COUNT; ++p)
  {
    choices.emplace_back(mrgi_screen_space_preset_name(p), p);
  }
  return choices;
}

std::vector<std::pair<std::string, long long>> PresetChoices()
{
  std::vector<std::pair<std::string, long long>> choices;
  for (int p = 0; p < MRGI_MULTIRES_PRESET_COUNT; ++p)
  {
    choices.emplace_back(mrgi_multires_preset_name(p), p);
  }
  return choices;
}

// ---- The table. ----

const std::vector<OptionSection>& OptionTable()
{
  static const std::vector<OptionSection> table = {
    { "Output",
      {
        { { "-o", "--output" }, "FILE",
          ".png (what the window shows, 8-bit) or .exr (the HDR\n"
          "float buffer); repeat to write several files",
          [](Options& o, const std::string&, const char* v) {
            if (!EndsWith(v, ".png") && !EndsWith(v, ".exr"))
            {
              return Fail(
                std::string("output '") + v + "': the file name must end in .png or .exr");
            }
            o.Outputs.emplace_back(v);
            return -1;
          } },
        { { "--half" }, nullptr, "write EXR channels as 16-bit half floats (default 32-bit)",
          Set(&Options::Half) },
        { { "--size" }, "WxH", "image size in pixels (default 512x512)",
          [](Options& o, const std::string&, const char* v) {
            int32_t w = 0, h = 0;
            mrgi_error err;
            if (mrgi_parse_size(v, &w, &h, &err) != MRGI_OK)
            {
              return Fail(std::string("--size: ") + err.message);
            }
            o.Width = w;
            o.Height = h;
            return -1;
          } },
        { { "--background" }, "R,G,B", "background colour, each >= 0 (default 0,0,0)",
          [](Options& o, const std::string& option, const char* v) {
            double rgb[3];
            std::string why;
            if (!ParseVec3(option, v, rgb, why))
            {
              return Fail(why);
            }
            if (!(rgb[0] >= 0 && rgb[1] >= 0 && rgb[2] >= 0))
            {
              return Fail(option + " '" + v + "': each component must be >= 0");
            }
            std::copy(rgb, rgb + 3, o.Background);
            return -1;
          } },
      } },
    { "Camera (built-in scenes bring theirs; files are framed automatically)",
      {
        { { "--camera-position" }, "X,Y,Z", "", Vector(&Options::Position, &Options::HasPosition) },
        { { "--camera-focal-point" }, "X,Y,Z", "", Vector(&Options::Focal, &Options::HasFocal) },
        { { "--camera-view-up" }, "X,Y,Z", "", Vector(&Options::Up, &Options::HasUp) },
        { { "--camera-view-angle" }, "DEG", "vertical field of view, degrees",
          Number(
            &Options::Angle, [](double a) { return a > 0 && a < 180; },
            "expected degrees in (0, 180)", &Options::HasAngle) },
        { { "--auto-camera" }, nullptr, "frame the whole scene (keeps the view direction)",
          Set(&Options::AutoCamera) },
        { { "--parallel" }, nullptr, "parallel (orthographic) projection",
          Set(&Options::Parallel) },
      } },
    { "Lights (replace the scene's lights when given; repeatable)",
      {
        { { "--light" }, "SPEC",
          "add a light; SPEC is one of\n"
          "  positional:X,Y,Z\n"
          "  spot:X,Y,Z:FX,FY,FZ:CONE  CONE = half angle in degrees\n"
          "  directional:DX,DY,DZ      direction the light travels\n"
          "  headlight",
          [](Options& o, const std::string&, const char* v) {
            // Checked now, so that nothing is built before a bad value is refused.
            vtkSmartPointer<vtkLight> light;
            std::string why;
            if (!ParseLight(v, light, why))
            {
              return Fail(why);
            }
            o.Lights.emplace_back(v);
            return -1;
          } },
        { { "--light-intensity" }, "S", "multiply every light's intensity by S, 0..1e6",
          Number(
            &Options::LightIntensity, [](double s) { return s >= 0 && s <= 1e6; },
            "expected a number in [0, 1e6]", &Options::HasLightIntensity) },
      } },
    { "Area lights (direct light from textured rectangles, nichols-penmatsa-wyman-2010;\n"
      "Documentation/AreaLights.md; drawn whatever --gi says)",
      {
        { { "--area-light" }, "CX,CY,CZ:UX,UY,UZ:VX,VY,VZ[:R,G,B[:I]]",
          "add a rectangle: centre, full edge vectors u and v\n"
          "(perpendicular; it emits towards u x v), colour, intensity\n"
          "(radiance = I x colour, I in 0..1e6; default 1,1,1 and 1); repeatable;\n"
          "cornell-area brings the Cornell box's emitter",
          [](Options& o, const std::string&, const char* v) {
            vtkNew<vtkMRGIAreaLight> light;
            std::string why;
            if (!ParseAreaLight(v, light, why))
            {
              return Fail(why);
            }
            o.AreaLights.emplace_back(v);
            return -1;
          } },
        { { "--area-light-two-sided" }, nullptr, "emit on both sides (every area light)",
          Set(&Options::AreaLightTwoSided) },
        { { "--area-light-samples" }, "N",
          "light samples per area light, 1..4096 (default 256; above 512,\n"
          "incremental visibility falls back to naive, with a warning)",
          Integer(
            &Options::AreaLightSamples, MRGI_AREA_LIGHT_MIN_SAMPLES, MRGI_AREA_LIGHT_MAX_SAMPLES) },
        { { "--area-lights" }, "on|off",
          "off: ignore the scene's and the command line's area lights (default on)",
          OnOff(&Options::AreaLightsOn) },
        { { "--area-light-visibility" }, "off|naive|incremental",
          "shadows: none; a march through screen-space voxels per texel and\n"
          "light sample; or coarse to fine, reusing agreeing coarse samples\n"
          "(default incremental; nichols-penmatsa-wyman-2010 3.3)",
          Choice<int>(&Options::AreaLightVisibility,
            { { "off", vtkMRGIPass::VisibilityOff }, { "naive", vtkMRGIPass::VisibilityNaive },
              { "incremental", vtkMRGIPass::VisibilityIncremental } }) },
        { { "--voxel-size" }, "N",
          "voxel buffer side for the area lights' visibility, 1..4096 and at most\n"
          "the OpenGL's largest 3D texture (GL_MAX_3D_TEXTURE_SIZE; 2048 on\n"
          "llvmpipe); default: automatic, voxels about as wide as deep, 128..512",
          Integer(&Options::VoxelSize, 1, MaxVoxelSize) },
        { { "--voxel-slices" }, "128|256|384|512",
          "depth slices per voxel pixel for the area lights' visibility; each 128\n"
          "is one render target: thinner voxels, finer penumbrae past edges\n"
          "(default " MRGI_OPTIONS_TEXT(MRGI_VOXEL_AREA_LIGHT_SLICES) ")",
          Choice<int>(&Options::VoxelSlices,
            { { "128", 128 }, { "256", 256 }, { "384", 384 }, { "512", 512 } }) },
        { { "--voxel-offset" }, "normals|receiver|both",
          "direction of the march's bias at the ends: along their normals (default),\n"
          "along the ray at the receiver, or at both ends (keeps penumbrae past edges)",
          Choice<int>(&Options::VoxelOffset,
            { { "normals", vtkMRGIVoxelization::OffsetNormals },
              { "receiver", vtkMRGIVoxelization::OffsetRayAtReceiver },
              { "both", vtkMRGIVoxelization::OffsetRayAtBoth } }) },
        { { "--visibility-interleave" }, "on|off",
          "incremental visibility: 2x2 interleaved light samples (default off)",
          OnOff(&Options::VisibilityInterleave) },
        { { "--incremental-stencil" }, "on|off",
          "incremental visibility: also gather below the geometric selection where\n"
          "the coarser level's visibility changes, e.g. penumbrae (default on;\n"
          "nichols-penmatsa-wyman-2010 3.4)",
          OnOff(&Options::IncrementalStencil) },
        { { "--area-light-specular" }, "on|off",
          "Phong highlights of the area lights on specular materials (default on)",
          OnOff(&Options::AreaLightSpecular) },
        { { "--area-light-specular-resolution" }, "full|multires",
          "where the highlights are gathered: every pixel (default), or the\n"
          "multiresolution texels refined where the Phong lobe is narrower than\n"
          "the texel spacing, then upsampled (nichols-penmatsa-wyman-2010 3.2.1;\n"
          "experimental: up to ~34% error on the highlight on flat scenes)",
          Choice<int>(&Options::AreaLightSpecularResolution,
            { { "full", vtkMRGIPass::SpecularFullResolution },
              { "multires", vtkMRGIPass::SpecularMultiresolution } }) },
        { { "--specular" }, "KS:POWER",
          "give every opaque surface VTK's Specular KS (0..1) and SpecularPower\n"
          "POWER (0..128), e.g. 0.5:40, to see the highlights",
          [](Options& o, const std::string&, const char* v) {
            const std::vector<std::string> parts = SplitColon(v);
            mrgi_error err;
            if (parts.size() != 2 ||
              mrgi_parse_double(parts[0].c_str(), &o.SpecularCoefficient, &err) != MRGI_OK ||
              mrgi_parse_double(parts[1].c_str(), &o.SpecularPower, &err) != MRGI_OK ||
              !(o.SpecularCoefficient >= 0 && o.SpecularCoefficient <= 1) ||
              !(o.SpecularPower >= 0 && o.SpecularPower <= 128))
            {
              return Fail(std::string("--specular '") + v +
                "': expected KS:POWER with KS in [0, 1] and POWER in [0, 128]");
            }
            o.HasSpecular = true;
            return -1;
          } },
      } },
    { "Scaling scene",
      {
        { { "--triangles" }, "N", "total triangle count, 12..20000000 (default 100000)",
          Integer(&Options::Triangles, 12, 20000000) },
        { { "--objects" }, "N", "number of objects, 1..4096 (default 64)",
          Integer(&Options::Objects, 1, 4096) },
        { { "--seed" }, "N",
          "random seed of the generated scenes and of --reference, >= 0 (default 1)",
          Integer(&Options::Seed, 0, INT64_MAX) },
      } },
    { "Staging of data files (Documentation/Staging.md; built-in scenes bring\n"
      "their own camera and lights and are never staged)",
      {
        { { "--stage" }, "on|off",
          "on (default): detect the up axis, frame the data, add a ground and a\n"
          "key light, show volumes as iso-surfaces; off: VTK's framing and\n"
          "headlight, volumes as their outer surface",
          OnOff(&Options::Stage) },
        { { "--up" }, "auto|x|y|z|-x|-y|-z",
          "the data's up axis (default auto: LAS/PCD metadata, a flat or\n"
          "open base, a thin extent, else y)",
          Staged(Choice<int>(&Options::StageUp,
            { { "auto", vtkMRGIStaging::UpAuto }, { "x", vtkMRGIStaging::UpPositiveX },
              { "y", vtkMRGIStaging::UpPositiveY }, { "z", vtkMRGIStaging::UpPositiveZ },
              { "-x", vtkMRGIStaging::UpNegativeX }, { "-y", vtkMRGIStaging::UpNegativeY },
              { "-z", vtkMRGIStaging::UpNegativeZ } })) },
        { { "--ground" }, "on|off", "a grey matte ground under the data (default on)",
          Staged(OnOff(&Options::StageGround)) },
        { { "--key-light" }, "spot|area|none",
          "the light from above and in front: a spot light (default), an area\n"
          "light, or none (the scene's lights, VTK's headlight)",
          Staged(Choice<int>(&Options::StageKeyLight,
            { { "spot", vtkMRGIStaging::KeyLightSpot }, { "area", vtkMRGIStaging::KeyLightArea },
              { "none", vtkMRGIStaging::KeyLightNone } })) },
        { { "--fill" }, "F",
          "fraction of the image width or height the data fills, 0.05..1\n"
          "(default 0.8)",
          Staged(Number(
            &Options::StageFill, [](double f) { return f >= 0.05 && f <= 1.0; },
            "expected a number in [0.05, 1]")) },
        { { "--iso" }, "V", "volumes: the iso-value (default Otsu's threshold of the scalars)",
          Staged(Number(
            &Options::Iso, [](double v) { return std::fabs(v) <= MaxFloatValue; },
            "expected a finite number", &Options::HasIso)) },
      } },
    { "Direct shadows (Documentation/DirectShadows.md)",
      {
        { { "--direct-shadows" }, "off|hard|soft",
          "shadows in VTK's direct light, from the reflective shadow maps, for\n"
          "the first two lights: hard (percentage-closer filtering) or soft\n"
          "(PCSS); lit pixels keep VTK's colour exactly (default soft with\n"
          "--gi on/full, off with --gi off or --indirect-only)",
          Choice<int>(&Options::DirectShadows,
            { { "off", vtkMRGIPass::DirectShadowsOff }, { "hard", vtkMRGIPass::DirectShadowsHard },
              { "soft", vtkMRGIPass::DirectShadowsSoft } }) },
        { { "--shadow-kernel" }, "N",
          "soft shadows: filter taps per side, 1..14 (N x N taps; default 8)",
          Given(Integer(&Options::ShadowKernel, 1, MRGI_DIRECT_SHADOW_MAX_SIDE),
            &Options::HasShadowKernel) },
        { { "--shadow-light-radius" }, "R",
          "soft shadows: the lights' radius in scene units, > 0 (default: 1% of\n"
          "the scene's bounding radius)",
          Number(
            &Options::ShadowLightRadius, [](double r) { return r > 0 && r <= MaxFloatValue; },
            "expected a positive finite number") },
        { { "--shadow-resolution" }, "full|multires",
          "shadow factors at every pixel (default) or BMR's four levels under\n"
          "edge stencils, blended (Documentation/ScreenSpaceEffects-Benchmark.md)",
          Given(Choice<bool>(&Options::ShadowMultires, { { "full", false }, { "multires", true } }),
            &Options::HasShadowResolution) },
      } },
    { "Indirect light (one bounce; Documentation/IndirectLight.md)",
      {
        { { "--gi" }, "on|multires|full|off",
          "on = multires (default): the stencil-selected multiresolution gather;\n"
          "full: every pixel gathers every VPL; off: VTK's direct light only",
          [](Options& o, const std::string&, const char* v) {
            o.Multires = std::strcmp(v, "multires") == 0 || std::strcmp(v, "on") == 0;
            if (!o.Multires && !ParseSwitch(v, "full", o.GI))
            {
              return Fail(std::string("--gi '") + v + "': expected off, on, multires or full");
            }
            if (o.Multires)
            {
              o.GI = true;
            }
            return -1;
          } },
        { { "--preset" }, "fast|balanced|accurate",
          "multires settings from the measured speed/accuracy frontier\n"
          "(default balanced; Documentation/Multiresolution.md); the options\n"
          "below override single knobs",
          Choice<long long>(&Options::Preset, PresetChoices()) },
        { { "--depth-threshold" }, "T",
          "multires: depth change per pixel width that refines, 0..1e30 (inf: never;\n"
          "the indirect light and the area lights alike)",
          Threshold(&Options::DepthThreshold) },
        { { "--normal-threshold" }, "T",
          "multires: normal-component spread that refines, 0..1e30 (inf: never)",
          Threshold(&Options::NormalThreshold) },
        { { "--finest-level" }, "N",
          "multires: finest level that gathers, 0..23 (0 = full resolution)",
          Integer(&Options::FinestLevel, 0, MRGI_MULTIRES_MAX_LEVELS - 1) },
        { { "--refinement" }, "geometry|illumination",
          "multires: refine at depth/normal discontinuities only (geometry), or also\n"
          "where neighbouring coarse results of the indirect light differ\n"
          "(illumination, gathered coarse to fine; default: the preset's, illumination\n"
          "for balanced and accurate)",
          Choice<int>(&Options::Refinement,
            { { "geometry", vtkMRGIMultiresolution::RefinementGeometry },
              { "illumination", vtkMRGIMultiresolution::RefinementIllumination } }) },
        { { "--illumination-threshold" }, "T",
          "multires, illumination: relative difference of neighbouring coarse\n"
          "results that refines, 0..1e30 (0: all; default: the preset's)",
          Number(
            &Options::IlluminationThreshold, [](double t) { return t >= 0 && t <= 1e30; },
            "expected a number in [0, 1e30]") },
        { { "--illumination-metric" }, "difference|curvature",
          "multires, illumination: neighbours differ (NPW10's test), or the centre\n"
          "leaves the line through opposite neighbours (linear changes do not refine)",
          Choice<int>(&Options::IlluminationMetric, { { "difference", 0 }, { "curvature", 1 } }) },
        { { "--upsample" }, "tent|mask",
          "multires: tent (default) or mask-weighted (Besenthal) upsampling",
          Choice<bool>(&Options::MaskUpsampling, { { "tent", false }, { "mask", true } }) },
        { { "--gather" }, "stencil|splat",
          "multires: stenciled gather (default) or multiresolution splatting\n"
          "(nichols-wyman-2009; same image, slower: for comparisons)",
          Choice<bool>(&Options::Splatting, { { "stencil", false }, { "splat", true } }) },
        { { "--surface-detail" }, "A",
          "multires: modulate by the view angle, nichols-wyman-2009 eq. 2 (0..1, default 0)",
          Number(
            &Options::SurfaceDetail, [](double a) { return a >= 0 && a <= 1; },
            "expected a number in [0, 1]") },
        { { "--vpls" }, "N", "virtual point lights, 0..4096 (default 256 = 16x16)",
          Integer(&Options::VPLs, 0, 4096) },
        { { "--vpl-selection" }, "grid|importance|clusters|tree|brsm",
          "regular grid over the light's view (default), flux importance sampling,\n"
          "multiresolution clusters (nichols-shopf-wyman-2009 3.4; a variable\n"
          "count up to 4096, --vpls does not apply), the VPL tree (3.5; each\n"
          "pixel walks the RSM's pyramid, --tree-threshold; --vpls does not apply)\n"
          "or bidirectional RSM importance (ritschel-et-al-2011 4, 6.5: texels\n"
          "weighted by their light on view samples of the frame)",
          Choice<int>(&Options::VPLSelection,
            { { "grid", vtkMRGIVPLSelection::Grid },
              { "importance", vtkMRGIVPLSelection::FluxImportance },
              { "clusters", vtkMRGIVPLSelection::Clusters }, { "tree", vtkMRGIVPLSelection::Tree },
              { "brsm", vtkMRGIVPLSelection::BRSM } }) },
        { { "--cluster-depth-threshold" }, "D",
          "clusters: light-space depth change per texel width that splits a patch,\n"
          "0..1e30 (inf: never; default 4)",
          ClusterThreshold(&Options::ClusterDepthThreshold) },
        { { "--cluster-normal-threshold" }, "N",
          "clusters: light-space normal-component spread that splits a patch,\n"
          "0..1e30 (inf: never; default 0.25)",
          ClusterThreshold(&Options::ClusterNormalThreshold) },
        { { "--tree-threshold" }, "T",
          "tree: a node is split where its form-factor bound exceeds T, 0..1e30\n"
          "(0: every RSM texel is a VPL; >= 1 or inf: the 16x16 roots; default 0.05)",
          ClusterThreshold(&Options::TreeThreshold) },
        { { "--rsm-size" }, "N", "reflective shadow map texels per side, 16..2048 (default 256)",
          Integer(&Options::RSMSize, 16, 2048) },
        { { "--indirect-visibility" }, "off|ism|voxel",
          "visibility of the VPLs, i.e. indirect shadows (default off: light bounces\n"
          "through occluders); ism: imperfect shadow maps (ritschel-et-al-2011);\n"
          "voxel: screen-space voxels of their own (--timings gives their size),\n"
          "blind to what the camera does not see",
          Choice<int>(&Options::IndirectVisibility,
            { { "off", vtkMRGIIndirectLight::VisibilityOff },
              { "ism", vtkMRGIIndirectLight::VisibilityISM },
              { "voxel", vtkMRGIIndirectLight::VisibilityVoxels } }) },
        { { "--ism-points" }, "N", "ism: points drawn into each VPL's map, 1..65536 (default 256)",
          Integer(&Options::ISMPointsPerVPL, 1, 65536) },
        { { "--ism-tile" }, "N", "ism: map side per VPL, a power of two 4..1024 (default 32)",
          Integer(&Options::ISMTileSize, 4, MRGI_ISM_MAX_TILE) },
        { { "--ism-point-mode" }, "uniform|adaptive1|adaptive8",
          "ism: point density by area, or view-adaptive from 1 or 8 view samples\n"
          "per triangle (ritschel-et-al-2011 5.2; default adaptive8)",
          Choice<int>(&Options::ISMPointMode,
            { { "uniform", vtkMRGIImperfectShadowMaps::Uniform },
              { "adaptive1", vtkMRGIImperfectShadowMaps::Adaptive1 },
              { "adaptive8", vtkMRGIImperfectShadowMaps::Adaptive8 } }) },
        { { "--ism-lazy-frames" }, "N",
          "ism: resample 1/N of the points per frame, 1..64 (default 8; 1: all)",
          Integer(&Options::ISMLazyFrames, 1, 64) },
        { { "--ism-bias" }, "B",
          "ism: depth bias as a fraction of the distance, 0..16 (default 0.02)",
          Number(
            &Options::ISMBias, [](double b) { return b >= 0 && b <= MRGI_ISM_MAX_BIAS; },
            "expected a number in [0, 16]") },
        { { "--ism-pcf" }, "on|off", "ism: 2x2 percentage-closer filtering (default on)",
          OnOff(&Options::ISMFiltering) },
        { { "--ism-texel-bias" }, "T",
          "ism: depth bias in texel footprints, 0..16 (default 1.5; 3 for dense maps)",
          Number(
            &Options::ISMTexelBias, [](double b) { return b >= 0 && b <= MRGI_ISM_MAX_BIAS; },
            "expected a number in [0, 16]") },
        { { "--ism-max-texel-angle" }, "A",
          "ism: no shadow test in directions whose map texel spans more than A radians,\n"
          "near each VPL's horizon, 0..4 (default 0.16; 0: test every direction)",
          Number(
            &Options::ISMMaxTexelAngle,
            [](double a) { return a >= 0 && a <= MRGI_ISM_MAX_TEXEL_ANGLE_LIMIT; },
            "expected a number in [0, 4] (radians)") },
        { { "--ism-push-pull" }, "LEVELS",
          "ism: push-pull hole filling over LEVELS mip levels of each tile, 0..16 (default 1: "
          "holes filled from their 2x2 block; 0: off)",
          Integer(&Options::ISMPushPullLevels, 0, MRGI_ISM_MAX_PUSH_PULL_LEVELS) },
        { { "--indirect-strength" }, "S", "factor on the indirect light (default 1)",
          Number(
            &Options::IndirectStrength, [](double s) { return s >= 0 && s <= 1e6; },
            "expected a number in [0, 1e6]") },
        { { "--indirect-only" }, nullptr, "write only the indirect light (EXR: float RGB)",
          Set(&Options::IndirectOnly) },
      } },
    { "Screen-space effects' preset (SSAO, soft shadows, SSGI;\n"
      "Documentation/ScreenSpaceEffects.md)",
      {
        { { "--screen-space-preset" }, "fast|balanced|accurate",
          "SSAO samples, soft-shadow taps, SSGI samples, the three resolutions\n"
          "and the BMR mask thresholds from one table (default none: the\n"
          "values of balanced); the knobs given explicitly override it. It\n"
          "switches no effect on, and is independent of --preset (indirect light)",
          Choice<long long>(&Options::ScreenSpacePreset, ScreenSpacePresetChoices()) },
      } },
    { "Ambient occlusion of the direct light, as vtkSSAOPass computes it\n"
      "(Documentation/ScreenSpaceEffects-SSAO.md)",
      {
        { { "--ssao" }, "on|off", "screen-space ambient occlusion (default off)",
          OnOff(&Options::SSAO) },
        { { "--ssao-samples" }, "N", "SSAO kernel samples, 1..1000 (default 32, vtkSSAOPass's)",
          Given(Integer(&Options::SSAOSamples, 1, MRGI_SSAO_MAX_KERNEL_SIZE),
            &Options::HasSSAOSamples) },
        { { "--ssao-radius" }, "R",
          "SSAO kernel radius in world units, > 0 (default 2% of the scene's\n"
          "bounding-box diagonal)",
          Number(
            &Options::SSAORadius, [](double r) { return r > 0 && r <= MaxFloatValue; },
            "expected a finite number > 0", &Options::HasSSAORadius) },
        { { "--ssao-bias" }, "B",
          "SSAO depth bias in world units (default radius / 50, vtkSSAOPass's ratio)",
          Number(
            &Options::SSAOBias, [](double b) { return std::fabs(b) <= MaxFloatValue; },
            "expected a finite number", &Options::HasSSAOBias) },
        { { "--ssao-blur" }, "on|off", "vtkSSAOPass's 3x3 blur of the occlusion (default off)",
          OnOff(&Options::SSAOBlur) },
        { { "--ssao-resolution" }, "full|multires",
          "every pixel (default) or BMR's four levels under edge stencils,\n"
          "blended (Documentation/ScreenSpaceEffects-SSAO.md)",
          Given(Choice<bool>(&Options::SSAOMultires, { { "full", false }, { "multires", true } }),
            &Options::HasSSAOResolution) },
      } },
    { "Screen-space one-bounce light (Documentation/ScreenSpaceEffects-SSGI.md)",
      {
        { { "--ssgi" }, "on|off",
          "screen-space one bounce from the direct light (default off); it\n"
          "replaces the VPL gather (the two are exclusive)",
          OnOff(&Options::SSGI) },
        { { "--ssgi-samples" }, "N", "SSGI hemisphere samples, 1..512 (default 64)",
          Given(
            Integer(&Options::SSGISamples, 1, MRGI_SSGI_MAX_SAMPLES), &Options::HasSSGISamples) },
        { { "--ssgi-radius" }, "R",
          "SSGI sample radius in world units, > 0 (default 10% of the scene's\n"
          "bounding-box diagonal; depth bias radius / 50)",
          Number(
            &Options::SSGIRadius, [](double r) { return r > 0 && r <= MaxFloatValue; },
            "expected a finite number > 0", &Options::HasSSGIRadius) },
        { { "--ssgi-resolution" }, "full|multires",
          "every pixel (default) or BMR's levels under edge stencils (Table 1's\n"
          "SSGI row: level 2 skipped), blended (Documentation/ScreenSpaceEffects-SSGI.md)",
          Given(Choice<bool>(&Options::SSGIMultires, { { "full", false }, { "multires", true } }),
            &Options::HasSSGIResolution) },
      } },
    { "Exposure and anti-aliasing (the PNG; EXR files keep the unscaled HDR radiance,\n"
      "and a run writing only EXR files skips these steps)",
      {
        { { "--exposure" }, "EV|auto[:KEY]",
          "scale the image by 2^EV before tone mapping (-20..20), or pick EV per\n"
          "frame so the log-average luminance of the drawn pixels (background\n"
          "ignored) becomes KEY (Reinhard 2002; default auto, KEY 0.18)",
          [](Options& o, const std::string& option, const char* v) {
            const std::string text = v;
            mrgi_error err;
            if (text.compare(0, 4, "auto") == 0 &&
              (text.size() == 4 ||
                (text[4] == ':' &&
                  mrgi_parse_double(text.c_str() + 5, &o.ExposureKey, &err) == MRGI_OK &&
                  o.ExposureKey > 0 && o.ExposureKey <= 1)))
            {
              o.AutoExposure = true;
              return -1;
            }
            if (text.compare(0, 4, "auto") != 0 &&
              mrgi_parse_double(v, &o.Exposure, &err) == MRGI_OK &&
              o.Exposure >= MRGI_EXPOSURE_MIN_EV && o.Exposure <= MRGI_EXPOSURE_MAX_EV)
            {
              o.AutoExposure = false;
              return -1;
            }
            return Fail(option + " '" + v +
              "': expected a number of stops in [-20, 20], auto, or auto:KEY with KEY in (0, 1]");
          } },
        { { "--tone-mapping" }, nullptr,
          "roll highlights off smoothly instead of clipping them; values up to\n"
          "0.5, mid-grey included, are kept (never darkens the mid-tones)",
          Set(&Options::ToneMapping) },
        { { "--aa" }, "off|fxaa|ssaa:N",
          "anti-aliasing: none; FXAA on the final image (default: one\n"
          "full-screen pass); or render N x N times the pixels (N = 2..8) and\n"
          "average each N x N block (N^2 times the cost; also for EXR)",
          [](Options& o, const std::string& option, const char* v) {
            const std::string text = v;
            int64_t n = 0;
            mrgi_error err;
            if (text == "off" || text == "fxaa")
            {
              o.AntiAliasing = text == "off" ? Options::AAOff : Options::AAFXAA;
              o.SSAAFactor = 1;
              return -1;
            }
            if (text.compare(0, 5, "ssaa:") == 0 &&
              mrgi_parse_int64(text.c_str() + 5, 2, 8, &n, &err) == MRGI_OK)
            {
              o.AntiAliasing = Options::AASSAA;
              o.SSAAFactor = static_cast<int>(n);
              return -1;
            }
            return Fail(option + " '" + v + "': expected off, fxaa or ssaa:N with N in 2..8");
          } },
      } },
    { "Ground truth (CPU, Embree: direct light and one bounce with exact visibility)",
      {
        { { "--reference" }, nullptr, "render the ground truth instead of the GPU image",
          Set(&Options::Reference) },
        { { "--reference-visibility" }, "on|off",
          "exact visibility between bounce points (default on); off = the RSM assumption",
          OnOff(&Options::ReferenceVisibility) },
        { { "--reference-shadows" }, "on|off",
          "shadows in the direct part (default on; VTK's direct light has none)",
          OnOff(&Options::ReferenceShadows) },
        { { "--reference-pixel" }, "box|center",
          "box: each pixel the mean over its area (default); center: primary rays\n"
          "through the pixel's centre, the truth of an image sampled as the GPU samples it",
          Choice<int>(&Options::ReferencePixel,
            { { "box", vtkMRGIReferenceRenderer::PixelBox },
              { "center", vtkMRGIReferenceRenderer::PixelCenter } }) },
        { { "--reference-error" }, "E",
          "stop when the per-pixel relative standard error of the indirect part (each pixel's\n"
          "over max(its value, the image's mean)) is at most E at --reference-percentile;\n"
          "0 = run all passes (default " MRGI_OPTIONS_TEXT(MRGI_REFERENCE_DEFAULT_TARGET) ")",
          Number(
            &Options::ReferenceError, [](double e) { return e >= 0 && e <= 1; },
            "expected a number in [0, 1]") },
        { { "--reference-percentile" }, "P",
          "the share of pixels that must reach --reference-error, in (0, 1]\n"
          "(default " MRGI_OPTIONS_TEXT(MRGI_REFERENCE_DEFAULT_PERCENTILE) ")",
          Number(
            &Options::ReferencePercentile, [](double p) { return p > 0 && p <= 1; },
            "expected a number in (0, 1]") },
        { { "--reference-passes" }, "N",
          "at most N passes of 16 bounce rays per pixel (default " MRGI_OPTIONS_TEXT(
            MRGI_REFERENCE_DEFAULT_MAX_PASSES) ")",
          Integer(&Options::ReferencePasses, 1, 100000) },
        { { "--progress" }, nullptr,
          "the ground truth's progress (passes, error, time left), at most once a second,\n"
          "even when stderr is no terminal (a terminal always gets it, unless -q)",
          Set(&Options::ReferenceProgress) },
      } },
    { "Measurement",
      {
        { { "--timings" }, nullptr, "print the GPU time of each stage (vtkRenderTimerLog)",
          Set(&Options::Timings) },
        { { "--frames" }, "N", "render N frames, 1..1000000; timings are medians (default 1)",
          Integer(&Options::Frames, 1, 1000000) },
        { { "--frame-budget" }, "MS",
          "choose preset, VPLs, RSM and voxel size each frame to meet MS ms\n"
          "(0 < MS <= 1e6; least predicted error, hysteresis between frames;\n"
          "calibrates once per GL renderer if no calibration is stored)",
          Number(
            &Options::FrameBudget, [](double ms) { return ms > 0 && ms <= 1e6; },
            "expected a frame time in ms, 0 < MS <= 1e6") },
        { { "--error-budget" }, "E",
          "the cheapest settings predicted within relative RMS error E of the\n"
          "dense reference, 0 < E <= 1 (--frame-budget wins when both are given)",
          Number(
            &Options::ErrorBudget, [](double e) { return e > 0 && e <= 1; },
            "expected a relative RMS error, 0 < E <= 1") },
        { { "--calibrate" }, nullptr,
          "measure this machine's frame cost model again and store it\n"
          "(XDG_CACHE_HOME/mrgi or ~/.cache/mrgi, keyed by the GL renderer)",
          Set(&Options::Calibrate) },
      } },
    { "Other",
      {
        { { "--interactive" }, nullptr, "open a window to look around (needs DISPLAY)",
          Set(&Options::Interactive) },
        { { "--backend" }, "auto|egl|osmesa|x",
          "render window backend; a named one that fails is an error (default: MRGI_BACKEND, "
          "else auto: EGL, then OSMesa)",
          Choice<std::string>(&Options::Backend,
            { { "auto", "auto" }, { "egl", "egl" }, { "osmesa", "osmesa" }, { "x", "x" } }) },
        { { "-q", "--quiet" }, nullptr, "no progress lines", Set(&Options::Quiet) },
        { { "--allow-empty" }, nullptr,
          "accept an image that shows only the background (default: an error, exit 1)",
          Set(&Options::AllowEmpty) },
        { { "--version" }, nullptr, "print the version",
          [](Options&, const std::string&, const char*) {
            std::printf("mrgi-render %s\n", MRGI_VERSION_STRING);
            return 0;
          } },
        { { "-h", "--help" }, nullptr, "this text",
          [](Options&, const std::string&, const char*) {
            PrintUsage(stdout);
            return 0;
          } },
      } },
  };
  return table;
}

}
