// MRGI's SSAO against VTK 9.1's own vtkSSAOPass on the Cornell box, with the
// same kernel size, radius and bias, in the same window (so the same noise
// texture):
//
// 1. Kernel: mrgi_ssao_kernel() equals vtkSSAOPass::ComputeKernel()'s
//    samples bit for bit, for sizes 1 .. 1000.
// 2. Algorithm: vtkSSAOPass's AO texture (8 bits) equals the C twin run on
//    vtkSSAOPass's OWN G-buffer (its half-float positions and normals, read
//    back), rounded to 8 bits, on every texel whose decisions are not
//    within rounding; here vtkSSAOPass's position mipmaps are limited to
//    level 0 (its textureLod then reads level 0 like MRGI).
// 3. MRGI against vtkSSAOPass as they are (MRGI: float G-buffer, float AO;
//    vtkSSAOPass: half-float positions, mipmaps, 8-bit AO): the residual is
//    measured and printed, and bounded by what those three differences
//    explain (Documentation/ScreenSpaceEffects-SSAO.md has the numbers).
#include "mrgiTestUtilities.h"

#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISSAO.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkSSAOPass.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "mrgi_ssao.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

// vtkSSAOPass with its kernel and buffers readable.
class vtkSSAOProbePass : public vtkSSAOPass
{
public:
  static vtkSSAOProbePass* New();
  vtkTypeMacro(vtkSSAOProbePass, vtkSSAOPass);

  const std::vector<float>& ComputeKernelSamples()
  {
    this->ComputeKernel();
    return this->Kernel;
  }
  vtkTextureObject* GetPosition() { return this->PositionTexture; }
  vtkTextureObject* GetNormal() { return this->NormalTexture; }
  vtkTextureObject* GetSSAO() { return this->SSAOTexture; }
  vtkTextureObject* GetDepth() { return this->DepthTexture; }

protected:
  vtkSSAOProbePass() = default;
  ~vtkSSAOProbePass() override = default;

private:
  vtkSSAOProbePass(const vtkSSAOProbePass&) = delete;
  void operator=(const vtkSSAOProbePass&) = delete;
};
vtkStandardNewMacro(vtkSSAOProbePass);

namespace
{
const int Width = 192;
const int Height = 128; // multiples of 64: vtkSSAOPass's noise lookups stay off texel edges
const int KernelSize = 32;
const double Radius = 30.0; // the Cornell box is 556 units wide
const double Bias = 0.6;

// Level 0 of a texture as floats (`format` GL_RGBA or GL_DEPTH_COMPONENT).
std::vector<float> Read(vtkTextureObject* t, unsigned int format, int components)
{
  std::vector<float> v(static_cast<size_t>(components) * t->GetWidth() * t->GetHeight());
  t->Activate();
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, format, GL_FLOAT, v.data());
  t->Deactivate();
  MRGI_TEST_CHECK(glGetError() == GL_NO_ERROR);
  return v;
}

// f rounded to a half float and back as llvmpipe stores it in an RGB16F
// texture: toward zero (measured: VTK's positions are MRGI's truncated).
float HalfRound(float f)
{
  if (!std::isfinite(f) || f == 0.0f)
  {
    return f;
  }
  if (std::fabs(f) < 6.103515625e-05f) // below the smallest normal half: steps of 2^-24
  {
    return std::trunc(f * 16777216.0f) / 16777216.0f;
  }
  uint32_t u;
  std::memcpy(&u, &f, sizeof(u));
  u &= ~0x1FFFu;
  std::memcpy(&f, &u, sizeof(u));
  return f;
}

float Quantize8(float v)
{
  return std::floor(v * 255.0f + 0.5f) / 255.0f;
}

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderStepsPass> Steps;

  Scene()
  {
    this->Window = mrgitest::HeadlessWindow(Width, Height);
    this->Window->AddRenderer(this->Renderer);
    vtkNew<vtkMRGISceneBuilder> builder;
    builder->SetScene("cornell");
    MRGI_TEST_CHECK(builder->Build(this->Renderer));
  }

  void Params(mrgi_ssao_params& params, std::vector<float>& kernel, std::vector<float>& noise)
  {
    kernel.resize(3 * KernelSize);
    MRGI_TEST_CHECK(mrgi_ssao_kernel(KernelSize, kernel.data(), nullptr) == MRGI_OK);
    MRGI_TEST_CHECK(
      vtkMRGISSAO::ReadNoise(vtkOpenGLRenderWindow::SafeDownCast(this->Window), noise));
    params.kernel = kernel.data();
    params.kernel_size = KernelSize;
    params.radius = static_cast<float>(Radius);
    params.bias = static_cast<float>(Bias);
    params.noise = noise.data();
    vtkMatrix4x4* m = this->Renderer->GetActiveCamera()->GetProjectionTransformMatrix(
      this->Renderer->GetTiledAspectRatio(), -1, 1);
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        params.projection[c * 4 + r] = static_cast<float>(m->GetElement(r, c));
      }
    }
  }

  // vtkSSAOPass's AO (8-bit, as floats) and, for the twin, its G-buffer:
  // position w = 1 where its depth buffer holds geometry.
  std::vector<float> RenderVTK(
    bool levelZeroOnly, mrgi_image* position, mrgi_image* normal, std::vector<float>* depth)
  {
    vtkNew<vtkSSAOProbePass> ssao;
    ssao->SetDelegatePass(this->Steps);
    ssao->SetKernelSize(KernelSize);
    ssao->SetRadius(Radius);
    ssao->SetBias(Bias);
    this->Renderer->SetPass(ssao);
    this->Window->Render(); // creates its buffers
    if (levelZeroOnly)
    {
      ssao->GetPosition()->SetMaxLevel(0);
      this->Window->Render();
    }
    const std::vector<float> ao = Read(ssao->GetSSAO(), GL_RED, 1);
    if (position)
    {
      const std::vector<float> p = Read(ssao->GetPosition(), GL_RGBA, 4);
      const std::vector<float> n = Read(ssao->GetNormal(), GL_RGBA, 4);
      const std::vector<float> d = Read(ssao->GetDepth(), GL_DEPTH_COMPONENT, 1);
      *depth = d;
      MRGI_TEST_CHECK(mrgi_image_create(position, Width, Height, 4, nullptr) == MRGI_OK);
      MRGI_TEST_CHECK(mrgi_image_create(normal, Width, Height, 4, nullptr) == MRGI_OK);
      std::copy(p.begin(), p.end(), position->pixels);
      std::copy(n.begin(), n.end(), normal->pixels);
      for (size_t i = 0; i < d.size(); ++i)
      {
        position->pixels[4 * i + 3] = d[i] > 0.0f && d[i] < 1.0f ? 1.0f : 0.0f;
      }
    }
    this->Renderer->SetPass(nullptr);
    ssao->ReleaseGraphicsResources(this->Window);
    return ao;
  }
};

void TestKernel()
{
  vtkNew<vtkSSAOProbePass> ssao;
  for (int size : { 1, 2, 8, 16, 32, 64, 128, 257, 1000 })
  {
    ssao->SetKernelSize(static_cast<unsigned int>(size));
    const std::vector<float>& vtk = ssao->ComputeKernelSamples();
    std::vector<float> mrgi(3 * static_cast<size_t>(size));
    MRGI_TEST_CHECK(mrgi_ssao_kernel(size, mrgi.data(), nullptr) == MRGI_OK);
    MRGI_TEST_CHECK(vtk.size() == mrgi.size());
    MRGI_TEST_CHECK(std::memcmp(vtk.data(), mrgi.data(), mrgi.size() * sizeof(float)) == 0);
  }
  std::printf("kernel: bit-equal to vtkSSAOPass's for sizes 1 .. 1000\n");
}

// The twin on vtkSSAOPass's own buffers reproduces its 8-bit AO.
void TestAlgorithm()
{
  Scene s;
  mrgi_image position, normal, twin;
  std::vector<float> depth;
  const std::vector<float> vtk = s.RenderVTK(true, &position, &normal, &depth);
  mrgi_ssao_params params = {};
  std::vector<float> kernel, noise;
  s.Params(params, kernel, noise);
  params.depth = depth.data(); // vtkSSAOPass's receiver test
  MRGI_TEST_CHECK(mrgi_ssao_compute(&params, &position, &normal, 0, &twin, nullptr) == MRGI_OK);
  const int n = Width * Height;
  int compared = 0, equal = 0, occluded = 0;
  double worst = 0.0;
  for (int i = 0; i < n; ++i)
  {
    occluded += vtk[i] < 0.99f;
    if (twin.pixels[2 * i + 1] < 1e-5f)
    {
      continue;
    }
    ++compared;
    const float d = std::fabs(Quantize8(twin.pixels[2 * i]) - vtk[i]);
    equal += d < 1e-6f;
    worst = std::max(worst, static_cast<double>(d));
  }
  std::printf("vtkSSAOPass (mipmaps off) against the C twin on its own buffers: %d texels, %d "
              "compared, %d equal after rounding to 8 bits, max |difference| %.3g, %d occluded\n",
    n, compared, equal, worst, occluded);
  MRGI_TEST_CHECK(compared >= 0.97 * n);
  MRGI_TEST_CHECK(occluded >= n / 50);
  // Exact but for ties of the 8-bit rounding (a float AO within an ulp of a
  // half step): at most one step, on few texels.
  MRGI_TEST_CHECK(worst <= 1.0 / 255.0 + 1e-6);
  MRGI_TEST_CHECK(equal >= compared - compared / 1000);
  mrgi_image_destroy(&twin);
  mrgi_image_destroy(&position);
  mrgi_image_destroy(&normal);
}

// MRGI's full-resolution SSAO against vtkSSAOPass as both are.
void TestMRGIAgainstVTK()
{
  Scene s;
  for (int mip = 0; mip <= 1; ++mip)
  {
    const std::vector<float> vtk = s.RenderVTK(mip == 0, nullptr, nullptr, nullptr);
    vtkNew<vtkMRGIPass> pass;
    pass->SetDelegatePass(s.Steps);
    pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
    pass->SSAOOn();
    pass->SetSSAOKernelSize(KernelSize);
    pass->SetSSAORadius(Radius);
    pass->SetSSAOBias(Bias);
    s.Renderer->SetPass(pass);
    s.Window->Render();
    vtkNew<vtkFloatArray> ao;
    MRGI_TEST_CHECK(pass->GetSSAOStage()->ReadAO(s.Window, ao));
    if (mip == 0)
    {
      // The cause of the residual: MRGI's float G-buffer rounded to half
      // floats (vtkSSAOPass's RGB16F), its depth test against the float
      // position's depth, through the twin, gives vtkSSAOPass's AO.
      vtkNew<vtkImageData> p, nrm, albedo;
      MRGI_TEST_CHECK(pass->GetGBuffer(s.Window, p, nrm, albedo));
      mrgi_ssao_params params = {};
      std::vector<float> kernel, noise, depth(static_cast<size_t>(Width) * Height);
      s.Params(params, kernel, noise);
      mrgi_image position, normal, twin;
      MRGI_TEST_CHECK(mrgi_image_create(&position, Width, Height, 4, nullptr) == MRGI_OK);
      MRGI_TEST_CHECK(mrgi_image_create(&normal, Width, Height, 4, nullptr) == MRGI_OK);
      const float* pf = vtkFloatArray::SafeDownCast(p->GetPointData()->GetScalars())->GetPointer(0);
      const float* nf =
        vtkFloatArray::SafeDownCast(nrm->GetPointData()->GetScalars())->GetPointer(0);
      for (size_t i = 0; i < depth.size(); ++i)
      {
        const float* q = pf + 4 * i;
        const float* m = params.projection;
        const float z = m[2] * q[0] + m[6] * q[1] + m[10] * q[2] + m[14];
        const float w = m[3] * q[0] + m[7] * q[1] + m[11] * q[2] + m[15];
        depth[i] = q[3] > 0.5f ? z / w * 0.5f + 0.5f : 1.0f;
        for (int c = 0; c < 3; ++c)
        {
          position.pixels[4 * i + c] = HalfRound(q[c]);
          normal.pixels[4 * i + c] = HalfRound(nf[4 * i + c]);
        }
        position.pixels[4 * i + 3] = q[3];
      }
      params.depth = depth.data();
      MRGI_TEST_CHECK(mrgi_ssao_compute(&params, &position, &normal, 0, &twin, nullptr) == MRGI_OK);
      int compared = 0, equal = 0;
      for (size_t i = 0; i < depth.size(); ++i)
      {
        if (twin.pixels[2 * i + 1] >= 1e-5f)
        {
          ++compared;
          equal += std::fabs(Quantize8(twin.pixels[2 * i]) - vtk[i]) < 1e-6f;
        }
      }
      std::printf("MRGI's G-buffer rounded to half floats, through the twin: %d of %d compared "
                  "texels equal vtkSSAOPass's 8-bit AO\n",
        equal, compared);
      MRGI_TEST_CHECK(compared >= 0.97 * Width * Height);
      MRGI_TEST_CHECK(equal >= compared - compared / 100);
      mrgi_image_destroy(&twin);
      mrgi_image_destroy(&position);
      mrgi_image_destroy(&normal);
    }
    s.Renderer->SetPass(nullptr);
    pass->ReleaseGraphicsResources(s.Window);
    const int n = Width * Height;
    MRGI_TEST_CHECK(ao->GetNumberOfTuples() == n);
    double sum = 0.0, sumQ = 0.0, sq = 0.0, worst = 0.0;
    int within1e3 = 0, sameStep = 0;
    for (int i = 0; i < n; ++i)
    {
      const float m = ao->GetValue(i);
      const double d = std::fabs(static_cast<double>(m) - vtk[i]);
      const double dq = std::fabs(static_cast<double>(Quantize8(m)) - vtk[i]);
      sum += d;
      sq += d * d;
      sumQ += dq;
      worst = std::max(worst, d);
      within1e3 += d <= 1e-3;
      sameStep += dq < 1e-6;
    }
    const double mean = sum / n, rms = std::sqrt(sq / n);
    std::printf("MRGI against vtkSSAOPass (mipmaps %s): AO mean |difference| %.3g, RMS %.3g, max "
                "%.3g; %.1f%% of pixels within 1e-3, %.1f%% equal after rounding MRGI's to 8 "
                "bits (mean %.3g)\n",
      mip ? "on, as VTK ships" : "off", mean, rms, worst, 100.0 * within1e3 / n,
      100.0 * sameStep / n, sumQ / n);
    // Not within 1e-3: vtkSSAOPass's half-float positions flip depth tests
    // (the twin above shows they explain every difference without
    // mipmaps), its 8-bit AO adds up to 1/510, its mipmaps read coarser
    // depths. Bounds at about 1.5x the measured residual on this scene
    // (Documentation/ScreenSpaceEffects-SSAO.md), so a change that moves
    // MRGI away from vtkSSAOPass fails.
    MRGI_TEST_CHECK(mean <= (mip ? 0.02 : 0.006));
    MRGI_TEST_CHECK(sameStep >= (mip ? 0.6 : 0.85) * n);
  }
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestKernel), MRGI_TEST_CASE(TestAlgorithm),
      MRGI_TEST_CASE(TestMRGIAgainstVTK) });
}
