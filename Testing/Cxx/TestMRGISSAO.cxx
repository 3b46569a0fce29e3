// GPU / C parity of MRGI's SSAO stage (vtkMRGISSAO against mrgi_ssao):
//
// 1. AO: a Cornell render (200 x 150: not square, not a multiple of the
//    64-texel noise tile) through vtkMRGIPass with SSAO on; the read-back
//    G-buffer, the window's noise tile and the camera's projection fed to
//    mrgi_ssao_compute() give the GPU's AO within 1e-4 (AO is in [0, 1]),
//    wherever no decision of the receiver lies within rounding of its
//    threshold (mrgi_ssao.h, "decision margin"); those must be rare;
// 2. apply: the colour with SSAO equals the colour without, times AO (and
//    times vtkSSAOPass's 3x3 Gaussian of AO with Blur);
// 3. levels 1 and 2 (a level texel evaluates its block's centre pixel)
//    against the twin's levels;
// 4. bad input: every argument out of range is refused, nothing drawn.
// The measured errors are printed for the documentation.
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISSAO.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "mrgi_ssao.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
const int Width = 200;
const int Height = 150;
const int KernelSize = 32;
const double Radius = 30.0; // the Cornell box is 556 units wide
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
    this->Pass->SetSSAOKernelSize(KernelSize);
    this->Pass->SetSSAORadius(Radius);
    this->Pass->SetSSAOBias(Bias);
    this->Renderer->SetPass(this->Pass);
  }
  ~Scene()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }

  // The twin's inputs from the last frame: G-buffer, noise, projection.
  void TwinInputs(mrgi_image& position, mrgi_image& normal, std::vector<float>& noise,
    std::vector<float>& kernel, mrgi_ssao_params& params)
  {
    vtkNew<vtkImageData> p, n, a;
    MRGI_TEST_CHECK(this->Pass->GetGBuffer(this->Window, p, n, a));
    int w = 0, h = 0, x0 = 0, y0 = 0;
    this->Renderer->GetTiledSizeAndOrigin(&w, &h, &x0, &y0);
    MRGI_TEST_CHECK(p->GetDimensions()[0] == w && p->GetDimensions()[1] == h);
    MRGI_TEST_CHECK(mrgi_image_create(&position, w, h, 4, nullptr) == MRGI_OK);
    MRGI_TEST_CHECK(mrgi_image_create(&normal, w, h, 4, nullptr) == MRGI_OK);
    std::copy(Floats(p), Floats(p) + 4 * w * h, position.pixels);
    std::copy(Floats(n), Floats(n) + 4 * w * h, normal.pixels);
    vtkOpenGLRenderWindow* gl = vtkOpenGLRenderWindow::SafeDownCast(this->Window);
    MRGI_TEST_CHECK(vtkMRGISSAO::ReadNoise(gl, noise));
    MRGI_TEST_CHECK(noise.size() == MRGI_SSAO_NOISE_SIZE * MRGI_SSAO_NOISE_SIZE);
    const auto range = std::minmax_element(noise.begin(), noise.end());
    std::printf(
      "window noise tile: %zu values in [%.4f, %.4f]\n", noise.size(), *range.first, *range.second);
    kernel.resize(3 * KernelSize);
    MRGI_TEST_CHECK(mrgi_ssao_kernel(KernelSize, kernel.data(), nullptr) == MRGI_OK);
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
};

// Compare GPU AO (w x h floats, rows bottom-up) with the twin's (AO, margin).
void CompareAO(const char* what, const float* gpu, const mrgi_image& twin, double minFraction)
{
  const int n = twin.width * twin.height;
  int compared = 0, occluded = 0, nearTie = 0, differing = 0;
  double worst = 0.0;
  for (int i = 0; i < n; ++i)
  {
    const float ao = twin.pixels[2 * i];
    const float margin = twin.pixels[2 * i + 1];
    MRGI_TEST_CHECK(std::isfinite(gpu[i]) && gpu[i] >= 0.0f && gpu[i] <= 1.0f);
    occluded += ao < 0.99f;
    if (std::fabs(gpu[i] - ao) > 1e-4f)
    {
      ++differing;
    }
    if (margin < 1e-5f)
    {
      ++nearTie;
      continue;
    }
    ++compared;
    worst = std::max(worst, static_cast<double>(std::fabs(gpu[i] - ao)));
  }
  std::printf("%s: %d texels, %d compared, %d within rounding of a decision, %d occluded (AO < "
              "0.99), max |GPU - C| = %.3g there; %d texels differ by more than 1e-4\n",
    what, n, compared, nearTie, occluded, worst, differing);
  MRGI_TEST_CHECK(worst <= 1e-4);
  MRGI_TEST_CHECK(compared >= minFraction * n);
  MRGI_TEST_CHECK(occluded >= n / 50);   // the corners and blocks do occlude
  MRGI_TEST_CHECK(occluded < 4 * n / 5); // not everything
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

void TestCornellAO()
{
  Scene s;
  s.Pass->SSAOOn();
  s.Window->Render();
  vtkNew<vtkFloatArray> ao;
  MRGI_TEST_CHECK(s.Pass->GetSSAOStage()->ReadAO(s.Window, ao));
  MRGI_TEST_CHECK(ao->GetNumberOfTuples() == Width * Height);

  mrgi_image position, normal, twin;
  std::vector<float> noise, kernel;
  mrgi_ssao_params params = {};
  s.TwinInputs(position, normal, noise, kernel, params);
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_ssao_compute(&params, &position, &normal, 0, &twin, &err) == MRGI_OK);
  CompareAO("level 0", ao->GetPointer(0), twin, 0.9);
  mrgi_image_destroy(&twin);

  // Levels 1 and 2 through ComputeAO() on the same G-buffer.
  vtkOpenGLRenderWindow* gl = vtkOpenGLRenderWindow::SafeDownCast(s.Window);
  vtkNew<vtkTextureObject> target;
  target->SetContext(gl);
  target->SetInternalFormat(GL_RGBA32F);
  target->SetFormat(GL_RGBA);
  target->SetDataType(GL_FLOAT);
  MRGI_TEST_CHECK(target->Allocate2D(Width, Height, 4, VTK_FLOAT));
  vtkMRGIFrameContext frame;
  frame.Window = gl;
  frame.Renderer = s.Renderer;
  frame.Position = s.Pass->GetPositionTexture();
  frame.Normal = s.Pass->GetNormalTexture();
  frame.Viewport[2] = Width;
  frame.Viewport[3] = Height;
  for (int level = 1; level <= 2; ++level)
  {
    gl->MakeCurrent();
    MRGI_TEST_CHECK(
      s.Pass->GetSSAOStage()->ComputeAO(frame, KernelSize, Radius, Bias, level, target));
    std::vector<float> rgba;
    MRGI_TEST_CHECK(ReadTexture(target, rgba));
    MRGI_TEST_CHECK(
      mrgi_ssao_compute(&params, &position, &normal, level, &twin, nullptr) == MRGI_OK);
    std::vector<float> gpu(static_cast<size_t>(twin.width) * twin.height);
    for (int y = 0; y < twin.height; ++y)
    {
      for (int x = 0; x < twin.width; ++x)
      {
        gpu[static_cast<size_t>(y) * twin.width + x] =
          rgba[4 * (static_cast<size_t>(y) * Width + x)];
      }
    }
    char what[32];
    std::snprintf(what, sizeof(what), "level %d", level);
    CompareAO(what, gpu.data(), twin, 0.9);
    mrgi_image_destroy(&twin);
  }

  // Bad input: refused, with the frame untouched.
  vtkNew<vtkTextureObject> small;
  small->SetContext(gl);
  small->SetInternalFormat(GL_RGBA32F);
  small->SetFormat(GL_RGBA);
  small->SetDataType(GL_FLOAT);
  MRGI_TEST_CHECK(small->Allocate2D(16, 16, 4, VTK_FLOAT));
  vtkMRGISSAO* stage = s.Pass->GetSSAOStage();
  std::printf("expected errors follow:\n");
  MRGI_TEST_CHECK(!stage->ComputeAO(frame, 0, Radius, Bias, 0, target));
  MRGI_TEST_CHECK(!stage->ComputeAO(frame, 1001, Radius, Bias, 0, target));
  MRGI_TEST_CHECK(!stage->ComputeAO(frame, KernelSize, std::nan(""), Bias, 0, target));
  MRGI_TEST_CHECK(!stage->ComputeAO(frame, KernelSize, 0.0, Bias, 0, target));
  MRGI_TEST_CHECK(!stage->ComputeAO(frame, KernelSize, 1e300, Bias, 0, target));
  MRGI_TEST_CHECK(!stage->ComputeAO(frame, KernelSize, Radius, INFINITY, 0, target));
  MRGI_TEST_CHECK(
    !stage->ComputeAO(frame, KernelSize, Radius, Bias, MRGI_SSAO_MAX_LEVEL + 1, target));
  MRGI_TEST_CHECK(!stage->ComputeAO(frame, KernelSize, Radius, Bias, 0, nullptr));
  MRGI_TEST_CHECK(!stage->ComputeAO(frame, KernelSize, Radius, Bias, 0, small));
  MRGI_TEST_CHECK(stage->ComputeAO(frame, KernelSize, Radius, Bias, 4, small)); // 13 x 10 fits
  vtkMRGIFrameContext empty;
  MRGI_TEST_CHECK(!stage->ComputeAO(empty, KernelSize, Radius, Bias, 0, target));
  MRGI_TEST_CHECK(!stage->Apply(empty, target, false, target));
  target->ReleaseGraphicsResources(gl);
  small->ReleaseGraphicsResources(gl);
  mrgi_image_destroy(&position);
  mrgi_image_destroy(&normal);
}

// A renderer in part of the window (a second one, without MRGI, behind
// it), FXAA on: the AO of the viewport still equals the twin's on the
// viewport's G-buffer, the colour with SSAO is the colour without times
// AO, and the window outside the viewport is untouched.
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
  s.Pass->SSAOOn();
  s.Window->Render();
  vtkSmartPointer<vtkImageData> shaded = mrgitest::GrabRGB(s.Window);
  vtkNew<vtkImageData> colour;
  MRGI_TEST_CHECK(s.Pass->GetColorBuffer(s.Window, colour));
  int w = 0, h = 0, x0 = 0, y0 = 0;
  s.Renderer->GetTiledSizeAndOrigin(&w, &h, &x0, &y0);
  MRGI_TEST_CHECK(x0 > 0 && y0 > 0 && w < Width && h < Height);
  vtkNew<vtkFloatArray> ao;
  MRGI_TEST_CHECK(s.Pass->GetSSAOStage()->ReadAO(s.Window, ao));
  MRGI_TEST_CHECK(ao->GetNumberOfTuples() == w * h);

  mrgi_image position, normal, twin;
  std::vector<float> noise, kernel;
  mrgi_ssao_params params = {};
  s.TwinInputs(position, normal, noise, kernel, params);
  MRGI_TEST_CHECK(mrgi_ssao_compute(&params, &position, &normal, 0, &twin, nullptr) == MRGI_OK);
  CompareAO("viewport", ao->GetPointer(0), twin, 0.9);
  mrgi_image_destroy(&twin);
  mrgi_image_destroy(&position);
  mrgi_image_destroy(&normal);

  double worst = 0.0;
  const float* d = Floats(direct);
  const float* c = Floats(colour);
  for (int i = 0; i < w * h; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double expected = static_cast<double>(d[4 * i + k]) * ao->GetValue(i);
      worst =
        std::max(worst, std::fabs(c[4 * i + k] - expected) / std::max(1e-3, std::fabs(expected)));
    }
  }
  std::printf("viewport %d x %d at (%d, %d): max relative |colour - direct x AO| = %.3g\n", w, h,
    x0, y0, worst);
  MRGI_TEST_CHECK(worst <= 1e-5);
  // Outside the viewport the window shows the other renderer, as before.
  const unsigned char* a = static_cast<unsigned char*>(plain->GetScalarPointer());
  const unsigned char* b = static_cast<unsigned char*>(shaded->GetScalarPointer());
  int outside = 0, changedOutside = 0, changedInside = 0;
  for (int y = 0; y < Height; ++y)
  {
    for (int x = 0; x < Width; ++x)
    {
      const int i = 3 * (y * Width + x);
      const bool same = a[i] == b[i] && a[i + 1] == b[i + 1] && a[i + 2] == b[i + 2];
      if (x < x0 || x >= x0 + w || y < y0 || y >= y0 + h)
      {
        ++outside;
        changedOutside += !same;
      }
      else
      {
        changedInside += !same;
      }
    }
  }
  std::printf("window pixels changed by SSAO: %d inside the viewport, %d of %d outside\n",
    changedInside, changedOutside, outside);
  MRGI_TEST_CHECK(changedOutside == 0);
  MRGI_TEST_CHECK(changedInside > w * h / 20);
  s.Window->RemoveRenderer(back);
}

// A PBR sphere resting on a Phong plane, a translucent box, depth peeling:
// the PBR sphere is in the G-buffer, it occludes the plane around its
// contact, and the AO still equals the twin's.
void TestComposition()
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(Width, Height);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  window->SetAlphaBitPlanes(1);
  renderer->UseDepthPeelingOn();
  renderer->SetMaximumNumberOfPeels(4);
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-100, 0, -100);
  plane->SetPoint1(100, 0, -100);
  plane->SetPoint2(-100, 0, 100);
  vtkNew<vtkPolyDataMapper> planeMapper;
  planeMapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> planeActor;
  planeActor->SetMapper(planeMapper);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0, 20, 0);
  sphere->SetRadius(20);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> sphereActor;
  sphereActor->SetMapper(sphereMapper);
  sphereActor->GetProperty()->SetInterpolationToPBR();
  sphereActor->GetProperty()->SetMetallic(0.0);
  sphereActor->GetProperty()->SetRoughness(0.5);
  vtkNew<vtkCubeSource> cube;
  cube->SetCenter(50, 15, 30);
  cube->SetXLength(20);
  cube->SetYLength(30);
  cube->SetZLength(20);
  vtkNew<vtkPolyDataMapper> cubeMapper;
  cubeMapper->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkActor> cubeActor;
  cubeActor->SetMapper(cubeMapper);
  cubeActor->GetProperty()->SetOpacity(0.4);
  renderer->AddActor(planeActor);
  renderer->AddActor(sphereActor);
  renderer->AddActor(cubeActor);
  renderer->GetActiveCamera()->SetPosition(0, 70, 110);
  renderer->GetActiveCamera()->SetFocalPoint(0, 15, 0);
  renderer->ResetCameraClippingRange();
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> pass;
  pass->SetDelegatePass(steps);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  pass->SSAOOn();
  pass->SetSSAOKernelSize(KernelSize);
  pass->SetSSAORadius(6.0);
  pass->SetSSAOBias(0.05);
  renderer->SetPass(pass);
  window->Render();

  vtkNew<vtkImageData> p, n, a;
  MRGI_TEST_CHECK(pass->GetGBuffer(window, p, n, a));
  const float* centre = Floats(p) + 4 * ((Height / 2) * Width + Width / 2);
  MRGI_TEST_CHECK(centre[3] > 0.5f); // the PBR sphere is captured
  vtkNew<vtkFloatArray> ao;
  MRGI_TEST_CHECK(pass->GetSSAOStage()->ReadAO(window, ao));
  float minimum = 1.0f;
  for (vtkIdType i = 0; i < ao->GetNumberOfTuples(); ++i)
  {
    minimum = std::min(minimum, ao->GetValue(i));
  }
  std::printf("PBR sphere on a plane: minimum AO %.3f\n", minimum);
  MRGI_TEST_CHECK(minimum < 0.8f);

  mrgi_image position, normal, twin;
  MRGI_TEST_CHECK(mrgi_image_create(&position, Width, Height, 4, nullptr) == MRGI_OK);
  MRGI_TEST_CHECK(mrgi_image_create(&normal, Width, Height, 4, nullptr) == MRGI_OK);
  std::copy(Floats(p), Floats(p) + 4 * Width * Height, position.pixels);
  std::copy(Floats(n), Floats(n) + 4 * Width * Height, normal.pixels);
  std::vector<float> noise, kernel(3 * KernelSize);
  MRGI_TEST_CHECK(vtkMRGISSAO::ReadNoise(vtkOpenGLRenderWindow::SafeDownCast(window), noise));
  MRGI_TEST_CHECK(mrgi_ssao_kernel(KernelSize, kernel.data(), nullptr) == MRGI_OK);
  mrgi_ssao_params params = {};
  params.kernel = kernel.data();
  params.kernel_size = KernelSize;
  params.radius = 6.0f;
  params.bias = 0.05f;
  params.noise = noise.data();
  vtkMatrix4x4* m = renderer->GetActiveCamera()->GetProjectionTransformMatrix(
    renderer->GetTiledAspectRatio(), -1, 1);
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      params.projection[c * 4 + r] = static_cast<float>(m->GetElement(r, c));
    }
  }
  MRGI_TEST_CHECK(mrgi_ssao_compute(&params, &position, &normal, 0, &twin, nullptr) == MRGI_OK);
  CompareAO("PBR sphere, translucent box, depth peeling", ao->GetPointer(0), twin, 0.9);
  mrgi_image_destroy(&twin);
  mrgi_image_destroy(&position);
  mrgi_image_destroy(&normal);
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
}

// The colour with SSAO is the colour without, times AO (blurred with Blur).
void TestApply()
{
  Scene s;
  s.Window->Render();
  vtkNew<vtkImageData> direct;
  MRGI_TEST_CHECK(s.Pass->GetColorBuffer(s.Window, direct));
  for (int blur = 0; blur <= 1; ++blur)
  {
    s.Pass->SSAOOn();
    s.Pass->SetSSAOBlur(blur != 0);
    s.Window->Render();
    vtkNew<vtkImageData> shaded;
    MRGI_TEST_CHECK(s.Pass->GetColorBuffer(s.Window, shaded));
    vtkNew<vtkFloatArray> ao;
    MRGI_TEST_CHECK(s.Pass->GetSSAOStage()->ReadAO(s.Window, ao));
    const float* a = ao->GetPointer(0);
    const float* d = Floats(direct);
    const float* c = Floats(shaded);
    auto at = [&](int x, int y) {
      x = std::min(std::max(x, 0), Width - 1);
      y = std::min(std::max(y, 0), Height - 1);
      return a[y * Width + x];
    };
    double worst = 0.0, darkened = 0.0;
    for (int y = 0; y < Height; ++y)
    {
      for (int x = 0; x < Width; ++x)
      {
        float f = at(x, y);
        if (blur)
        {
          // vtkSSAOPass's weights and order; taps clamped to the viewport.
          f = 0.195346f * f;
          f += 0.077847f * at(x - 1, y - 1);
          f += 0.077847f * at(x - 1, y + 1);
          f += 0.077847f * at(x + 1, y - 1);
          f += 0.077847f * at(x + 1, y + 1);
          f += 0.123317f * at(x - 1, y);
          f += 0.123317f * at(x + 1, y);
          f += 0.123317f * at(x, y - 1);
          f += 0.123317f * at(x, y + 1);
        }
        const int i = 4 * (y * Width + x);
        for (int k = 0; k < 3; ++k)
        {
          const double expected = static_cast<double>(d[i + k]) * f;
          worst =
            std::max(worst, std::fabs(c[i + k] - expected) / std::max(1e-3, std::fabs(expected)));
          darkened += d[i + k] - c[i + k];
        }
        MRGI_TEST_CHECK(c[i + 3] == d[i + 3]); // alpha kept
      }
    }
    std::printf(
      "apply (blur %s): max relative |colour - direct x AO| = %.3g, total darkening %.1f\n",
      blur ? "on" : "off", worst, darkened);
    MRGI_TEST_CHECK(worst <= 1e-5);
    MRGI_TEST_CHECK(darkened > 1.0);
  }
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestCornellAO), MRGI_TEST_CASE(TestApply), MRGI_TEST_CASE(TestViewport),
      MRGI_TEST_CASE(TestComposition) });
}
