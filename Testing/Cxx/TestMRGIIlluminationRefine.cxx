/**
 * @file TestMRGIIlluminationRefine.cxx
 * @brief Refinement that follows the indirect light (issue 17 part 2):
 *        vtkMRGIPass::SetRefinement(RefinementIllumination).
 *
 * - Parity: on the Cornell box (spot) at several thresholds and geometric
 *   settings, the texels the GPU gathered equal
 *   mrgi_incremental_stencil_illumination_level() fed, level by level, with
 *   the GPU's own flags, selection, receivers and gathered irradiance, bit
 *   for bit; the gather's per-level statistics count the same texels. The
 *   same with the VPL tree as the light term.
 * - The threshold matters: 0 gathers every texel of every level (but the
 *   geometrically refined ones), 1e30 the geometric selection alone, and a
 *   small threshold beats the geometric selection it starts from by far,
 *   close to gathering everything (whose image is the full gather after
 *   the upsampling's tent filter, not the full gather itself).
 * - The presets carry the refinement: a new pass (Balanced) and Accurate
 *   gather by illumination at their own thresholds, Fast by geometry; a
 *   preset applied after SetRefinement() sets it again. The area lights
 *   select with their own thresholds.
 */
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkMRGIAreaLight.h"
#include "vtkMRGIAreaLightStage.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIIncrementalStencil.h"
#include "vtkMRGIIndirectLight.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkUnsignedCharArray.h"

#include "mrgi_incremental_stencil.h"
#include "mrgi_multires.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
struct Outcome
{
  long long Selected = 0; // texels of the geometric selection
  long long Rendered = 0; // texels gathered
  long long Differ = 0;   // texels where GPU and C disagree
  long long Counted = 0;  // texels the gather's occlusion queries counted
  long long Candidates = 0; // non-empty texels at the gathering levels
};

void Configure(vtkMRGIPass* pass, int refinement, double threshold, double depth, double normal)
{
  pass->SetIndirectMode(vtkMRGIPass::IndirectMultires);
  pass->SetRefinement(refinement);
  pass->SetIlluminationThreshold(threshold);
  pass->GetMultiresolution()->SetDepthThreshold(depth);
  pass->GetMultiresolution()->SetNormalThreshold(normal);
  pass->GetMultiresolution()->SetFinestLevel(0);
}

// Render, read the GPU's mask and inputs back and rebuild the mask in C.
Outcome Check(mrgitest::PassScene& scene)
{
  Outcome out;
  vtkMRGIPass* pass = scene.Pass;
  vtkRenderWindow* window = scene.Window;
  vtkMRGIMultiresolution* mr = pass->GetMultiresolution();
  vtkMRGIGather* gather = pass->GetGather();
  vtkMRGIIndirectLight* stage = pass->GetIndirectLightStage();
  gather->SetCollectStatistics(true);
  window->Render();
  gather->SetCollectStatistics(false);
  MRGI_TEST_CHECK(stage->GetLastRefinedByIllumination());
  vtkNew<vtkUnsignedCharArray> gpu, flags, selection;
  vtkNew<vtkFloatArray> position, normal, irradiance;
  mrgi_multires_layout layout;
  MRGI_TEST_CHECK(stage->GetIlluminationStencil()->ReadStencil(window, gpu) &&
    mr->ReadFlags(window, flags) && mr->ReadSelection(window, selection, false) &&
    mr->ReadReceivers(window, position, normal) && gather->ReadIrradiance(window, irradiance) &&
    mr->GetLayout(&layout));
  const size_t texels = static_cast<size_t>(mrgi_multires_texel_count(&layout));
  MRGI_TEST_CHECK(static_cast<size_t>(gpu->GetNumberOfValues()) == texels);
  std::vector<uint8_t> rendered(gpu->GetPointer(0), gpu->GetPointer(0) + texels);
  const int finest = mr->GetFinestGatherLevel();
  const float threshold = static_cast<float>(pass->GetIlluminationThreshold());
  for (int i = layout.level_count - 1; i >= finest; --i)
  {
    // Levels above i hold the GPU's mask (equal to C's where parity holds).
    mrgi_error err;
    MRGI_TEST_CHECK(mrgi_incremental_stencil_illumination_level(&layout, finest, i,
                      flags->GetPointer(0), selection->GetPointer(0), texels,
                      position->GetPointer(0), static_cast<size_t>(position->GetNumberOfValues()),
                      irradiance->GetPointer(0),
                      static_cast<size_t>(irradiance->GetNumberOfValues()),
                      stage->GetIlluminationStencil()->GetIlluminationMetric(), threshold,
                      rendered.data(), texels, nullptr, &err) == MRGI_OK);
    out.Counted += gather->GetNumberOfGatheredTexels(i);
  }
  for (size_t t = 0; t < texels; ++t)
  {
    const bool g = gpu->GetValue(static_cast<vtkIdType>(t)) != 0;
    out.Differ += g != (rendered[t] != 0);
    out.Rendered += g;
    out.Selected += selection->GetValue(static_cast<vtkIdType>(t)) != 0;
    int level = 0, x = 0, y = 0;
    if (mrgi_multires_locate(&layout, static_cast<int32_t>(t % static_cast<size_t>(layout.total_width)),
          static_cast<int32_t>(t / static_cast<size_t>(layout.total_width)), &level, &x, &y) &&
      level >= finest)
    {
      // T = 0 renders every non-empty texel but the geometrically refined
      // ones above the finest level (finer texels cover those).
      const int f = flags->GetValue(static_cast<vtkIdType>(t));
      out.Candidates += (f & MRGI_MULTIRES_FLAG_NONEMPTY) != 0 &&
        (level == finest || (f & MRGI_MULTIRES_FLAG_REFINE) == 0);
    }
  }
  return out;
}

vtkSmartPointer<vtkImageData> Indirect(mrgitest::PassScene& scene)
{
  scene.Window->Render();
  auto image = vtkSmartPointer<vtkImageData>::New();
  MRGI_TEST_CHECK(scene.Pass->GetIndirectBuffer(scene.Window, image));
  return image;
}

double RelativeRMS(vtkImageData* a, vtkImageData* reference)
{
  vtkDataArray* x = a->GetPointData()->GetScalars();
  vtkDataArray* r = reference->GetPointData()->GetScalars();
  double num = 0.0, den = 0.0;
  for (vtkIdType i = 0; i < r->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double d = x->GetComponent(i, c) - r->GetComponent(i, c);
      num += d * d;
      den += r->GetComponent(i, c) * r->GetComponent(i, c);
    }
  }
  return std::sqrt(num / std::max(den, 1e-300));
}

void TestParity()
{
  mrgitest::PassScene scene(128, 112, "cornell-spot");
  const int lit = vtkMRGIMultiresolution::RefinementIllumination;
  struct Setting
  {
    double Threshold, Depth, Normal;
    int Metric;
  };
  const int curvature = MRGI_INCREMENTAL_ILLUMINATION_CURVATURE;
  const Setting settings[] = { { 0.1, -1.0, 1.0, 0 }, { 0.02, -1.0, 1.0, 0 },
    { 0.3, 16.0, 0.5, 0 },
    { 0.1, MRGI_MULTIRES_DEFAULT_DEPTH_THRESHOLD, MRGI_MULTIRES_DEFAULT_NORMAL_THRESHOLD, 0 },
    { 0.02, -1.0, 1.0, curvature }, { 0.005, -1.0, 1.0, curvature }, { 0.05, 16.0, 0.5, curvature } };
  vtkMRGIIncrementalStencil* stencil = scene.Pass->GetIndirectLightStage()->GetIlluminationStencil();
  for (const Setting& s : settings)
  {
    Configure(scene.Pass, lit, s.Threshold, s.Depth, s.Normal);
    stencil->SetIlluminationMetric(s.Metric);
    const Outcome o = Check(scene);
    std::printf("metric %d T %.3f depth %g normal %g: %lld selected, %lld gathered (counted %lld), "
                "%lld differ from the C twin\n",
      s.Metric, s.Threshold, s.Depth, s.Normal, o.Selected, o.Rendered, o.Counted, o.Differ);
    MRGI_TEST_CHECK(o.Differ == 0);
    MRGI_TEST_CHECK(o.Counted == o.Rendered);
    MRGI_TEST_CHECK(o.Rendered > o.Selected); // the rule adds texels: the test can fail
  }
  // The VPL tree as the light term: the same rule between its levels.
  stencil->SetIlluminationMetric(MRGI_INCREMENTAL_ILLUMINATION_DIFFERENCE);
  scene.Pass->SetVPLSelectionMode(vtkMRGIVPLSelection::Tree);
  Configure(scene.Pass, lit, 0.1, 16.0, 0.5);
  const Outcome tree = Check(scene);
  std::printf("VPL tree, T 0.1 depth 16 normal 0.5: %lld selected, %lld gathered (counted %lld), "
              "%lld differ from the C twin\n",
    tree.Selected, tree.Rendered, tree.Counted, tree.Differ);
  MRGI_TEST_CHECK(tree.Differ == 0 && tree.Counted == tree.Rendered);
  MRGI_TEST_CHECK(tree.Rendered > tree.Selected);
  scene.Pass->SetVPLSelectionMode(vtkMRGIVPLSelection::Grid);
  // Threshold extremes: everything, or the geometric selection alone.
  Configure(scene.Pass, lit, 0.0, -1.0, 1.0);
  Outcome all = Check(scene);
  MRGI_TEST_CHECK(all.Differ == 0 && all.Rendered == all.Candidates);
  Configure(scene.Pass, lit, 1.0e30, -1.0, 1.0);
  Outcome none = Check(scene);
  MRGI_TEST_CHECK(none.Differ == 0 && none.Rendered == none.Selected);
  std::printf("T 0: %lld of %lld texels; T 1e30: %lld = the selection\n", all.Rendered,
    all.Candidates, none.Rendered);
}

void TestThresholdMatters()
{
  mrgitest::PassScene scene(128, 112, "cornell-spot");
  scene.Pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  vtkSmartPointer<vtkImageData> full = Indirect(scene);
  const int lit = vtkMRGIMultiresolution::RefinementIllumination;
  Configure(scene.Pass, lit, 0.0, -1.0, 1.0);
  const double everything = RelativeRMS(Indirect(scene), full);
  Configure(scene.Pass, lit, 0.05, -1.0, 1.0);
  const double refined = RelativeRMS(Indirect(scene), full);
  Configure(scene.Pass, vtkMRGIMultiresolution::RefinementGeometry, 0.05, -1.0, 1.0);
  const double geometric = RelativeRMS(Indirect(scene), full);
  std::printf("relative RMS against the full gather: T 0 %.4f, T 0.05 %.4f, geometry alone %.4f\n",
    everything, refined, geometric);
  MRGI_TEST_CHECK(refined < 0.5 * geometric);
  MRGI_TEST_CHECK(everything <= refined * 1.05 + 1e-6);
  MRGI_TEST_CHECK(!scene.Pass->GetIndirectLightStage()->GetLastRefinedByIllumination());
}

void TestPresetsRefine()
{
  mrgitest::PassScene scene(64, 56, "cornell-spot");
  vtkMRGIPass* pass = scene.Pass;
  vtkMRGIMultiresolution* mr = pass->GetMultiresolution();
  pass->SetIndirectMode(vtkMRGIPass::IndirectMultires);
  for (int preset : { vtkMRGIMultiresolution::PresetBalanced, vtkMRGIMultiresolution::PresetFast,
         vtkMRGIMultiresolution::PresetAccurate })
  {
    if (preset != vtkMRGIMultiresolution::PresetBalanced) // a new pass starts Balanced
    {
      pass->SetRefinement(vtkMRGIMultiresolution::RefinementGeometry);
      MRGI_TEST_CHECK(mr->SetPreset(preset));
    }
    // 64 x 56 is under the presets' minimum view: they select as the area
    // lights do, without the rule.
    MRGI_TEST_CHECK(mr->GetIlluminationMinimumPixels() ==
      (mr->GetRefinement() == vtkMRGIMultiresolution::RefinementIllumination
          ? MRGI_MULTIRES_ILLUMINATION_MIN_PIXELS
          : 0));
    scene.Window->Render();
    MRGI_TEST_CHECK(!pass->GetIndirectLightStage()->GetLastRefinedByIllumination());
    MRGI_TEST_CHECK(mr->SelectionServesAreaLights());
    mr->SetIlluminationMinimumPixels(0);
    double threshold = 0.0;
    MRGI_TEST_CHECK(
      mrgi_multires_preset_illumination_threshold(preset, &threshold, nullptr) == MRGI_OK);
    const bool lit = !std::isinf(threshold);
    MRGI_TEST_CHECK(pass->GetRefinement() ==
      (lit ? vtkMRGIMultiresolution::RefinementIllumination
           : vtkMRGIMultiresolution::RefinementGeometry));
    MRGI_TEST_CHECK(!lit || pass->GetIlluminationThreshold() == threshold);
    scene.Window->Render();
    MRGI_TEST_CHECK(pass->GetIndirectLightStage()->GetLastRefinedByIllumination() == lit);
    MRGI_TEST_CHECK(mr->SelectionServesAreaLights() == !lit);
    // The stage took the buffer's threshold for this frame.
    MRGI_TEST_CHECK(!lit ||
      pass->GetIndirectLightStage()->GetIlluminationStencil()->GetIlluminationThreshold() ==
        threshold);
  }
}
}

// The area lights select with their own thresholds (their shadows change at
// depth edges): with the indirect light's selection held, the area gather's
// work follows the area thresholds alone.
void TestAreaLightsSelectApart()
{
  mrgitest::PassScene scene(96, 80, "cornell-area");
  vtkMRGIPass* pass = scene.Pass;
  for (int i = 0; i < scene.Builder->GetNumberOfAreaLights(); ++i)
  {
    pass->AddAreaLight(scene.Builder->GetAreaLight(i));
  }
  MRGI_TEST_CHECK(pass->GetNumberOfAreaLights() > 0);
  vtkMRGIMultiresolution* mr = pass->GetMultiresolution();
  MRGI_TEST_CHECK(!mr->AreaLightsShareSelection()); // Balanced
  // Without the area stage's own stencil its gather works on the geometric
  // selection alone.
  pass->GetAreaLightStage()->SetIncrementalStencil(false);
  vtkMRGIGather* areaGather = pass->GetAreaLightStage()->GetGather();
  const auto areaWork = [&](double threshold) {
    mr->SetAreaLightDepthThreshold(threshold);
    mr->SetAreaLightNormalThreshold(threshold);
    areaGather->SetCollectStatistics(true);
    scene.Window->Render();
    areaGather->SetCollectStatistics(false);
    return areaGather->GetGatherWorkFraction();
  };
  mr->SetDepthThreshold(-1.0); // the indirect light's: never refine
  mr->SetNormalThreshold(-1.0);
  const double everything = areaWork(0.0), edges = areaWork(-1.0);
  std::printf("area gather work: area thresholds 0 %.4f, off %.4f\n", everything, edges);
  MRGI_TEST_CHECK(everything > 0.99 && edges < 0.9 * everything);
  mr->SetPreset(vtkMRGIMultiresolution::PresetFast);
  MRGI_TEST_CHECK(mr->AreaLightsShareSelection());
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestParity), MRGI_TEST_CASE(TestThresholdMatters),
      MRGI_TEST_CASE(TestPresetsRefine), MRGI_TEST_CASE(TestAreaLightsSelectApart) });
}
