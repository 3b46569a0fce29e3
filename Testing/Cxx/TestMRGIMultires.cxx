// The multiresolution gather inside vtkMRGIPass (IndirectMultires): with
// thresholds 0 it reproduces the full-resolution gather to rounding; with the
// default thresholds it stays within 5% relative RMS of it (the papers report
// 2-3%); with thresholds off every selected texel is at the coarsest level;
// its stages are timed; the image is finite.
#include "vtk_glew.h"

#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIUpsample.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkPointData.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderTimerLog.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"

#include "mrgi_multires.h"
#include "mrgi_upsample.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
double RelativeRMS(vtkImageData* a, vtkImageData* b)
{
  vtkDataArray* x = a->GetPointData()->GetScalars();
  vtkDataArray* y = b->GetPointData()->GetScalars();
  MRGI_TEST_CHECK(x->GetNumberOfValues() == y->GetNumberOfValues());
  double num = 0, den = 0;
  for (vtkIdType i = 0; i < x->GetNumberOfValues(); ++i)
  {
    const double u = x->GetVariantValue(i).ToDouble(), v = y->GetVariantValue(i).ToDouble();
    MRGI_TEST_CHECK(std::isfinite(u));
    num += (u - v) * (u - v);
    den += v * v;
  }
  return std::sqrt(num / (den > 0 ? den : 1));
}
}

int main()
{
  const int W = 160, H = 120;
  mrgitest::PassScene scene(W, H, "cornell-spot");
  vtkRenderWindow* window = scene.Window;
  vtkRenderer* renderer = scene.Renderer;
  vtkMRGIPass* pass = scene.Pass;
  pass->SetStageTimingEnabled(true);
  window->GetRenderTimer()->SetLoggingEnabled(true);
  MRGI_TEST_CHECK(pass->GetIndirectMode() == vtkMRGIPass::IndirectMultires); // the default
  MRGI_TEST_CHECK(pass->GetMultiresolution()->GetDepthThreshold() ==
    [] { double s[3]; vtkMRGIMultiresolution::GetPresetSettings(vtkMRGIMultiresolution::PresetBalanced, s); return s[0]; }());

  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  window->Render();
  vtkNew<vtkImageData> full;
  MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, full));

  pass->SetIndirectMode(vtkMRGIPass::IndirectMultires);
  vtkMRGIMultiresolution* mr = pass->GetMultiresolution();
  vtkMRGIGather* gather = pass->GetGather();
  // This test is about the geometric selection: the texels the indirect
  // light gathers are the stencil's (the illumination rule of the default
  // preset adds its own, TestMRGIIlluminationRefine).
  mr->SetRefinement(vtkMRGIMultiresolution::RefinementGeometry);
  struct Setting
  {
    double Depth, Normal;
    double MaxError;
  };
  for (const Setting& setting : { Setting{ 0.0, 0.0, 1e-5 }, Setting{ 4.0, 0.25, 0.05 } })
  {
    mr->SetDepthThreshold(setting.Depth);
    mr->SetNormalThreshold(setting.Normal);
    window->Render();
    MRGI_TEST_CHECK(pass->GetIndirectComputed());
    vtkNew<vtkImageData> multires;
    MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, multires));
    const double error = RelativeRMS(multires, full);
    std::printf("thresholds (%g, %g): relative RMS against the full gather %.3g\n", setting.Depth,
      setting.Normal, error);
    MRGI_TEST_CHECK(error <= setting.MaxError);
  }

  // Thresholds off: only the coarsest level gathers.
  mr->SetDepthThreshold(-1);
  mr->SetNormalThreshold(-1);
  window->Render();
  vtkNew<vtkUnsignedCharArray> mask;
  MRGI_TEST_CHECK(mr->ReadSelection(window, mask, true));
  const int flatWidth = mr->GetFlattenedWidth();
  mrgi_multires_layout layout;
  MRGI_TEST_CHECK(mrgi_multires_layout_init(&layout, W, H, mr->GetCoarsestSide(), nullptr) == MRGI_OK);
  MRGI_TEST_CHECK(layout.total_width == flatWidth && layout.level_count == mr->GetNumberOfLevels());
  const int coarsestOffset = layout.level_offset[layout.level_count - 1];
  int coarse = 0, finer = 0;
  for (vtkIdType i = 0; i < mask->GetNumberOfTuples(); ++i)
  {
    if (mask->GetValue(i))
    {
      ((i % flatWidth) >= coarsestOffset ? coarse : finer) += 1;
    }
  }
  std::printf("thresholds off: %d texels at the coarsest level, %d elsewhere\n", coarse, finer);
  MRGI_TEST_CHECK(coarse > 0 && finer == 0);

  // Memory per pixel (Documentation/reliability/memory.md): the flags in one
  // half-float channel, the selection in one byte, no NORMAL_MAX texture at
  // level 0 (it stores one normal); level 1 keeps its three mipmap textures.
  vtkTextureObject* flags0 = mr->GetFlagsTexture(0);
  vtkTextureObject* selection = mr->GetSelectionTexture();
  MRGI_TEST_CHECK(flags0 && flags0->GetInternalFormat(VTK_FLOAT, 4, false) == GL_R16F);
  MRGI_TEST_CHECK(selection && selection->GetInternalFormat(VTK_FLOAT, 4, false) == GL_R8);
  MRGI_TEST_CHECK(mr->GetMipmapTexture(0, MRGI_MULTIRES_TEX_DEPTH));
  MRGI_TEST_CHECK(!mr->GetMipmapTexture(0, MRGI_MULTIRES_TEX_NORMAL_MIN));
  MRGI_TEST_CHECK(!mr->GetMipmapTexture(0, MRGI_MULTIRES_TEX_NORMAL_MAX));
  MRGI_TEST_CHECK(mr->GetNumberOfLevels() < 2 || mr->GetMipmapTexture(1, MRGI_MULTIRES_TEX_NORMAL_MAX));

  // Statistics: the occlusion-query counts per level equal the stencil's
  // selected texels per level, and the valid pixels those of the G-buffer.
  gather->SetCollectStatistics(true);
  MRGI_TEST_CHECK(gather->GetNumberOfGatheredTexels(0) == -1 || gather->GetGatherWorkFraction() < 0);
  mr->SetDepthThreshold(4.0);
  mr->SetNormalThreshold(0.25);
  window->Render();
  MRGI_TEST_CHECK(mr->ReadSelection(window, mask, true));
  vtkNew<vtkImageData> gPosition, gNormal, gAlbedo;
  MRGI_TEST_CHECK(pass->GetGBuffer(window, gPosition, gNormal, gAlbedo));
  long long validPixels = 0;
  for (vtkIdType i = 0; i < gPosition->GetNumberOfPoints(); ++i)
  {
    validPixels += gPosition->GetPointData()->GetScalars()->GetComponent(i, 3) > 0.5 ? 1 : 0;
  }
  long long gathered = 0;
  for (int level = 0; level < layout.level_count; ++level)
  {
    long long selected = 0;
    for (int y = 0; y < layout.level_height[level]; ++y)
    {
      for (int x = 0; x < layout.level_width[level]; ++x)
      {
        selected += mask->GetValue(static_cast<vtkIdType>(y) * flatWidth + layout.level_offset[level] + x);
      }
    }
    std::printf("level %d: %lld texels selected, %lld counted by the query\n", level, selected,
      static_cast<long long>(gather->GetNumberOfGatheredTexels(level)));
    MRGI_TEST_CHECK(gather->GetNumberOfGatheredTexels(level) == selected);
    gathered += selected;
  }
  std::printf("valid pixels %lld (queried %lld), work fraction %.4f\n", validPixels,
    static_cast<long long>(gather->GetNumberOfValidPixels()), gather->GetGatherWorkFraction());
  MRGI_TEST_CHECK(gather->GetNumberOfValidPixels() == validPixels);
  MRGI_TEST_CHECK(std::fabs(gather->GetGatherWorkFraction() - double(gathered) / double(validPixels)) < 1e-12);
  MRGI_TEST_CHECK(gathered > 0 && gathered < validPixels);

  // Multiresolution splatting (nichols-wyman-2009 3.4) gathers the same
  // texels with the same numbers as the stenciled gather: flattened E equal
  // to rounding, alpha (which texels hold data) equal, counts equal. At the
  // default selection, with a finest level of 1 and with everything at full
  // resolution (thresholds 0).
  struct SplatCase
  {
    double Depth, Normal;
    int Finest;
  };
  for (const SplatCase& c : { SplatCase{ 4.0, 0.25, 0 }, SplatCase{ 4.0, 0.25, 1 }, SplatCase{ 0.0, 0.0, 0 } })
  {
    mr->SetDepthThreshold(c.Depth);
    mr->SetNormalThreshold(c.Normal);
    mr->SetFinestLevel(c.Finest);
    vtkNew<vtkFloatArray> stenciled, splatted;
    std::vector<long long> stenciledCounts, splattedCounts;
    for (const int mode : { vtkMRGIGather::GatherStenciled, vtkMRGIGather::GatherSplatting })
    {
      gather->SetGatherMode(mode);
      window->Render();
      MRGI_TEST_CHECK(gather->ReadIrradiance(window, mode == vtkMRGIGather::GatherStenciled ? stenciled : splatted));
      auto& counts = mode == vtkMRGIGather::GatherStenciled ? stenciledCounts : splattedCounts;
      for (int level = 0; level < layout.level_count; ++level)
      {
        counts.push_back(static_cast<long long>(gather->GetNumberOfGatheredTexels(level)));
      }
    }
    MRGI_TEST_CHECK(stenciledCounts == splattedCounts);
    MRGI_TEST_CHECK(stenciled->GetNumberOfValues() == splatted->GetNumberOfValues());
    double peak = 0.0, worst = 0.0;
    long long texels = 0, alphaMismatch = 0;
    for (vtkIdType i = 0; i < stenciled->GetNumberOfTuples(); ++i)
    {
      const double a0 = stenciled->GetComponent(i, 3), a1 = splatted->GetComponent(i, 3);
      alphaMismatch += (a0 != a1) ? 1 : 0;
      texels += a0 > 0.5 ? 1 : 0;
      for (int k = 0; k < 3; ++k)
      {
        peak = std::max(peak, std::fabs(stenciled->GetComponent(i, k)));
        MRGI_TEST_CHECK(std::isfinite(splatted->GetComponent(i, k)));
        worst = std::max(worst, std::fabs(splatted->GetComponent(i, k) - stenciled->GetComponent(i, k)));
      }
    }
    std::printf("splatting (%g, %g, finest %d): %lld texels, alpha mismatches %lld, worst |dE| %.3g of peak %.3g\n",
      c.Depth, c.Normal, c.Finest, texels, alphaMismatch, worst, peak);
    MRGI_TEST_CHECK(texels > 0 && alphaMismatch == 0);
    MRGI_TEST_CHECK(peak > 0.0 && worst <= 1e-5 * peak);
  }
  gather->SetGatherMode(vtkMRGIGather::GatherStenciled);
  mr->SetFinestLevel(0);
  mr->SetDepthThreshold(4.0);
  mr->SetNormalThreshold(0.25);
  gather->SetCollectStatistics(false);

  // Surface-detail modulation (nichols-wyman-2009 eq. 2): the resolved E is
  // the upsampled E times the C twin's factor, pixel by pixel.
  for (const double alpha : { 0.0, 0.5, 1.0 })
  {
    pass->SetSurfaceDetail(alpha);
    window->Render();
    vtkNew<vtkFloatArray> upsampled;
    vtkNew<vtkImageData> irradiance;
    MRGI_TEST_CHECK(pass->GetUpsample()->ReadUpsampled(window, upsampled));
    MRGI_TEST_CHECK(pass->GetIrradianceBuffer(window, irradiance));
    MRGI_TEST_CHECK(pass->GetGBuffer(window, gPosition, gNormal, gAlbedo));
    vtkDataArray* E = irradiance->GetPointData()->GetScalars();
    vtkDataArray* P = gPosition->GetPointData()->GetScalars();
    vtkDataArray* N = gNormal->GetPointData()->GetScalars();
    double worst = 0.0, darkest = 1.0;
    for (vtkIdType i = 0; i < E->GetNumberOfTuples(); ++i)
    {
      if (P->GetComponent(i, 3) < 0.5 || upsampled->GetComponent(i, 3) < 0.5)
      {
        continue;
      }
      const float position[3] = { float(P->GetComponent(i, 0)), float(P->GetComponent(i, 1)),
        float(P->GetComponent(i, 2)) };
      const float normal[3] = { float(N->GetComponent(i, 0)), float(N->GetComponent(i, 1)),
        float(N->GetComponent(i, 2)) };
      const float factor = mrgi_surface_detail_factor(position, normal, 0, float(alpha));
      darkest = std::min(darkest, double(factor));
      for (int c = 0; c < 3; ++c)
      {
        const double expected = upsampled->GetComponent(i, c) * factor;
        const double got = E->GetComponent(i, c);
        worst = std::max(worst, std::fabs(got - expected) / std::max(std::fabs(expected), 1e-12));
      }
    }
    std::printf("surface detail %.1f: darkest factor %.3f, worst relative difference %.3g\n",
      alpha, darkest, worst);
    MRGI_TEST_CHECK(worst < 1e-5);
    MRGI_TEST_CHECK(alpha == 0.0 ? darkest == 1.0 : (darkest < 1.0 && darkest >= 1.0 - alpha));
  }
  pass->SetSurfaceDetail(0.0);

  // The stages of a multiresolution frame.
  pass->FetchStageTimings(window, true);
  window->Render();
  const int stages = pass->FetchStageTimings(window, true);
  std::string names;
  for (int s = 0; s < stages; ++s)
  {
    names += std::string(pass->GetStageName(s)) + " ";
  }
  std::printf("stages: %s\n", names.c_str());
  // Top-level stages in order; "stage.step" parts right after their stage.
  std::string top;
  std::string last;
  for (int s = 0; s < stages; ++s)
  {
    const std::string name = pass->GetStageName(s);
    const size_t dot = name.find('.');
    if (dot == std::string::npos)
    {
      top += name + " ";
      last = name;
    }
    else
    {
      MRGI_TEST_CHECK(name.substr(0, dot) == last);
      MRGI_TEST_CHECK(pass->GetStageTimeMilliseconds(s) >= 0.0);
    }
  }
  MRGI_TEST_CHECK(top == "scene rsm shadows vpl select gather upsample add forward output ");
  MRGI_TEST_CHECK(names.find("select.stencil") != std::string::npos &&
    names.find("gather.vpls") != std::string::npos);

  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  return 0;
}
