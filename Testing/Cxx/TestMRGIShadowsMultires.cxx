// Multiresolution soft shadows (vtkMRGIDirectShadows::ComputeMultiresolution,
// BMR 3-4 with its SSM preset, through vtkMRGIPass ShadowResolution) against
// full resolution (Compute) on `cornell-spot` (a spot light's PCSS shadows):
// 1. the factors of slot 0 over the valid pixels are within BMR's figure-10
//    target (absolute RMS <= 0.005), all finite and in [0, 1], background 1;
// 2. the shadowed direct light (the picture) is within the same bound,
//    relative to its largest value;
// 3. it can fail: with the blend weights of levels 1-3 at 0 (level 4, 1/8
//    resolution, everywhere) the error is far larger;
// 4. the full-resolution path of the same code (depth threshold 0 and
//    normal threshold 0: level 1 everywhere) equals Compute().
// With MRGI_BMR_BENCHMARK=1, case Benchmark prints full vs multiresolution
// frame times (A B A B, medians) at 1280 x 720 and 1920 x 1080 and 196 taps.
#include "mrgiBMRTestUtilities.h"

#include "vtkMRGIBMRBlend.h"
#include "vtkMRGIDirectShadows.h"
#include "vtkPointData.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
using bmrtest::Median;

std::vector<float> Factors(bmrtest::Scene& s)
{
  s.Window->Render();
  vtkNew<vtkImageData> image;
  MRGI_TEST_CHECK(s.Pass->GetShadowFactorBuffer(s.Window, image));
  const float* f =
    vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars())->GetPointer(0);
  return std::vector<float>(f, f + 4 * static_cast<size_t>(s.W) * static_cast<size_t>(s.H));
}

std::vector<float> Picture(bmrtest::Scene& s)
{
  vtkNew<vtkFloatArray> rgba;
  MRGI_TEST_CHECK(s.Window->GetRGBAPixelData(0, 0, s.W - 1, s.H - 1, 0, rgba) == 1);
  return std::vector<float>(
    rgba->GetPointer(0), rgba->GetPointer(0) + 4 * rgba->GetNumberOfTuples());
}

struct Compared
{
  double RMS = 0.0;
  double MaxError = 0.0;
  size_t Bad = 0;
};

Compared CompareFactors(
  const bmrtest::Scene& s, const std::vector<float>& full, const std::vector<float>& multi)
{
  Compared c;
  double sum = 0.0;
  size_t n = 0;
  for (size_t p = 0; p < static_cast<size_t>(s.W) * static_cast<size_t>(s.H); ++p)
  {
    const bool valid = s.Position[4 * p + 3] > 0.5f;
    const float f = multi[4 * p];
    if (!std::isfinite(f) || f < 0.0f || f > 1.0f || (!valid && f != 1.0f))
    {
      ++c.Bad;
      continue;
    }
    if (valid)
    {
      const double d = static_cast<double>(f) - full[4 * p];
      sum += d * d;
      c.MaxError = std::max(c.MaxError, std::fabs(d));
      ++n;
    }
  }
  MRGI_TEST_CHECK(n > 0);
  c.RMS = std::sqrt(sum / static_cast<double>(n));
  return c;
}

void Setup(bmrtest::Scene& s, int w, int h, int kernel)
{
  bmrtest::RenderScene(s, "cornell-spot", w, h, false);
  s.Pass->SetDirectShadowsToSoft();
  s.Pass->SetSoftShadowKernelSize(kernel);
}

void CornellSpot()
{
  bmrtest::Scene s;
  Setup(s, 320, 240, 6);
  const std::vector<float> full = Factors(s);
  const std::vector<float> fullPicture = Picture(s);
  s.Pass->SetShadowResolution(vtkMRGIPass::ResolutionMultiresolution);
  const std::vector<float> multi = Factors(s);
  const std::vector<float> multiPicture = Picture(s);
  size_t shadowed = 0, penumbra = 0;
  for (size_t p = 0; p < full.size() / 4; ++p)
  {
    shadowed += full[4 * p] < 0.5f && s.Position[4 * p + 3] > 0.5f;
    penumbra += full[4 * p] > 0.0f && full[4 * p] < 1.0f && s.Position[4 * p + 3] > 0.5f;
  }
  bmrtest::GPUMasks g;
  bmrtest::ReadMasks(s.Window, s.Pass->GetDirectShadowStage()->GetBMRLevels(), g);
  mrgi_bmr_stats stats;
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_bmr_stats_compute(&g.Masks, &stats, &err) == MRGI_OK);
  const double v = static_cast<double>(std::max<int64_t>(stats.valid_pixels, 1));
  std::printf("SSM masks: pixels whose finest level is 1..4: %.3f %.3f %.3f %.3f; work %.3f; "
              "%zu penumbra pixels\n",
    stats.finest_pixels[0] / v, stats.finest_pixels[1] / v, stats.finest_pixels[2] / v,
    stats.finest_pixels[3] / v, stats.work_fraction, penumbra);
  const Compared c = CompareFactors(s, full, multi);
  double sum = 0.0, maxValue = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < fullPicture.size(); ++i)
  {
    if (i % 4 != 3)
    {
      const double d = multiPicture[i] - fullPicture[i];
      sum += d * d;
      maxValue = std::max(maxValue, static_cast<double>(fullPicture[i]));
      ++n;
    }
  }
  const double pictureRMS = std::sqrt(sum / static_cast<double>(n));
  std::printf("cornell-spot 320 x 240, 36 taps: %zu pixels in shadow; multiresolution factors "
              "vs full: absolute RMS %.5f, max %.4f, %zu bad; picture RMS %.5f (of max %.3f)\n",
    shadowed, c.RMS, c.MaxError, c.Bad, pictureRMS, maxValue);
  MRGI_TEST_CHECK(shadowed > 1000);
  MRGI_TEST_CHECK(c.Bad == 0);
  MRGI_TEST_CHECK(c.RMS <= 0.005);
  MRGI_TEST_CHECK(pictureRMS <= 0.005 * std::max(1.0, maxValue));

  // Level 1 everywhere: the same factors as Compute().
  vtkMRGIDirectShadows* stage = s.Pass->GetDirectShadowStage();
  stage->GetBMRMask()->SetDepthThreshold(0.0);
  const Compared same = CompareFactors(s, full, Factors(s));
  std::printf("threshold 0 (level 1 everywhere): RMS %.3g, max %.3g\n", same.RMS, same.MaxError);
  MRGI_TEST_CHECK(same.Bad == 0 && same.MaxError <= 1e-6);

  // Levels 1-3 weighted 0: level 4 everywhere.
  stage->GetBMRMask()->SetPreset(vtkMRGIBMRMask::SSM);
  for (int k = 0; k < 3; ++k)
  {
    stage->GetBMRBlend()->SetWeight(k, 0.0);
  }
  const Compared coarse = CompareFactors(s, full, Factors(s));
  std::printf("weights 0 (level 4 everywhere): RMS %.5f, max %.4f\n", coarse.RMS, coarse.MaxError);
  MRGI_TEST_CHECK(coarse.Bad == 0);
  MRGI_TEST_CHECK(coarse.RMS > 4.0 * c.RMS && coarse.RMS > 0.005);
  stage->GetBMRBlend()->SetPreset(vtkMRGIBMRMask::SSM);
  s.Pass->SetShadowResolution(99);
  MRGI_TEST_CHECK(s.Pass->GetShadowResolution() == vtkMRGIPass::ResolutionMultiresolution);
}

// Full (A) and multiresolution (B) frames, A B A B, wall clock after a warm-up.
void Benchmark()
{
  if (!bmrtest::BenchmarkEnabled())
  {
    return;
  }
  const char* repeatsEnv = std::getenv("MRGI_BMR_REPEATS");
  const int repeats = std::max(1, std::atoi(repeatsEnv ? repeatsEnv : "3"));
  const int sizes[2][2] = { { 1280, 720 }, { 1920, 1080 } };
  for (const auto& size : sizes)
  {
    for (int side : { 6, 10, 14 })
    {
      bmrtest::Scene s;
      Setup(s, size[0], size[1], side);
      std::vector<double> a, b;
      std::vector<float> full, multi;
      for (int r = 0; r <= repeats; ++r)
      {
        for (int m = 0; m < 2; ++m)
        {
          s.Pass->SetShadowResolution(m);
          s.GL->WaitForCompletion();
          auto t0 = std::chrono::steady_clock::now();
          s.Window->Render();
          s.GL->WaitForCompletion();
          auto t1 = std::chrono::steady_clock::now();
          if (r > 0)
          {
            (m ? b : a).push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
          }
        }
      }
      s.Pass->SetShadowResolution(0);
      full = Factors(s);
      s.Pass->SetShadowResolution(1);
      multi = Factors(s);
      const Compared c = CompareFactors(s, full, multi);
      std::printf("BENCH shadows %d %d taps %d full_frame_ms %.2f multires_frame_ms %.2f "
                  "speedup %.3f rms %.5f\n",
        s.W, s.H, side * side, Median(a), Median(b), Median(a) / Median(b), c.RMS);
      std::fflush(stdout);
    }
  }
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(
    argc, argv, { MRGI_TEST_CASE(CornellSpot), MRGI_TEST_CASE(Benchmark) });
}
