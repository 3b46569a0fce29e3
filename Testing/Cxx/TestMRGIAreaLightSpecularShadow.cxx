// Shadows on the Phong highlights of an area light (nichols-penmatsa-wyman-2010
// 3.3.3), in a scene: a glossy black floor (Specular 1: its area-light
// buffer is the highlight alone) under a square light, and a slab halfway
// a quarter of the way from the floor to the light that hides the light
// from the left half of the highlight (floor x < 0, with a penumbra
// |x| < 0.083 for this light; the camera sees the floor past the slab). Two materials: glossy
// (SpecularPower 50, 256 light samples: the sample sum, shadowed per sample)
// and sharp (SpecularPower 100, 4 samples: the 5 x 5 lobe grid, shadowed by
// the variance shadow query).
//
// Over the highlight's pixels (the unshadowed highlight above 10% of its
// peak) left of the umbra's edge (x < -0.15) and right of the penumbra
// (x > 0.15), each visibility mode against AreaLightVisibility Off:
// - Off: the highlight is not darkened, left as bright as right (the scene
//   is symmetric but for the slab): if it were, the comparison below could
//   not tell a shadow from a dim highlight;
// - Naive and Incremental: left is dark (< 10% of Off), right is unchanged
//   (within 3%, never brighter).
// Which specular path each region's pixels take is checked with the C twin
// (mrgi_area_light_specular_classify()) on the captured G-buffer.
#include "mrgiTestUtilities.h"
#include "mrgiVoxelTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIVarianceShadowQuery.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"

#include "mrgi_area_light.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
const int W = 200, H = 150;
// Region bounds on the floor (world x): a floor point x sees light point
// lx past the slab's edge (x = 0, a quarter of the way up) when
// 0.75 x + 0.25 lx > 0: the umbra ends at -0.083 and the penumbra at
// +0.083 for the light's half size 0.25; 0.05 of margin at the slab (2
// voxels).
const double Edge = 0.15;

struct Regions
{
  double Left = 0, Right = 0; // mean highlight (luminance-free: R + G + B)
  int LeftPixels = 0, RightPixels = 0;
  int Paths[2][5] = { { 0 } };  // [left/right][MRGI_AREA_LIGHT_SPECULAR_*]
};

std::vector<double> SpecularImage(vtkMRGIPass* pass, vtkRenderWindow* window)
{
  vtkNew<vtkImageData> image;
  MRGI_TEST_CHECK(pass->GetAreaLightBuffer(window, image));
  vtkDataArray* a = image->GetPointData()->GetScalars();
  std::vector<double> sum(static_cast<size_t>(a->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    sum[static_cast<size_t>(i)] = a->GetComponent(i, 0) + a->GetComponent(i, 1) + a->GetComponent(i, 2);
    MRGI_TEST_CHECK(std::isfinite(sum[static_cast<size_t>(i)]) && sum[static_cast<size_t>(i)] >= 0.0);
  }
  return sum;
}

// The highlight's pixels on the floor, by region; `mask` the pixels' region
// (-1 left, 1 right, 0 neither), computed from the unshadowed image.
Regions Measure(const std::vector<double>& image, const std::vector<int>& mask)
{
  Regions r;
  for (size_t i = 0; i < image.size(); ++i)
  {
    if (mask[i] < 0)
    {
      r.Left += image[i];
      ++r.LeftPixels;
    }
    else if (mask[i] > 0)
    {
      r.Right += image[i];
      ++r.RightPixels;
    }
  }
  r.Left /= std::max(r.LeftPixels, 1);
  r.Right /= std::max(r.RightPixels, 1);
  return r;
}

struct Material
{
  const char* Name;
  double Power;
  int Samples;
  int Path; // the path most of the highlight takes
};

bool RunMaterial(const Material& m)
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(W, H);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  // Glossy black floor (y = 0), grey slab at y = 0.5 over x in [-2, 0].
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-3, 0, -2);
  plane->SetPoint1(3, 0, -2);
  plane->SetPoint2(-3, 0, 4);
  vtkSmartPointer<vtkActor> floor = mrgitest::MakeActor(plane);
  floor->GetProperty()->SetColor(0, 0, 0);
  floor->GetProperty()->SetSpecular(1.0);
  floor->GetProperty()->SetSpecularColor(1, 1, 1);
  floor->GetProperty()->SetSpecularPower(m.Power);
  renderer->AddActor(floor);
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(-2.0, 0.0, 0.45, 0.55, 1.0, 1.8);
  vtkSmartPointer<vtkActor> slab = mrgitest::MakeActor(cube);
  slab->GetProperty()->SetColor(0.5, 0.5, 0.5);
  renderer->AddActor(slab);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 3.5, 5);
  camera->SetFocalPoint(0, 0.5, 1);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(40);
  renderer->ResetCameraClippingRange();

  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> pass;
  pass->SetDelegatePass(steps);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  renderer->SetPass(pass);
  vtkNew<vtkMRGIAreaLight> light;
  light->SetCenter(0, 2, 0);
  light->SetEdgeU(0.5, 0, 0);
  light->SetEdgeV(0, 0, 0.5); // u x v = -y: faces the floor
  light->SetIntensity(4.0);
  light->SetNumberOfSamples(m.Samples);
  pass->AddAreaLight(light);

  // Visibility off: the unshadowed highlight, and the regions.
  pass->SetAreaLightVisibility(vtkMRGIPass::VisibilityOff);
  window->Render();
  const std::vector<double> off = SpecularImage(pass, window);
  vtkNew<vtkImageData> gP, gN, gA, gK, gE;
  MRGI_TEST_CHECK(pass->GetGBuffer(window, gP, gN, gA));
  MRGI_TEST_CHECK(pass->GetSpecularGBuffer(window, gK, gE));
  vtkDataArray* P = gP->GetPointData()->GetScalars();
  vtkDataArray* N = gN->GetPointData()->GetScalars();
  vtkDataArray* E = gE->GetPointData()->GetScalars();
  const double* v2w = pass->GetLastViewToWorld();
  float mv[16];
  std::copy(v2w, v2w + 16, mv);
  int count = 0;
  const mrgi_area_light_sample* samples = light->GetCoreSamples(&count);
  mrgi_area_light_uniforms uniforms;
  MRGI_TEST_CHECK(samples && light->GetCoreUniforms(&uniforms));
  const double peak = *std::max_element(off.begin(), off.end());
  MRGI_TEST_CHECK(peak > 0.0);
  std::vector<int> mask(off.size(), 0);
  Regions paths;
  for (vtkIdType i = 0; i < P->GetNumberOfTuples(); ++i)
  {
    if (P->GetComponent(i, 3) < 0.5 || off[static_cast<size_t>(i)] < 0.1 * peak)
    {
      continue;
    }
    // World position, normal and view as the shaders compute them.
    float p[3], n[3], v[3];
    for (int r = 0; r < 3; ++r)
    {
      p[r] = mv[12 + r];
      n[r] = v[r] = 0.0f;
      for (int k = 0; k < 3; ++k)
      {
        p[r] += mv[4 * k + r] * static_cast<float>(P->GetComponent(i, k));
        n[r] += mv[4 * k + r] * static_cast<float>(N->GetComponent(i, k));
        v[r] -= mv[4 * k + r] * static_cast<float>(P->GetComponent(i, k));
      }
    }
    if (std::fabs(p[1]) > 1e-3)
    {
      continue; // not the floor
    }
    const int side = p[0] < -Edge ? -1 : (p[0] > Edge ? 1 : 0);
    if (side != 0)
    {
      // Measured where the highlight takes the material's path (the glossy
      // lobe's tails, where its half-maximum cone barely meets the light,
      // fall back to the lobe grid).
      mrgi_area_light_specular_info info;
      mrgi_area_light_specular_classify(&uniforms, samples, count, p, n, v,
        static_cast<float>(E->GetComponent(i, 0)), &info);
      ++paths.Paths[side < 0 ? 0 : 1][info.path];
      mask[static_cast<size_t>(i)] = info.path == m.Path ? side : 0;
    }
  }
  const Regions o = Measure(off, mask);
  std::printf("%s (SpecularPower %g, %d samples): highlight pixels left %d on the sample sum, %d on "
              "the lobe grid; right %d, %d; measured on the %s\n",
    m.Name, m.Power, count, paths.Paths[0][MRGI_AREA_LIGHT_SPECULAR_SAMPLES],
    paths.Paths[0][MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID], paths.Paths[1][MRGI_AREA_LIGHT_SPECULAR_SAMPLES],
    paths.Paths[1][MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID],
    m.Path == MRGI_AREA_LIGHT_SPECULAR_SAMPLES ? "sample sum" : "lobe grid");
  std::printf("  off:         left %.4g right %.4g (left / right %.3f)\n", o.Left, o.Right,
    o.Left / o.Right);
  bool ok = true;
  auto check = [&ok](bool condition, const char* what) {
    if (!condition)
    {
      std::printf("  FAILED: %s\n", what);
      ok = false;
    }
  };
  check(o.LeftPixels >= 100 && o.RightPixels >= 100, "highlight pixels of the path on both sides");
  // Off: no darkening on the slab's side.
  check(o.Left > 0.7 * o.Right && o.Left < 1.4 * o.Right, "off: left as bright as right");

  const int modes[2] = { vtkMRGIPass::VisibilityNaive, vtkMRGIPass::VisibilityIncremental };
  const char* names[2] = { "naive", "incremental" };
  for (int k = 0; k < 2; ++k)
  {
    pass->SetAreaLightVisibility(modes[k]);
    window->Render();
    const Regions s = Measure(SpecularImage(pass, window), mask);
    std::printf("  %-12s left %.4g right %.4g: shadowed side %.2f%% of off, open side %.2f%% of off\n",
      names[k], s.Left, s.Right, 100.0 * s.Left / o.Left, 100.0 * s.Right / o.Right);
    check(s.Left < 0.1 * o.Left, "the slab's shadow darkens the highlight");
    check(s.Right > 0.97 * o.Right && s.Right <= (1.0 + 1e-4) * o.Right,
      "the open side is unchanged");
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  return ok;
}
}

int main(int argc, char* argv[])
{
  static const Material glossy = { "glossy", 50.0, 256, MRGI_AREA_LIGHT_SPECULAR_SAMPLES };
  static const Material sharp = { "sharp", 100.0, 4, MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID };
  return mrgitest::RunCases(argc, argv,
    { { "Glossy", [] { MRGI_TEST_CHECK(RunMaterial(glossy)); } },
      { "Sharp", [] { MRGI_TEST_CHECK(RunMaterial(sharp)); } } });
}
