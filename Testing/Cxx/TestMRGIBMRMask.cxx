// The GPU's BMR masks and stencils (vtkMRGIBMRMask into vtkMRGIBMRLevels)
// against their C twin (mrgi_bmr_mask.h): per level E, NE, R and S exact,
// the stencil bytes exactly S, the masks a_k within 1e-4 relative. On
// renders through vtkMRGIPass (Cornell boxes, perspective and parallel, odd
// sizes, 1 x 1, the three presets, thresholds 0 and off, min combination,
// a shadow image, the NW09 flags as source) and on random G-buffers with
// NaN and infinite texels. Prints the fraction of pixels per finest level.
#include "mrgiBMRTestUtilities.h"

#include "vtkMRGIMultiresolution.h"

#include <cstdio>
#include <string>

namespace
{
struct Settings
{
  int Preset = vtkMRGIBMRMask::SSAO;
  double DepthThreshold = -2.0; // -2: the preset's
  double NormalThreshold = -2.0;
  int Combine = vtkMRGIBMRMask::CombineMax;
  bool Shadow = false;
  bool Flags = false;
};

// Build on the GPU and in C, compare everything; returns the C masks' stats.
mrgi_bmr_stats Compare(bmrtest::Scene& s, const Settings& settings, const char* label)
{
  vtkNew<vtkMRGIBMRLevels> levels;
  vtkNew<vtkMRGIBMRMask> gpu;
  gpu->SetPreset(settings.Preset);
  if (settings.DepthThreshold > -2.0)
  {
    gpu->SetDepthThreshold(settings.DepthThreshold);
  }
  if (settings.NormalThreshold > -2.0)
  {
    gpu->SetNormalThreshold(settings.NormalThreshold);
  }
  gpu->SetCombine(settings.Combine);
  MRGI_TEST_CHECK(levels->Prepare(s.GL, s.W, s.H));
  const size_t n = static_cast<size_t>(s.W) * static_cast<size_t>(s.H);

  // A shadow image: lit where the eye-space x is above the middle of the
  // valid pixels' range (a straight shadow edge across the scene).
  std::vector<float> shadowRGBA, shadow;
  if (settings.Shadow)
  {
    float lo = INFINITY, hi = -INFINITY;
    for (size_t p = 0; p < n; ++p)
    {
      if (s.Position[4 * p + 3] > 0.5f && std::isfinite(s.Position[4 * p]))
      {
        lo = std::fmin(lo, s.Position[4 * p]);
        hi = std::fmax(hi, s.Position[4 * p]);
      }
    }
    shadowRGBA.assign(4 * n, 0.0f);
    shadow.assign(n, 0.0f);
    for (size_t p = 0; p < n; ++p)
    {
      shadow[p] = s.Position[4 * p] > 0.5f * (lo + hi) ? 1.0f : 0.0f;
      shadowRGBA[4 * p] = shadow[p];
    }
  }

  mrgi_bmr_params params;
  gpu->GetParams(&params);
  mrgi_bmr_masks c{};
  mrgi_error err;
  const mrgi_gather_receivers view = s.View();
  vtkNew<vtkMRGIMultiresolution> buffer;
  if (settings.Flags)
  {
    // NW09 flags at the multiresolution defaults, on the GPU and in C.
    buffer->SetDepthThreshold(MRGI_MULTIRES_DEFAULT_DEPTH_THRESHOLD);
    buffer->SetNormalThreshold(MRGI_MULTIRES_DEFAULT_NORMAL_THRESHOLD);
    buffer->SetFinestLevel(0);
    MRGI_TEST_CHECK(buffer->Update(s.GL, s.Frame.Position, s.Frame.Normal, s.Frame.Viewport[0],
      s.Frame.Viewport[1], s.W, s.H, s.PixelSize[0], s.PixelSize[1]));
    MRGI_TEST_CHECK(gpu->BuildFromFlags(s.Frame, levels, buffer));
    mrgi_multires_layout layout;
    MRGI_TEST_CHECK(mrgi_multires_layout_init(
                      &layout, s.W, s.H, MRGI_MULTIRES_DEFAULT_COARSEST_SIDE, &err) == MRGI_OK);
    mrgi_multires_mipmap mipmap;
    MRGI_TEST_CHECK(
      mrgi_multires_mipmap_build(&layout, &view, s.PixelSize, &mipmap, &err) == MRGI_OK);
    mrgi_multires_params mp;
    mrgi_multires_params_default(&mp);
    const size_t texels = static_cast<size_t>(mrgi_multires_texel_count(&layout));
    std::vector<uint8_t> flags(texels);
    MRGI_TEST_CHECK(
      mrgi_multires_flags_compute(&mipmap, &mp, flags.data(), texels, &err) == MRGI_OK);
    mrgi_multires_mipmap_destroy(&mipmap);
    MRGI_TEST_CHECK(
      mrgi_bmr_mask_from_flags(&layout, flags.data(), texels, &params, &c, &err) == MRGI_OK);
  }
  else
  {
    vtkTextureObject* shadowTexture = settings.Shadow ? s.Texture(shadowRGBA.data()) : nullptr;
    MRGI_TEST_CHECK(gpu->Build(s.Frame, levels, shadowTexture));
    MRGI_TEST_CHECK(mrgi_bmr_mask_build(&view, settings.Shadow ? shadow.data() : nullptr,
                      s.PixelSize, &params, &c, &err) == MRGI_OK);
  }
  bmrtest::GPUMasks g;
  bmrtest::ReadMasks(s.Window, levels, g);

  size_t diffEdge = 0, diffNonEmpty = 0, diffRequired = 0, diffStencil = 0, diffStencilBytes = 0,
         diffMask = 0, stencilled = 0;
  double maxMaskError = 0.0;
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    MRGI_TEST_CHECK(
      g.Masks.level_width[k] == c.level_width[k] && g.Masks.level_height[k] == c.level_height[k]);
    const size_t texels =
      static_cast<size_t>(c.level_width[k]) * static_cast<size_t>(c.level_height[k]);
    for (size_t t = 0; t < texels; ++t)
    {
      diffEdge += g.Masks.edge[k][t] != c.edge[k][t];
      diffNonEmpty += g.Masks.nonempty[k][t] != c.nonempty[k][t];
      diffRequired += g.Masks.required[k][t] != c.required[k][t];
      diffStencil += g.Masks.stencil[k][t] != c.stencil[k][t];
      diffStencilBytes += g.StencilBytes[static_cast<size_t>(k)][t] != c.stencil[k][t];
      diffMask += !bmrtest::Near(g.Masks.mask[k][t], c.mask[k][t]);
      maxMaskError = std::fmax(maxMaskError, std::fabs(g.Masks.mask[k][t] - c.mask[k][t]));
      stencilled += c.stencil[k][t];
    }
  }
  mrgi_bmr_stats stats;
  MRGI_TEST_CHECK(mrgi_bmr_stats_compute(&c, &stats, &err) == MRGI_OK);
  std::printf(
    "%s (%d x %d, %s): %zu stencilled texels, work %.3f; finest level 1..4: %.4f %.4f %.4f "
    "%.4f of %lld pixels; differences E %zu NE %zu R %zu S %zu stencil %zu a %zu (max %.3g)\n",
    label, s.W, s.H, mrgi_bmr_effect_name(settings.Preset), stencilled, stats.work_fraction,
    stats.valid_pixels ? static_cast<double>(stats.finest_pixels[0]) / stats.valid_pixels : 0.0,
    stats.valid_pixels ? static_cast<double>(stats.finest_pixels[1]) / stats.valid_pixels : 0.0,
    stats.valid_pixels ? static_cast<double>(stats.finest_pixels[2]) / stats.valid_pixels : 0.0,
    stats.valid_pixels ? static_cast<double>(stats.finest_pixels[3]) / stats.valid_pixels : 0.0,
    static_cast<long long>(stats.valid_pixels), diffEdge, diffNonEmpty, diffRequired, diffStencil,
    diffStencilBytes, diffMask, maxMaskError);
  mrgi_bmr_masks_destroy(&c);
  MRGI_TEST_CHECK(diffEdge == 0 && diffNonEmpty == 0 && diffRequired == 0 && diffStencil == 0 &&
    diffStencilBytes == 0 && diffMask == 0);
  levels->ReleaseGraphicsResources(s.Window);
  gpu->ReleaseGraphicsResources(s.Window);
  buffer->ReleaseGraphicsResources(s.Window);
  return stats;
}

void Cornell()
{
  bmrtest::Scene s;
  bmrtest::RenderScene(s, "cornell", 160, 120, false);
  Settings ssao;
  const mrgi_bmr_stats stats = Compare(s, ssao, "cornell SSAO preset");
  // Edges at full resolution, and more than half of the pixels coarser
  // (at 160 x 120 the blurs reach most of the box: level 3's radius of 6
  // texels is 24 pixels).
  MRGI_TEST_CHECK(stats.finest_pixels[0] > 0);
  MRGI_TEST_CHECK(stats.finest_pixels[0] < stats.valid_pixels / 2);
  Settings ssm;
  ssm.Preset = vtkMRGIBMRMask::SSM;
  ssm.Shadow = true;
  Compare(s, ssm, "cornell SSM preset with a shadow edge");
  Settings ssgi;
  ssgi.Preset = vtkMRGIBMRMask::SSGI;
  const mrgi_bmr_stats skipped = Compare(s, ssgi, "cornell SSGI preset (level 2 skipped)");
  MRGI_TEST_CHECK(skipped.stencilled[1] == 0);
  Settings full;
  full.DepthThreshold = 0.0;
  const mrgi_bmr_stats fullStats = Compare(s, full, "cornell threshold 0 (full resolution)");
  MRGI_TEST_CHECK(fullStats.finest_pixels[0] == fullStats.valid_pixels);
  Settings off;
  off.DepthThreshold = -1.0;
  off.NormalThreshold = -1.0;
  const mrgi_bmr_stats offStats = Compare(s, off, "cornell tests off (coarsest only)");
  MRGI_TEST_CHECK(offStats.finest_pixels[3] == offStats.valid_pixels);
  Settings min;
  min.Combine = vtkMRGIBMRMask::CombineMin;
  Compare(s, min, "cornell min combination");
  Settings flags;
  flags.Flags = true;
  Compare(s, flags, "cornell NW09 flags as source");
}

void CornellSpotParallelOdd()
{
  bmrtest::Scene s;
  bmrtest::RenderScene(s, "cornell-spot", 97, 61, true);
  Compare(s, Settings(), "cornell-spot parallel");
  Settings flags;
  flags.Flags = true;
  Compare(s, flags, "cornell-spot parallel, NW09 flags");
}

void OnePixel()
{
  bmrtest::Scene s;
  bmrtest::RenderScene(s, "cornell", 1, 1, false);
  Compare(s, Settings(), "cornell 1 x 1");
}

void Random()
{
  const int sizes[3][2] = { { 75, 53 }, { 128, 9 }, { 17, 66 } };
  for (uint32_t seed = 1; seed <= 3; ++seed)
  {
    bmrtest::Scene s;
    bmrtest::RandomScene(s, sizes[seed - 1][0], sizes[seed - 1][1], seed);
    Settings settings;
    settings.Preset = static_cast<int>(seed - 1);
    settings.DepthThreshold = seed == 2 ? -1.0 : 0.5;
    settings.NormalThreshold = 0.05 * seed;
    settings.Combine = seed == 3 ? vtkMRGIBMRMask::CombineMin : vtkMRGIBMRMask::CombineMax;
    settings.Shadow = seed != 2;
    const std::string label = "random G-buffer, seed " + std::to_string(seed);
    Compare(s, settings, label.c_str());
  }
}

void BadInput()
{
  bmrtest::Scene s;
  bmrtest::RandomScene(s, 20, 10, 9);
  vtkNew<vtkMRGIBMRLevels> levels;
  vtkNew<vtkMRGIBMRMask> gpu;
  // Levels of another size than the frame.
  MRGI_TEST_CHECK(levels->Prepare(s.GL, 21, 10));
  std::printf("(an error about the levels' size is expected)\n");
  MRGI_TEST_CHECK(!gpu->Build(s.Frame, levels, nullptr));
  std::printf("(errors about a bad variance and level are expected)\n");
  gpu->SetVariance(0, 17.0);
  MRGI_TEST_CHECK(gpu->GetVariance(0) == 0.924);
  gpu->SetSkipLevel(3, true);
  MRGI_TEST_CHECK(!gpu->GetSkipLevel(3));
  levels->ReleaseGraphicsResources(s.Window);
  gpu->ReleaseGraphicsResources(s.Window);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(Cornell), MRGI_TEST_CASE(CornellSpotParallelOdd), MRGI_TEST_CASE(OnePixel),
      MRGI_TEST_CASE(Random), MRGI_TEST_CASE(BadInput) });
}
