// The GPU's incremental voxel-space visibility (vtkMRGIVisibilityPyramid,
// nichols-penmatsa-wyman-2010 sections 3.3.2 and 3.4) against its C twin
// mrgi_voxel_visibility_pyramid() (mrgi_visibility_pyramid.h) on the same
// receivers (vtkMRGIMultiresolution::ReadReceivers()), the same voxels
// (vtkMRGIVoxelization::ReadVoxels(), GetGrid(), GetMarchParams()) and the
// same light samples (mrgi_area_light_make_samples(), taken to eye space as
// the shader does): every mask bit of every level is compared.
//
// Modes: naive (incremental off: the C twin on each level alone, i.e. as
// its coarsest level), incremental with and without 2x2 interleaving, the
// count-spread metric with the selection as refine mask, threshold 0; 64
// and 256 samples; NPOT windows; the Cornell box with its area emitter and
// with a spot light (a light under the ceiling).
//
// What may differ: a ray on which the GLSL and C marches round differently
// (mrgi_voxel_march.h "Precision"; also the sample's eye-space transform,
// mat4 x vec4 on the GPU); in incremental mode such a bit can be reused or
// inherited by finer texels. Bound: < 0.5% of the receiver bits. A twin
// with a wrong refinement threshold must exceed it. Also checked: the
// GPU's ray and texel counts against the C twin's statistics, and that the
// incremental default marches far fewer rays than the naive query.
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"
#include "mrgiVoxelTestUtilities.h"

#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMRGIVisibilityPyramid.h"
#include "vtkMRGIVoxelization.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtkTypeUInt32Array.h"
#include "vtkUnsignedCharArray.h"

#include "mrgi_area_light.h"
#include "mrgi_multires.h"
#include "mrgi_visibility_pyramid.h"
#include "mrgi_voxel_march.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace
{
const double MaxBitRate = 0.005; // 0.5% of the receiver bits

struct Mode
{
  const char* Name;
  bool Incremental, Interleave;
  float Fraction;
  int Metric;
  bool RefineSelected;
  bool TwoSided = false; // the light emits on both sides (sample normals face each receiver)
};

struct Result
{
  size_t Bits = 0, Differ = 0, Texels = 0, TexelsDiffer = 0;
  double Rate() const { return Bits ? double(Differ) / double(Bits) : 0.0; }
};

int Popcount(uint32_t v)
{
  int n = 0;
  for (; v; v &= v - 1)
  {
    ++n;
  }
  return n;
}

Result Compare(const mrgi_multires_layout& layout, const std::vector<float>& P,
  const uint32_t* gpu, const std::vector<uint32_t>& c, int words)
{
  Result r;
  const size_t texels = static_cast<size_t>(mrgi_multires_texel_count(&layout));
  const int samples = words * 32; // bits compared: the mask words (padding is 0 on both sides)
  for (size_t t = 0; t < texels; ++t)
  {
    if (!(P[4 * t + 3] > MRGI_GBUFFER_VALID_THRESHOLD))
    {
      // Non-receivers: all zero on both sides.
      for (int w = 0; w < words; ++w)
      {
        MRGI_TEST_CHECK(gpu[t * words + w] == 0u && c[t * words + w] == 0u);
      }
      continue;
    }
    ++r.Texels;
    r.Bits += static_cast<size_t>(samples);
    int d = 0;
    for (int w = 0; w < words; ++w)
    {
      d += Popcount(gpu[t * words + w] ^ c[t * words + w]);
    }
    r.Differ += static_cast<size_t>(d);
    if (d > 0 && getenv("MRGI_VIS_DEBUG") && r.TexelsDiffer < 12)
    {
      std::printf("diff texel %zu (x %zu y %zu):", t, t % layout.total_width, t / layout.total_width);
      for (int w = 0; w < words; ++w)
      {
        std::printf(" [%08x %08x]", gpu[t * words + w], c[t * words + w]);
      }
      std::printf("\n");
    }
    r.TexelsDiffer += d > 0;
  }
  return r;
}

// The C twin; naive (incremental off): each level alone, as a one-level layout.
void CTwin(const mrgi_multires_layout& layout, const std::vector<float>& P,
  const std::vector<float>& N, const mrgi_voxel_view& view, const mrgi_voxel_samples& samples,
  const uint8_t* refine, const mrgi_voxel_incremental_params& params, bool incremental,
  std::vector<uint32_t>& masks, mrgi_voxel_incremental_stats& stats)
{
  const size_t texels = static_cast<size_t>(mrgi_multires_texel_count(&layout));
  const int words = mrgi_voxel_mask_words(samples.count);
  masks.assign(texels * words, 0u);
  mrgi_error err;
  if (incremental)
  {
    MRGI_TEST_CHECK(mrgi_voxel_visibility_pyramid(&layout, P.data(), N.data(), P.size(), &view,
                      &samples, refine, refine ? texels : 0, &params, masks.data(), masks.size(),
                      &stats, &err) == MRGI_OK);
    return;
  }
  std::memset(&stats, 0, sizeof(stats));
  for (int i = 0; i < layout.level_count; ++i)
  {
    const int lw = layout.level_width[i], lh = layout.level_height[i];
    mrgi_multires_layout one;
    MRGI_TEST_CHECK(mrgi_multires_layout_init(&one, lw, lh, std::max(lw, lh), &err) == MRGI_OK);
    MRGI_TEST_CHECK(one.level_count == 1);
    const size_t n = static_cast<size_t>(lw) * lh;
    std::vector<float> p(4 * n), q(4 * n);
    for (int y = 0; y < lh; ++y)
    {
      for (int x = 0; x < lw; ++x)
      {
        const size_t s = mrgi_multires_index(&layout, i, x, y), d = mrgi_multires_index(&one, 0, x, y);
        std::copy(&P[4 * s], &P[4 * s] + 4, &p[4 * d]);
        std::copy(&N[4 * s], &N[4 * s] + 4, &q[4 * d]);
      }
    }
    std::vector<uint32_t> m(n * words);
    mrgi_voxel_incremental_stats s;
    MRGI_TEST_CHECK(mrgi_voxel_visibility_pyramid(&one, p.data(), q.data(), p.size(), &view,
                      &samples, nullptr, 0, &params, m.data(), m.size(), &s, &err) == MRGI_OK);
    for (int y = 0; y < lh; ++y)
    {
      for (int x = 0; x < lw; ++x)
      {
        std::copy(&m[mrgi_multires_index(&one, 0, x, y) * words],
          &m[mrgi_multires_index(&one, 0, x, y) * words] + words,
          &masks[mrgi_multires_index(&layout, i, x, y) * words]);
      }
    }
    stats.computed[i] = s.computed[0];
    stats.rays[i] = s.rays[0];
    stats.rays_total += s.rays[0];
    if (i == 0)
    {
      stats.rays_naive = s.rays_naive;
    }
  }
}

double Seconds(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

size_t failureChecks = 0;

void RunScene(const char* scene, int W, int H, const std::vector<int>& sampleCounts,
  const std::vector<Mode>& modes, bool proveFailure, bool parallel = false)
{
  mrgitest::PassScene built(W, H, scene);
  vtkRenderWindow* window = built.Window;
  vtkOpenGLRenderWindow* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  vtkRenderer* renderer = built.Renderer;
  vtkMRGIPass* pass = built.Pass;
  pass->SetNumberOfVPLs(16);
  vtkCamera* camera = renderer->GetActiveCamera();
  if (parallel)
  {
    // Parallel projection: screen sides are compared without the division
    // by depth (mrgi_voxel_screen_side(), the surround rule).
    camera->ParallelProjectionOn();
    camera->SetParallelScale(0.5 * renderer->ComputeVisiblePropBounds()[3]);
    std::printf("parallel projection\n");
  }
  window->Render();
  const int* vp = pass->GetViewport();
  MRGI_TEST_CHECK(vp[2] == W && vp[3] == H);

  // Multiresolution receivers.
  mrgi_multires_projection projection = { camera->GetParallelProjection() ? 1 : 0,
    camera->GetViewAngle(), camera->GetParallelScale() };
  float ab[2];
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_multires_pixel_size_coefficients(&projection, H, ab, &err) == MRGI_OK);
  vtkNew<vtkMRGIMultiresolution> multires;
  MRGI_TEST_CHECK(multires->Update(gl, pass->GetPositionTexture(), pass->GetNormalTexture(), vp[0],
    vp[1], W, H, ab[0], ab[1]));
  MRGI_TEST_CHECK(multires->BuildReceivers(gl, pass->GetPositionTexture(), pass->GetNormalTexture(), vp[0], vp[1]));
  mrgi_multires_layout layout;
  MRGI_TEST_CHECK(multires->GetLayout(&layout));
  const size_t texels = static_cast<size_t>(mrgi_multires_texel_count(&layout));
  vtkNew<vtkFloatArray> rp, rn;
  MRGI_TEST_CHECK(multires->ReadReceivers(window, rp, rn));
  std::vector<float> P(rp->GetPointer(0), rp->GetPointer(0) + 4 * texels);
  std::vector<float> N(rn->GetPointer(0), rn->GetPointer(0) + 4 * texels);
  vtkNew<vtkUnsignedCharArray> selection;
  MRGI_TEST_CHECK(multires->ReadSelection(window, selection, false));
  std::vector<uint8_t> refine(selection->GetPointer(0), selection->GetPointer(0) + texels);

  // Voxels, over the camera's clipping range (as vtkMRGIPass does).
  vtkNew<vtkMRGIVoxelization> voxels;
  double range[2];
  camera->GetClippingRange(range);
  MRGI_TEST_CHECK(voxels->Voxelize(renderer, range[0], range[1]));
  vtkNew<vtkTypeUInt32Array> voxelWords;
  double w2v[16];
  const mrgi_voxel_view view = mrgitest::ReadVoxelView(voxels, window, voxelWords, w2v);
  float M[16];
  for (int k = 0; k < 16; ++k)
  {
    M[k] = static_cast<float>(w2v[k]);
  }

  // The light: the scene's area emitter, else one under the ceiling facing down.
  mrgi_area_light light{};
  if (built.Builder->GetNumberOfAreaLights() > 0)
  {
    MRGI_TEST_CHECK(built.Builder->GetAreaLight(0)->GetCoreLight(&light));
  }
  else
  {
    double bounds[6];
    renderer->ComputeVisiblePropBounds(bounds);
    const double ext[3] = { bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] };
    light.center[0] = bounds[0] + 0.45 * ext[0];
    light.center[1] = bounds[2] + 0.95 * ext[1];
    light.center[2] = bounds[4] + 0.55 * ext[2];
    light.edge_u[0] = 0.3 * ext[0];
    light.edge_v[2] = 0.25 * ext[2];
    light.color[0] = light.color[1] = light.color[2] = 1.0;
    light.intensity = 3.0;
  }
  light.two_sided = 0;
  light.texture = nullptr; // radiance is irrelevant to visibility
  MRGI_TEST_CHECK(mrgi_area_light_check(&light, &err) == MRGI_OK);
  std::printf("%s %dx%d: %d levels, %zu flattened texels, voxels %dx%d over [%g, %g]\n", scene, W,
    H, layout.level_count, texels, view.grid.width, view.grid.height, range[0], range[1]);

  vtkNew<vtkMRGIVisibilityPyramid> vis;
  vis->CollectStatisticsOn();
  for (const int requested : sampleCounts)
  {
    std::vector<mrgi_area_light_sample> samples(static_cast<size_t>(requested));
    int32_t count = 0;
    MRGI_TEST_CHECK(mrgi_area_light_make_samples(&light, nullptr, requested, 1, 7u, samples.data(),
                      requested, &count, &err) == MRGI_OK);
    vtkNew<vtkTextureObject> sampleTexture;
    sampleTexture->SetContext(gl);
    MRGI_TEST_CHECK(sampleTexture->Create2DFromRaw(MRGI_AREA_LIGHT_SAMPLE_TEXELS,
      static_cast<unsigned int>(count), 4, VTK_FLOAT,
      const_cast<float*>(mrgi_area_light_sample_texture_data(samples.data()))));
    // Eye space, as the shader computes it (column-major M, one sum per row).
    std::vector<float> Lp(3 * count), Ln(3 * count);
    for (int j = 0; j < count; ++j)
    {
      const float* p = samples[j].position;
      const float* n = samples[j].normal;
      for (int r = 0; r < 3; ++r)
      {
        Lp[3 * j + r] = M[r] * p[0] + M[4 + r] * p[1] + M[8 + r] * p[2] + M[12 + r];
        Ln[3 * j + r] = M[r] * n[0] + M[4 + r] * n[1] + M[8 + r] * n[2];
      }
    }
    const mrgi_voxel_samples oneSided = { count, Lp.data(), Ln.data(), 0 };
    const mrgi_voxel_samples twoSided = { count, Lp.data(), Ln.data(), 1 };
    const int words = mrgi_voxel_mask_words(count);

    for (const Mode& mode : modes)
    {
      vis->SetIncremental(mode.Incremental);
      vis->SetInterleave(mode.Interleave);
      vis->SetRefineFraction(mode.Fraction);
      vis->SetMetric(mode.Metric);
      vis->SetRefineSelected(mode.RefineSelected);
      auto t0 = std::chrono::steady_clock::now();
      MRGI_TEST_CHECK(vis->Update(gl, multires, voxels, sampleTexture, count, mode.TwoSided, M));
      const mrgi_voxel_samples& cs = mode.TwoSided ? twoSided : oneSided;
      vtkNew<vtkTypeUInt32Array> gpu;
      MRGI_TEST_CHECK(vis->ReadMasks(window, gpu));
      const double gpuTime = Seconds(t0);
      MRGI_TEST_CHECK(gpu->GetNumberOfComponents() == words &&
        static_cast<size_t>(gpu->GetNumberOfTuples()) == texels);

      mrgi_voxel_incremental_params params;
      params.interleave = mode.Interleave ? 1 : 0;
      params.metric = mode.Metric;
      params.refine_fraction = mode.Fraction;
      std::vector<uint32_t> c;
      mrgi_voxel_incremental_stats cstats;
      t0 = std::chrono::steady_clock::now();
      CTwin(layout, P, N, view, cs, mode.RefineSelected ? refine.data() : nullptr, params,
        mode.Incremental, c, cstats);
      const double cTime = Seconds(t0);
      const Result r = Compare(layout, P, gpu->GetPointer(0), c, words);
      const double ratio = double(vis->GetTotalNumberOfRays()) / double(vis->GetNumberOfNaiveRays());
      std::printf("  N=%3d %-34s | %zu receiver texels, %zu bits differ = %.4f%% (%zu texels) | "
                  "rays GPU %lld C %lld, naive %lld, ratio %.3f | draws %d | GPU %.2fs C %.2fs\n",
        count, mode.Name, r.Texels, r.Differ, 100.0 * r.Rate(), r.TexelsDiffer,
        static_cast<long long>(vis->GetTotalNumberOfRays()), static_cast<long long>(cstats.rays_total),
        static_cast<long long>(vis->GetNumberOfNaiveRays()), ratio, vis->GetNumberOfDraws(), gpuTime, cTime);
      for (int i = layout.level_count - 1; i >= 0; --i)
      {
        std::printf("      level %d: computed %lld (C %lld) inherited %lld (C %lld) rays %lld (C %lld)\n", i,
          static_cast<long long>(vis->GetNumberOfComputedTexels(i)), static_cast<long long>(cstats.computed[i]),
          static_cast<long long>(vis->GetNumberOfInheritedTexels(i)), static_cast<long long>(cstats.inherited[i]),
          static_cast<long long>(vis->GetNumberOfRays(i)), static_cast<long long>(cstats.rays[i]));
      }
      std::fflush(stdout);
      MRGI_TEST_CHECK(r.Texels > 0);
      MRGI_TEST_CHECK(r.Rate() < MaxBitRate);
      // Counts agree up to what the differing bits change.
      const double tolerance = 0.01 * double(cstats.rays_total) + 64.0 * double(r.TexelsDiffer) * count;
      MRGI_TEST_CHECK(std::fabs(double(vis->GetTotalNumberOfRays() - cstats.rays_total)) <= tolerance);
      MRGI_TEST_CHECK(vis->GetNumberOfNaiveRays() == cstats.rays_naive);
      if (mode.Incremental && mode.Fraction > 0.0f)
      {
        // NPW10's claim: incremental visibility marches far fewer rays than
        // the naive query at full resolution (all levels counted; measured
        // 0.45-0.50 alone, 0.19-0.23 with interleaving).
        MRGI_TEST_CHECK(ratio < (mode.Interleave ? 0.3 : 0.6));
      }
      if (mode.TwoSided)
      {
        // The flip matters: a one-sided twin disagrees (the ceiling above
        // the light sees its samples only through flipped normals).
        std::vector<uint32_t> c1;
        mrgi_voxel_incremental_stats s1;
        CTwin(layout, P, N, view, oneSided, nullptr, params, true, c1, s1);
        const Result r1 = Compare(layout, P, gpu->GetPointer(0), c1, words);
        std::printf("    one-sided twin against the two-sided GPU: %zu bits differ\n", r1.Differ);
        MRGI_TEST_CHECK(r1.Differ > 0);
      }
      if (proveFailure && mode.Incremental && mode.Fraction > 0.0f && !mode.RefineSelected)
      {
        // A twin with the wrong threshold (refine fraction 1: almost never
        // refine) must fail the bound.
        mrgi_voxel_incremental_params wrong = params;
        wrong.refine_fraction = 1.0f;
        std::vector<uint32_t> cw;
        mrgi_voxel_incremental_stats ws;
        CTwin(layout, P, N, view, cs, nullptr, wrong, true, cw, ws);
        const Result rw = Compare(layout, P, gpu->GetPointer(0), cw, words);
        std::printf("    twin with refine fraction 1 (GPU %.2f): %zu bits differ = %.3f%% (must be >= %.1f%%)\n",
          double(mode.Fraction), rw.Differ, 100.0 * rw.Rate(), 100.0 * MaxBitRate);
        MRGI_TEST_CHECK(rw.Rate() >= MaxBitRate);
        ++failureChecks;
      }
    }
    sampleTexture->ReleaseGraphicsResources(window);
  }
  vis->ReleaseGraphicsResources(window);
  voxels->ReleaseGraphicsResources(window);
  multires->ReleaseGraphicsResources(window);
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
}
}

int main()
{
  const Mode naive = { "naive", false, false, 0.5f, MRGI_VOXEL_METRIC_DISAGREE, false };
  const Mode naiveInterleaved = { "naive, interleaved", false, true, 0.5f, MRGI_VOXEL_METRIC_DISAGREE, false };
  const Mode incremental = { "incremental", true, false, 0.5f, MRGI_VOXEL_METRIC_DISAGREE, false };
  const Mode incrementalInterleaved = { "incremental, interleaved", true, true, 0.5f,
    MRGI_VOXEL_METRIC_DISAGREE, false };
  const Mode spreadRefined = { "incr., count spread 0.25, selection", true, true, 0.25f,
    MRGI_VOXEL_METRIC_COUNT_SPREAD, true };
  const Mode everywhere = { "incremental, threshold 0", true, false, 0.0f, MRGI_VOXEL_METRIC_DISAGREE, false };
  // The light under cornell-spot's ceiling, emitting up as well: the ceiling
  // sees it through flipped sample normals.
  const Mode twoSided = { "incremental, two-sided light", true, false, 0.5f, MRGI_VOXEL_METRIC_DISAGREE,
    false, true };
  RunScene("cornell-area", 97, 61, { 64, 256 },
    { naive, naiveInterleaved, incremental, incrementalInterleaved, spreadRefined, everywhere }, true);
  RunScene("cornell-spot", 80, 53, { 64 }, { naive, incremental, incrementalInterleaved, twoSided }, true);
  // Levels 0 and 1 at least 128 wide march in batches, one draw per sample
  // range; the smaller ones as copies side by side (one draw): both ways.
  RunScene("cornell-area", 260, 132, { 64 }, { naive, incremental }, false);
  RunScene("cornell-area", 97, 61, { 64 }, { incremental, incrementalInterleaved }, false, true);
  MRGI_TEST_CHECK(failureChecks >= 2);
  return 0;
}
