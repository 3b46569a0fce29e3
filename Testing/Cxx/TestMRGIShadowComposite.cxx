// Direct shadows applied to VTK's own light (vtkMRGIShadowComposite,
// mrgi_shadow_composite.h), through vtkMRGIPass:
// - Capture: the light terms captured from VTK's light loop are exactly
//   what each light adds. Removing the terms of the first two shader
//   lights (every factor 0, computed by the C twin on the read-back) gives
//   the image VTK draws with those two lights at intensity 0, for Phong
//   (solid colour, texture, scalars) and PBR actors, with a third light
//   that stays. Read with the wrong law (PBR terms as linear), the same
//   records miss that image by far: the check can fail.
// - Lit pixels are VTK's: where every factor is 1 the shadowed colour is
//   the unshadowed one bit for bit.
// - Parity: the frame's colour equals the C twin applied to the frame's
//   read-back unshadowed colour, terms and factors (1e-4 relative).
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkElevationFilter.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTexture.h"

#include "mrgi_shadow_composite.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
const float* Pixels(vtkImageData* image)
{
  return vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars())->GetPointer(0);
}

struct Buffers
{
  vtkNew<vtkImageData> Colour, Unshadowed, Factors;
  vtkNew<vtkImageData> Terms[MRGI_SHADOW_SLOTS];
};

void Read(vtkMRGIPass* pass, vtkRenderWindow* window, Buffers& b)
{
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, b.Colour));
  MRGI_TEST_CHECK(pass->GetUnshadowedBuffer(window, b.Unshadowed));
  MRGI_TEST_CHECK(pass->GetShadowFactorBuffer(window, b.Factors));
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    MRGI_TEST_CHECK(pass->GetLightTermBuffer(window, s, b.Terms[s]));
  }
}

vtkSmartPointer<vtkActor> AddActor(vtkRenderer* renderer, vtkAlgorithm* source, int kind)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  mapper->SetScalarVisibility(kind == 2);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  vtkProperty* p = actor->GetProperty();
  p->SetColor(0.8, 0.6, 0.4);
  p->SetAmbient(0.1);
  p->SetSpecular(0.4);
  p->SetSpecularPower(20);
  if (kind == 1)
  {
    // A checker texture (VTK multiplies its lit colour by it).
    vtkNew<vtkImageData> checker;
    checker->SetDimensions(8, 8, 1);
    checker->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
    for (int y = 0; y < 8; ++y)
    {
      for (int x = 0; x < 8; ++x)
      {
        unsigned char* t = static_cast<unsigned char*>(checker->GetScalarPointer(x, y, 0));
        t[0] = ((x + y) & 1) ? 255 : 60;
        t[1] = ((x + y) & 1) ? 200 : 90;
        t[2] = 120;
      }
    }
    vtkNew<vtkTexture> texture;
    texture->SetInputData(checker);
    actor->SetTexture(texture);
  }
  if (kind == 3)
  {
    p->SetInterpolationToPBR();
    p->SetMetallic(0.3);
    p->SetRoughness(0.4);
  }
  renderer->AddActor(actor);
  return actor;
}

vtkSmartPointer<vtkLight> AddLight(vtkRenderer* renderer, const double position[3], double cone,
  bool positional, double intensity)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->SetPosition(position[0], position[1], position[2]);
  light->SetFocalPoint(0, 0, 0);
  light->SetPositional(positional);
  light->SetConeAngle(cone);
  light->SetIntensity(intensity);
  renderer->AddLight(light);
  return light;
}

// Phong, textured, scalar-coloured and PBR actors under two shadow slots'
// lights and a third light.
void Capture()
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(200, 150);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  renderer->AutomaticLightCreationOff();
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-2, -1, -2);
  plane->SetPoint1(2, -1, -2);
  plane->SetPoint2(-2, -1, 2);
  plane->SetResolution(8, 8);
  vtkNew<vtkElevationFilter> elevation;
  elevation->SetInputConnection(plane->GetOutputPort());
  elevation->SetLowPoint(-2, 0, 0);
  elevation->SetHighPoint(2, 0, 0);
  AddActor(renderer, elevation, 2);
  const double centres[3][3] = { { -1.1, -0.3, 0 }, { 0, -0.3, 0.3 }, { 1.1, -0.3, 0 } };
  std::vector<vtkSmartPointer<vtkSphereSource>> spheres;
  for (int k = 0; k < 3; ++k)
  {
    auto sphere = vtkSmartPointer<vtkSphereSource>::New();
    sphere->SetCenter(centres[k][0], centres[k][1], centres[k][2]);
    sphere->SetRadius(0.5);
    sphere->SetThetaResolution(32);
    sphere->SetPhiResolution(24);
    spheres.push_back(sphere);
    AddActor(renderer, sphere, k == 0 ? 0 : k == 1 ? 1 : 3);
  }
  const double spot[3] = { 1, 4, 2 }, point[3] = { -3, 3, 1 }, third[3] = { 0, 2, 4 };
  vtkSmartPointer<vtkLight> l0 = AddLight(renderer, spot, 40, true, 0.8);
  vtkSmartPointer<vtkLight> l1 = AddLight(renderer, point, 180, true, 0.6);
  AddLight(renderer, third, 180, false, 0.3);
  renderer->GetActiveCamera()->SetPosition(0, 2.5, 6);
  renderer->GetActiveCamera()->SetFocalPoint(0, -0.5, 0);
  renderer->ResetCameraClippingRange();

  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> pass;
  pass->SetDelegatePass(steps);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  pass->SetDirectShadowsToSoft();
  renderer->SetPass(pass);
  window->Render();
  Buffers lit;
  Read(pass, window, lit);

  // VTK's image without the first two lights' light.
  l0->SetIntensity(0);
  l1->SetIntensity(0);
  pass->SetDirectShadowsToOff();
  window->Render();
  vtkNew<vtkImageData> dark;
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, dark));

  const int w = 200, h = 150;
  const float* u = Pixels(lit.Unshadowed);
  const float* c = Pixels(lit.Colour);
  const float* f = Pixels(lit.Factors);
  const float* d = Pixels(dark);
  const float* t[MRGI_SHADOW_SLOTS];
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    t[s] = Pixels(lit.Terms[s]);
  }
  double maxLinear = 0, maxGamma = 0, wrongLaw = 0;
  size_t gammaPixels = 0, termPixels = 0, litPixels = 0;
  for (size_t i = 0; i < static_cast<size_t>(w) * h; ++i)
  {
    float terms[4 * MRGI_SHADOW_SLOTS];
    bool gamma = false, any = false;
    for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
    {
      for (int k = 0; k < 4; ++k)
      {
        terms[4 * s + k] = t[s][4 * i + k];
      }
      for (int k = 0; k < 3; ++k)
      {
        gamma = gamma || terms[4 * s + k] < 0;
        any = any || terms[4 * s + k] != 0;
      }
    }
    const float none[MRGI_SHADOW_SLOTS] = { 0 };
    float out[4];
    mrgi_shadow_composite_pixel(u + 4 * i, terms, none, out);
    double err = 0;
    for (int k = 0; k < 3; ++k)
    {
      err = std::max(err, static_cast<double>(std::fabs(out[k] - d[4 * i + k])));
    }
    (gamma ? maxGamma : maxLinear) = std::max(gamma ? maxGamma : maxLinear, err);
    gammaPixels += gamma;
    termPixels += any;
    if (gamma)
    {
      // The same records read as linear terms.
      for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
      {
        for (int k = 0; k < 3; ++k)
        {
          terms[4 * s + k] = std::fabs(terms[4 * s + k]) + 0.0f;
        }
      }
      float linearOut[4];
      const float u4[4] = { u[4 * i], u[4 * i + 1], u[4 * i + 2], u[4 * i + 3] };
      // Linear law by hand: colour minus terms.
      for (int k = 0; k < 3; ++k)
      {
        float removed = 0;
        for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
        {
          removed += terms[4 * s + k];
        }
        linearOut[k] = std::max(u4[k] - removed, 0.0f);
        wrongLaw = std::max(wrongLaw, static_cast<double>(std::fabs(linearOut[k] - d[4 * i + k])));
      }
    }
    // Lit everywhere: VTK's colour bit for bit.
    bool allLit = true;
    for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
    {
      allLit = allLit && f[4 * i + s] == 1.0f;
    }
    if (allLit)
    {
      ++litPixels;
      for (int k = 0; k < 4; ++k)
      {
        MRGI_TEST_CHECK(c[4 * i + k] == u[4 * i + k]);
      }
    }
  }
  std::printf("pixels with terms %zu (PBR %zu), lit %zu; max |twin(f=0) - VTK without the two "
              "lights|: Phong %.2e, PBR %.2e; PBR terms read as linear: %.3f\n",
    termPixels, gammaPixels, litPixels, maxLinear, maxGamma, wrongLaw);
  MRGI_TEST_CHECK(termPixels > static_cast<size_t>(w * h / 4));
  MRGI_TEST_CHECK(gammaPixels > 500);
  // Float terms: VTK's sum and the twin's difference round differently.
  MRGI_TEST_CHECK(maxLinear < 1e-5);
  // PBR: through the display gamma and back (pow(pow(x, 2.2), 1/2.2)).
  MRGI_TEST_CHECK(maxGamma < 1e-4);
  MRGI_TEST_CHECK(wrongLaw > 0.05);
}

// The frame's colour is the twin applied to the frame's own inputs.
void Parity()
{
  mrgitest::PassScene scene(160, 160, "cornell-spot");
  vtkRenderWindow* window = scene.Window;
  vtkMRGIPass* pass = scene.Pass;
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  for (int mode : { vtkMRGIPass::DirectShadowsHard, vtkMRGIPass::DirectShadowsSoft })
  {
    pass->SetDirectShadows(mode);
    window->Render();
    Buffers b;
    Read(pass, window, b);
    const size_t n = static_cast<size_t>(160) * 160;
    std::vector<float> twin(4 * n);
    const float* terms[MRGI_SHADOW_SLOTS];
    for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
    {
      terms[s] = Pixels(b.Terms[s]);
    }
    mrgi_error err;
    MRGI_TEST_CHECK(mrgi_shadow_composite(
                      Pixels(b.Unshadowed), terms, Pixels(b.Factors), n, twin.data(), &err) == MRGI_OK);
    const float* gpu = Pixels(b.Colour);
    double worst = 0;
    size_t shadowed = 0;
    for (size_t i = 0; i < n; ++i)
    {
      shadowed += Pixels(b.Factors)[4 * i] < 1.0f;
      for (int k = 0; k < 4; ++k)
      {
        const double e = std::fabs(gpu[4 * i + k] - twin[4 * i + k]) /
          std::max(1e-2, static_cast<double>(std::fabs(twin[4 * i + k])));
        worst = std::max(worst, e);
      }
    }
    std::printf("mode %d: %zu pixels with a factor below 1; max relative difference GPU vs twin %.2e\n",
      mode, shadowed, worst);
    MRGI_TEST_CHECK(worst < 1e-4);
  }
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv, { MRGI_TEST_CASE(Capture), MRGI_TEST_CASE(Parity) });
}
