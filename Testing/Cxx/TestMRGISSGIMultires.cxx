// Multiresolution SSGI (vtkMRGISSGI::ComputeMultiresolution, BMR 3-4 with
// the SSGI row of its Table 1: level 2 skipped) against the full-resolution
// SSGI (Compute level 0) on Cornell renders, the direct light of the frame
// as the senders:
// 1. the absolute RMS of the bounce (rgb, colour units) over the valid
//    pixels is within BMR's figure-10 target (<= 0.01), every value finite,
//    background 0;
// 2. the full-resolution path of the same code (depth threshold 0: level 1
//    everywhere) equals Compute level 0;
// 3. it can fail: with the edge tests off (level 4 only) the error is far
//    larger;
// 4. vtkMRGIPass with SSGIResolution multiresolution renders the same
//    picture as full resolution within the same bound;
// 5. bad input is refused.
// With MRGI_BMR_BENCHMARK=1, case Benchmark prints full vs multiresolution
// times (A B A B, medians) at 1280 x 720 and 1920 x 1080 for the sample
// counts of MRGI_BMR_SSGI_SAMPLES (default 228, BMR figure 6).
#include "mrgiBMRTestUtilities.h"

#include "vtkMRGIBMRBlend.h"
#include "vtkMRGISSGI.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
const int Samples = 64;
const double Radius = 60.0; // the Cornell box is 556 units wide (as TestMRGISSGI)
const double Bias = 0.6;

struct Compared
{
  std::vector<float> Difference; // |multires - full| bounce (max over rgb) per pixel
  double RMS = 0.0;              // absolute RMS of the bounce over valid pixels and channels
  double MaxError = 0.0;
  double Largest = 0.0; // the largest full-resolution bounce
  size_t Bad = 0;       // non-finite, or a background value other than 0
};

// The direct light of the scene's frame (no indirect light) as a texture.
vtkTextureObject* Direct(bmrtest::Scene& s)
{
  s.Pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  s.Window->Render();
  vtkNew<vtkImageData> colour;
  MRGI_TEST_CHECK(s.Pass->GetColorBuffer(s.Window, colour));
  MRGI_TEST_CHECK(colour->GetDimensions()[0] == s.W && colour->GetDimensions()[1] == s.H);
  return s.Texture(static_cast<const float*>(colour->GetScalarPointer()));
}

// Both paths over the scene's viewport, compared at the valid pixels.
Compared Compare(bmrtest::Scene& s, vtkMRGISSGI* ssgi, vtkTextureObject* direct, int samples)
{
  vtkTextureObject* full = s.Texture(nullptr);
  vtkTextureObject* multi = s.Texture(nullptr);
  MRGI_TEST_CHECK(ssgi->Compute(s.Frame, direct, samples, Radius, Bias, 0, full));
  MRGI_TEST_CHECK(ssgi->ComputeMultiresolution(s.Frame, direct, samples, Radius, Bias, multi));
  const std::vector<float> a = bmrtest::Read(s.GL, full, 0, 0, s.W, s.H);
  const std::vector<float> b = bmrtest::Read(s.GL, multi, 0, 0, s.W, s.H);
  Compared c;
  const size_t pixels = static_cast<size_t>(s.W) * static_cast<size_t>(s.H);
  c.Difference.assign(pixels, 0.0f);
  double sum = 0.0;
  size_t n = 0;
  for (size_t p = 0; p < pixels; ++p)
  {
    const bool valid = s.Position[4 * p + 3] > 0.5f;
    for (size_t k = 0; k < 3; ++k)
    {
      const double m = b[4 * p + k];
      if (!std::isfinite(m) || (!valid && m != 0.0))
      {
        ++c.Bad;
        continue;
      }
      if (!valid)
      {
        continue;
      }
      const double d = m - static_cast<double>(a[4 * p + k]);
      sum += d * d;
      ++n;
      c.MaxError = std::max(c.MaxError, std::fabs(d));
      c.Largest = std::max(c.Largest, static_cast<double>(a[4 * p + k]));
      c.Difference[p] = std::max(c.Difference[p], static_cast<float>(std::fabs(d)));
    }
  }
  MRGI_TEST_CHECK(n > 0);
  c.RMS = std::sqrt(sum / static_cast<double>(n));
  return c;
}

void CheckScene(const char* name, int w, int h, bool parallel)
{
  bmrtest::Scene s;
  bmrtest::RenderScene(s, name, w, h, parallel);
  vtkTextureObject* direct = Direct(s);
  vtkNew<vtkMRGISSGI> ssgi;
  MRGI_TEST_CHECK(ssgi->GetBMRMask()->GetSkipLevel(1)); // Table 1's SSGI row
  const Compared multi = Compare(s, ssgi, direct, Samples);
  std::printf("%s %d x %d: multiresolution vs full-resolution SSGI bounce, absolute RMS %.5f, "
              "max %.4f (largest bounce %.4f); %zu bad values\n",
    name, s.W, s.H, multi.RMS, multi.MaxError, multi.Largest, multi.Bad);
  MRGI_TEST_CHECK(multi.Bad == 0 && multi.Largest > 0.01);
  MRGI_TEST_CHECK(multi.RMS <= 0.01);

  // The full-resolution path of the same code.
  ssgi->GetBMRMask()->SetDepthThreshold(0.0);
  const Compared same = Compare(s, ssgi, direct, Samples);
  std::printf("%s: threshold 0 (level 1 everywhere): RMS %.3g, max %.3g\n", name, same.RMS,
    same.MaxError);
  MRGI_TEST_CHECK(same.Bad == 0 && same.MaxError <= 1e-6);

  // Masks forced to nothing: level 4 (1/8 resolution) everywhere.
  ssgi->GetBMRMask()->SetDepthThreshold(-1.0);
  ssgi->GetBMRMask()->SetNormalThreshold(-1.0);
  const Compared coarse = Compare(s, ssgi, direct, Samples);
  std::printf("%s: edge tests off (level 4 only): RMS %.5f, max %.4f\n", name, coarse.RMS,
    coarse.MaxError);
  MRGI_TEST_CHECK(coarse.Bad == 0);
  MRGI_TEST_CHECK(coarse.RMS > 2.0 * multi.RMS);
  ssgi->ReleaseGraphicsResources(s.Window);
}

void Cornell()
{
  CheckScene("cornell", 320, 240, false);
}

// Odd sizes: level sizes that do not divide (ceil(W / 2^k)).
void CornellOdd()
{
  CheckScene("cornell", 241, 163, false);
}

// The pass: SSGIResolution multiresolution against full resolution.
void Pass()
{
  bmrtest::Scene s;
  bmrtest::RenderScene(s, "cornell", 320, 240, false);
  s.Pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  s.Pass->SSGIOn();
  s.Pass->SetSSGISamples(Samples);
  s.Pass->SetSSGIRadius(Radius);
  s.Pass->SetSSGIBias(Bias);
  MRGI_TEST_CHECK(s.Pass->GetSSGIResolution() == vtkMRGIPass::ResolutionFull);
  const std::vector<std::vector<float>> images = bmrtest::RenderResolutions(s,
    { vtkMRGIPass::ResolutionFull, vtkMRGIPass::ResolutionMultiresolution },
    [&s](int r) { s.Pass->SetSSGIResolution(r); });
  MRGI_TEST_CHECK(images.size() == 2);
  if (images.size() != 2)
  {
    return;
  }
  s.Pass->SetSSGIResolution(99);
  MRGI_TEST_CHECK(s.Pass->GetSSGIResolution() == vtkMRGIPass::ResolutionMultiresolution);
  s.Pass->SetSSGIResolution(-3);
  MRGI_TEST_CHECK(s.Pass->GetSSGIResolution() == vtkMRGIPass::ResolutionFull);
  const bmrtest::ImageDifference d = bmrtest::CompareRGB(images[0], images[1]);
  std::printf("pass 320 x 240: multiresolution vs full-resolution SSGI picture: RMS %.5f, max "
              "%.4f (colour up to %.3f), %zu non-finite\n",
    d.RMS, d.MaxError, d.MaxValue, d.Bad);
  MRGI_TEST_CHECK(d.Bad == 0 && d.MaxValue > 0.0);
  MRGI_TEST_CHECK(d.MaxError > 0.0); // the two paths did run differently
  MRGI_TEST_CHECK(d.RMS <= 0.01 * std::max(1.0, d.MaxValue));
}

void BadInput()
{
  bmrtest::Scene s;
  bmrtest::RenderScene(s, "cornell", 64, 48, false);
  vtkTextureObject* direct = Direct(s);
  vtkNew<vtkMRGISSGI> ssgi;
  vtkNew<vtkMRGIBMRLevels> unprepared;
  std::printf("(errors about unprepared levels, a small target and bad arguments are expected)\n");
  MRGI_TEST_CHECK(!ssgi->ComputeLevels(s.Frame, direct, Samples, Radius, Bias, unprepared));
  MRGI_TEST_CHECK(!ssgi->ComputeLevels(s.Frame, direct, Samples, Radius, Bias, nullptr));
  vtkSmartPointer<vtkTextureObject> small = bmrtest::Upload(s.GL, 8, 8, nullptr);
  MRGI_TEST_CHECK(!ssgi->ComputeMultiresolution(s.Frame, direct, Samples, Radius, Bias, small));
  MRGI_TEST_CHECK(
    !ssgi->ComputeMultiresolution(s.Frame, direct, 0, Radius, Bias, s.Texture(nullptr)));
  MRGI_TEST_CHECK(
    !ssgi->ComputeMultiresolution(s.Frame, nullptr, Samples, Radius, Bias, s.Texture(nullptr)));
  MRGI_TEST_CHECK(
    !ssgi->ComputeMultiresolution(s.Frame, direct, Samples, Radius, -1.0, s.Texture(nullptr)));
  MRGI_TEST_CHECK(!ssgi->RenderMultiresolution(s.Frame, Samples, -1.0, Bias, s.Texture(nullptr)));
  MRGI_TEST_CHECK(!ssgi->RenderMultiresolution(s.Frame, Samples, Radius, Bias, nullptr));
  small->ReleaseGraphicsResources(s.Window);
  ssgi->ReleaseGraphicsResources(s.Window);
}

// Full (A) and multiresolution (B) SSGI, A B A B, wall clock after a warm-up.
void Benchmark()
{
  if (!bmrtest::BenchmarkEnabled())
  {
    return;
  }
  const int sizes[2][2] = { { 1280, 720 }, { 1920, 1080 } };
  const std::vector<int> sampleCounts = bmrtest::EnvInts("MRGI_BMR_SSGI_SAMPLES", "228");
  const int repeats = bmrtest::BenchmarkRepeats();
  for (const auto& size : sizes)
  {
    bmrtest::Scene s;
    bmrtest::RenderScene(s, "cornell", size[0], size[1], false);
    vtkTextureObject* direct = Direct(s);
    vtkNew<vtkMRGISSGI> ssgi;
    vtkTextureObject* full = s.Texture(nullptr);
    vtkTextureObject* multi = s.Texture(nullptr);
    for (int samples : sampleCounts)
    {
      std::vector<double> a, b;
      for (int r = 0; r <= repeats; ++r)
      {
        s.GL->WaitForCompletion();
        auto t0 = std::chrono::steady_clock::now();
        MRGI_TEST_CHECK(ssgi->Compute(s.Frame, direct, samples, Radius, Bias, 0, full));
        s.GL->WaitForCompletion();
        auto t1 = std::chrono::steady_clock::now();
        MRGI_TEST_CHECK(
          ssgi->ComputeMultiresolution(s.Frame, direct, samples, Radius, Bias, multi));
        s.GL->WaitForCompletion();
        auto t2 = std::chrono::steady_clock::now();
        if (r > 0) // the first run compiles the programs
        {
          a.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
          b.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
        }
      }
      const Compared c = Compare(s, ssgi, direct, samples);
      std::printf("BENCH ssgi %d %d samples %d full_ms %.2f multires_ms %.2f speedup %.3f "
                  "rms %.5f max %.5f largest %.4f\n",
        s.W, s.H, samples, bmrtest::Median(a), bmrtest::Median(b), bmrtest::Median(a) / bmrtest::Median(b), c.RMS, c.MaxError,
        c.Largest);
      std::fflush(stdout);
    }
    ssgi->ReleaseGraphicsResources(s.Window);
  }
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(Cornell), MRGI_TEST_CASE(CornellOdd), MRGI_TEST_CASE(Pass),
      MRGI_TEST_CASE(BadInput), MRGI_TEST_CASE(Benchmark) });
}
