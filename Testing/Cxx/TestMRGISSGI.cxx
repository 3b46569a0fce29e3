// GPU / C parity of MRGI's SSGI stage (vtkMRGISSGI against mrgi_ssgi):
//
// 1. a Cornell render (200 x 150: not square) through vtkMRGIPass with SSGI
//    on: the read-back G-buffer, the direct light of the same frame without
//    SSGI and the camera's projection fed to mrgi_ssgi_compute() give the
//    GPU's bounce within 1e-4 relative (of the texel's value, or of 1 % of
//    the largest bounce where the value is smaller) and its visibility
//    within 1e-4, wherever no decision of the receiver lies within rounding
//    of its threshold (mrgi_ssgi.h, "decision margin"); those must be rare;
// 2. apply: the colour with SSGI is the colour without plus the bounce;
//    exclusive with the VPL gather: with IndirectMode on, no indirect light
//    is computed while SSGI is on;
// 3. level 1 (a level texel evaluates its block's centre pixel) against
//    the twin's level 1;
// 4. bad input: every argument out of range is refused;
// 5. a renderer in part of the window, on a second layer, with FXAA: the
//    same parity on the viewport, nothing outside it changes.
// The measured errors are printed for the documentation.
#include "mrgiTestUtilities.h"

#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISSGI.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "mrgi_ssgi.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
const int Width = 200;
const int Height = 150;
const int Samples = 64;
const double Radius = 60.0; // the Cornell box is 556 units wide
const double Bias = 0.6;

float* Floats(vtkImageData* image)
{
  return vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars())->GetPointer(0);
}

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderStepsPass> Steps;
  vtkNew<vtkMRGIPass> Pass;

  Scene()
  {
    this->Window = mrgitest::HeadlessWindow(Width, Height);
    this->Window->AddRenderer(this->Renderer);
    vtkNew<vtkMRGISceneBuilder> builder;
    builder->SetScene("cornell");
    MRGI_TEST_CHECK(builder->Build(this->Renderer));
    this->Pass->SetDelegatePass(this->Steps);
    this->Pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
    this->Pass->SetSSGISamples(Samples);
    this->Pass->SetSSGIRadius(Radius);
    this->Pass->SetSSGIBias(Bias);
    this->Renderer->SetPass(this->Pass);
  }
  ~Scene()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
};

void ToImage(vtkImageData* src, int w, int h, mrgi_image& out)
{
  MRGI_TEST_CHECK(mrgi_image_create(&out, w, h, 4, nullptr) == MRGI_OK);
  std::copy(Floats(src), Floats(src) + 4 * w * h, out.pixels);
}

// GPU (4 floats per texel, `stride` texels per row) against the twin's
// (rgb, V, margin).
void Compare(const char* what, const float* gpu, int stride, const mrgi_image& twin)
{
  float largest = 0.0f;
  for (int i = 0; i < twin.width * twin.height; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      largest = std::max(largest, twin.pixels[MRGI_SSGI_CHANNELS * i + c]);
    }
  }
  int compared = 0, nearTie = 0, bouncing = 0, differing = 0;
  double worst = 0.0, worstV = 0.0;
  for (int y = 0; y < twin.height; ++y)
  {
    for (int x = 0; x < twin.width; ++x)
    {
      const float* t = mrgi_image_at(&twin, x, y);
      const float* g = gpu + 4 * (static_cast<size_t>(y) * stride + x);
      double rel = 0.0;
      for (int c = 0; c < 4; ++c)
      {
        MRGI_TEST_CHECK(std::isfinite(g[c]));
      }
      for (int c = 0; c < 3; ++c)
      {
        const double scale = std::max(std::fabs(t[c]), 0.01f * largest);
        rel = std::max(rel, std::fabs(g[c] - t[c]) / std::max(scale, 1e-30));
      }
      const double dv = std::fabs(g[3] - t[3]);
      bouncing += t[0] + t[1] + t[2] > 0.0f;
      differing += rel > 1e-4 || dv > 1e-4;
      if (t[4] < 1e-5f)
      {
        ++nearTie;
        continue;
      }
      ++compared;
      worst = std::max(worst, rel);
      worstV = std::max(worstV, dv);
    }
  }
  const int n = twin.width * twin.height;
  std::printf("%s: %d texels, %d compared, %d within rounding of a decision, %d bounce; max "
              "relative bounce error %.3g, max |V| error %.3g there; %d texels differ by more "
              "than 1e-4 (largest bounce %.4g)\n",
    what, n, compared, nearTie, bouncing, worst, worstV, differing, largest);
  MRGI_TEST_CHECK(worst <= 1e-4);
  MRGI_TEST_CHECK(worstV <= 1e-4);
  MRGI_TEST_CHECK(compared >= 9 * n / 10);
  MRGI_TEST_CHECK(bouncing >= n / 50); // the corners do bounce
  MRGI_TEST_CHECK(largest > 0.0f);
}

bool ReadTexture(vtkTextureObject* t, std::vector<float>& rgba)
{
  rgba.assign(4 * static_cast<size_t>(t->GetWidth()) * t->GetHeight(), 0.0f);
  t->Activate();
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, rgba.data());
  t->Deactivate();
  return glGetError() == GL_NO_ERROR;
}

// The twin's inputs from the last frame: G-buffer, direct light, projection.
struct TwinInputs
{
  mrgi_image Position = {}, Normal = {}, Albedo = {}, Direct = {};
  std::vector<float> Kernel;
  mrgi_ssgi_params Params = {};

  TwinInputs(Scene& s, vtkImageData* directImage)
  {
    vtkNew<vtkImageData> p, n, a;
    MRGI_TEST_CHECK(s.Pass->GetGBuffer(s.Window, p, n, a));
    int w = 0, h = 0, x0 = 0, y0 = 0;
    s.Renderer->GetTiledSizeAndOrigin(&w, &h, &x0, &y0);
    MRGI_TEST_CHECK(p->GetDimensions()[0] == w && p->GetDimensions()[1] == h);
    ToImage(p, w, h, this->Position);
    ToImage(n, w, h, this->Normal);
    ToImage(a, w, h, this->Albedo);
    ToImage(directImage, w, h, this->Direct);
    this->Kernel.resize(3 * Samples);
    MRGI_TEST_CHECK(mrgi_ssgi_kernel(Samples, this->Kernel.data(), nullptr) == MRGI_OK);
    this->Params.kernel = this->Kernel.data();
    this->Params.sample_count = Samples;
    this->Params.radius = static_cast<float>(Radius);
    this->Params.bias = static_cast<float>(Bias);
    vtkMatrix4x4* m = s.Renderer->GetActiveCamera()->GetProjectionTransformMatrix(
      s.Renderer->GetTiledAspectRatio(), -1, 1);
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        this->Params.projection[c * 4 + r] = static_cast<float>(m->GetElement(r, c));
      }
    }
  }
  ~TwinInputs()
  {
    mrgi_image_destroy(&this->Position);
    mrgi_image_destroy(&this->Normal);
    mrgi_image_destroy(&this->Albedo);
    mrgi_image_destroy(&this->Direct);
  }
  bool Compute(int level, mrgi_image& out)
  {
    return mrgi_ssgi_compute(&this->Params, &this->Position, &this->Normal, &this->Albedo,
             &this->Direct, level, &out, nullptr) == MRGI_OK;
  }
};

void TestCornell()
{
  Scene s;
  s.Window->Render();
  vtkNew<vtkImageData> directImage;
  MRGI_TEST_CHECK(s.Pass->GetColorBuffer(s.Window, directImage));
  s.Pass->SSGIOn();
  s.Window->Render();
  vtkNew<vtkImageData> colourImage;
  MRGI_TEST_CHECK(s.Pass->GetColorBuffer(s.Window, colourImage));
  vtkNew<vtkFloatArray> result;
  MRGI_TEST_CHECK(s.Pass->GetSSGIStage()->ReadResult(s.Window, result));
  MRGI_TEST_CHECK(result->GetNumberOfTuples() == Width * Height);

  TwinInputs in(s, directImage);
  mrgi_image twin;
  MRGI_TEST_CHECK(in.Compute(0, twin));
  Compare("level 0", result->GetPointer(0), Width, twin);
  mrgi_image_destroy(&twin);

  // Apply: colour = direct + bounce, alpha kept.
  double worst = 0.0;
  const float* d = Floats(directImage);
  const float* c = Floats(colourImage);
  const float* r = result->GetPointer(0);
  for (int i = 0; i < Width * Height; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double expected = static_cast<double>(d[4 * i + k]) + r[4 * i + k];
      worst =
        std::max(worst, std::fabs(c[4 * i + k] - expected) / std::max(1e-3, std::fabs(expected)));
    }
    MRGI_TEST_CHECK(c[4 * i + 3] == d[4 * i + 3]);
  }
  std::printf("apply: max relative |colour - (direct + bounce)| = %.3g\n", worst);
  MRGI_TEST_CHECK(worst <= 1e-5);

  // Level 1 through Compute() on the same buffers.
  vtkOpenGLRenderWindow* gl = vtkOpenGLRenderWindow::SafeDownCast(s.Window);
  vtkNew<vtkTextureObject> target;
  target->SetContext(gl);
  target->SetInternalFormat(GL_RGBA32F);
  target->SetFormat(GL_RGBA);
  target->SetDataType(GL_FLOAT);
  MRGI_TEST_CHECK(target->Allocate2D(Width, Height, 4, VTK_FLOAT));
  vtkNew<vtkTextureObject> directTexture;
  directTexture->SetContext(gl);
  directTexture->SetInternalFormat(GL_RGBA32F);
  directTexture->SetFormat(GL_RGBA);
  directTexture->SetDataType(GL_FLOAT);
  MRGI_TEST_CHECK(directTexture->Create2DFromRaw(Width, Height, 4, VTK_FLOAT, Floats(directImage)));
  vtkMRGIFrameContext frame;
  frame.Window = gl;
  frame.Renderer = s.Renderer;
  frame.Position = s.Pass->GetPositionTexture();
  frame.Normal = s.Pass->GetNormalTexture();
  frame.Albedo = s.Pass->GetAlbedoTexture();
  frame.Viewport[2] = Width;
  frame.Viewport[3] = Height;
  vtkMRGISSGI* stage = s.Pass->GetSSGIStage();
  gl->MakeCurrent();
  MRGI_TEST_CHECK(stage->Compute(frame, directTexture, Samples, Radius, Bias, 1, target));
  std::vector<float> rgba;
  MRGI_TEST_CHECK(ReadTexture(target, rgba));
  MRGI_TEST_CHECK(in.Compute(1, twin));
  Compare("level 1", rgba.data(), Width, twin);
  mrgi_image_destroy(&twin);

  // Bad input: refused.
  std::printf("expected errors follow:\n");
  MRGI_TEST_CHECK(!stage->Compute(frame, directTexture, 0, Radius, Bias, 0, target));
  MRGI_TEST_CHECK(
    !stage->Compute(frame, directTexture, MRGI_SSGI_MAX_SAMPLES + 1, Radius, Bias, 0, target));
  MRGI_TEST_CHECK(!stage->Compute(frame, directTexture, Samples, std::nan(""), Bias, 0, target));
  MRGI_TEST_CHECK(!stage->Compute(frame, directTexture, Samples, 0.0, Bias, 0, target));
  MRGI_TEST_CHECK(!stage->Compute(frame, directTexture, Samples, 1e300, Bias, 0, target));
  MRGI_TEST_CHECK(!stage->Compute(frame, directTexture, Samples, Radius, -1.0, 0, target));
  MRGI_TEST_CHECK(
    !stage->Compute(frame, directTexture, Samples, Radius, Bias, MRGI_SSGI_MAX_LEVEL + 1, target));
  MRGI_TEST_CHECK(!stage->Compute(frame, nullptr, Samples, Radius, Bias, 0, target));
  MRGI_TEST_CHECK(!stage->Compute(frame, directTexture, Samples, Radius, Bias, 0, nullptr));
  vtkMRGIFrameContext empty;
  MRGI_TEST_CHECK(!stage->Compute(empty, directTexture, Samples, Radius, Bias, 0, target));
  MRGI_TEST_CHECK(!stage->Apply(empty, target, target));
  target->ReleaseGraphicsResources(gl);
  directTexture->ReleaseGraphicsResources(gl);
}

// A renderer in part of the window (a second one, without MRGI, behind
// it), FXAA on: the result on the viewport equals the twin's on the
// viewport's buffers, colour = direct + bounce there, and the window
// outside the viewport is untouched.
void TestViewport()
{
  Scene s;
  s.Renderer->SetViewport(0.15, 0.1, 0.9, 0.95);
  s.Renderer->UseFXAAOn();
  vtkNew<vtkRenderer> back;
  back->SetBackground(0.2, 0.4, 0.6);
  back->SetLayer(0);
  s.Window->SetNumberOfLayers(2);
  s.Renderer->SetLayer(1);
  s.Window->AddRenderer(back);
  s.Window->Render();
  vtkSmartPointer<vtkImageData> plain = mrgitest::GrabRGB(s.Window);
  vtkNew<vtkImageData> direct;
  MRGI_TEST_CHECK(s.Pass->GetColorBuffer(s.Window, direct));
  s.Pass->SSGIOn();
  s.Window->Render();
  vtkSmartPointer<vtkImageData> shaded = mrgitest::GrabRGB(s.Window);
  vtkNew<vtkImageData> colour;
  MRGI_TEST_CHECK(s.Pass->GetColorBuffer(s.Window, colour));
  int w = 0, h = 0, x0 = 0, y0 = 0;
  s.Renderer->GetTiledSizeAndOrigin(&w, &h, &x0, &y0);
  MRGI_TEST_CHECK(x0 > 0 && y0 > 0 && w < Width && h < Height);
  vtkNew<vtkFloatArray> result;
  MRGI_TEST_CHECK(s.Pass->GetSSGIStage()->ReadResult(s.Window, result));
  MRGI_TEST_CHECK(result->GetNumberOfTuples() == w * h);
  {
    TwinInputs in(s, direct);
    mrgi_image twin;
    MRGI_TEST_CHECK(in.Compute(0, twin));
    Compare("viewport", result->GetPointer(0), w, twin);
    mrgi_image_destroy(&twin);
  }
  double worst = 0.0;
  const float* d = Floats(direct);
  const float* c = Floats(colour);
  const float* r = result->GetPointer(0);
  for (int i = 0; i < w * h; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double expected = static_cast<double>(d[4 * i + k]) + r[4 * i + k];
      worst =
        std::max(worst, std::fabs(c[4 * i + k] - expected) / std::max(1e-3, std::fabs(expected)));
    }
  }
  std::printf("viewport %d x %d at (%d, %d): max relative |colour - (direct + bounce)| = %.3g\n", w,
    h, x0, y0, worst);
  MRGI_TEST_CHECK(worst <= 1e-5);
  const unsigned char* a = static_cast<unsigned char*>(plain->GetScalarPointer());
  const unsigned char* b = static_cast<unsigned char*>(shaded->GetScalarPointer());
  int changedOutside = 0, changedInside = 0;
  for (int y = 0; y < Height; ++y)
  {
    for (int x = 0; x < Width; ++x)
    {
      const int i = 3 * (y * Width + x);
      const bool same = a[i] == b[i] && a[i + 1] == b[i + 1] && a[i + 2] == b[i + 2];
      if (x < x0 || x >= x0 + w || y < y0 || y >= y0 + h)
      {
        changedOutside += !same;
      }
      else
      {
        changedInside += !same;
      }
    }
  }
  std::printf("window pixels changed by SSGI: %d inside the viewport, %d outside\n", changedInside,
    changedOutside);
  MRGI_TEST_CHECK(changedOutside == 0);
  MRGI_TEST_CHECK(changedInside > 0);
  s.Window->RemoveRenderer(back);
}

// SSGI and the VPL gather are exclusive: with an indirect mode set, the
// gather runs without SSGI and not with it.
void TestExclusive()
{
  Scene s;
  s.Pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  s.Window->Render();
  MRGI_TEST_CHECK(s.Pass->GetIndirectComputed());
  s.Pass->SSGIOn();
  s.Window->Render();
  MRGI_TEST_CHECK(!s.Pass->GetIndirectComputed());
  vtkNew<vtkFloatArray> result;
  MRGI_TEST_CHECK(s.Pass->GetSSGIStage()->ReadResult(s.Window, result));
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestCornell), MRGI_TEST_CASE(TestViewport), MRGI_TEST_CASE(TestExclusive) });
}
