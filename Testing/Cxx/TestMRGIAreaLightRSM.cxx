// Area lights bounce (mrgi_area_light_rsm.h): the reflective shadow maps of
// a vtkMRGIAreaLight, rendered by vtkMRGIReflectiveShadowMapPass under
// vtkMRGIPass.
// 1. Parity on random configurations (light pose, size, one/two-sided,
//    texture, floor and box albedos): every valid texel of the light's views
//    holds flux = albedo x X(p, n) x area, X from mrgi_area_light_rsm_texel()
//    (the C twin, the same 16 samples), relative RMS <= 2e-3.
// 2. Energy: a small light over a large floor; the sum of the views' flux
//    equals the power reaching the floor, L x A_light x F(light -> floor),
//    F by Hottel's parallel-rectangle view factor integrated over the light
//    (within 3 %; a missing side face loses about a third).
// 3. Views and cache: 5 faces one-sided, 6 two-sided; nothing re-rendered
//    while nothing changed; a changed light re-renders; AreaLightIndirect
//    off and IndirectMode off give the light no view; the bounce reaches
//    the image (the pass's indirect buffer is non-zero) with no vtkLight lit.
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMath.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"

#include "mrgi_area_light.h"
#include "mrgi_area_light_rsm.h"
#include "mrgi_vpl.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

namespace
{
struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderStepsPass> Steps;
  vtkNew<vtkMRGIPass> Pass;
  vtkNew<vtkMRGIAreaLight> Light;
  vtkNew<vtkActor> Floor;
  vtkNew<vtkActor> Box;

  // A floor of half-size `half` at y = 0; optionally a box on it. Lit by the
  // area light only (a switched-on vtkLight of intensity 0 keeps VTK's
  // lighting on, as the scene builder does).
  Scene(double half, bool box)
  {
    this->Window = mrgitest::HeadlessWindow(64, 64);
    this->Window->AddRenderer(this->Renderer);
    vtkNew<vtkPlaneSource> plane;
    plane->SetOrigin(-half, 0, -half);
    plane->SetPoint1(half, 0, -half);
    plane->SetPoint2(-half, 0, half);
    vtkNew<vtkPolyDataMapper> floorMapper;
    floorMapper->SetInputConnection(plane->GetOutputPort());
    this->Floor->SetMapper(floorMapper);
    this->Floor->GetProperty()->SetDiffuse(1.0);
    this->Floor->GetProperty()->SetAmbient(0.0);
    this->Renderer->AddActor(this->Floor);
    if (box)
    {
      vtkNew<vtkCubeSource> cube;
      cube->SetBounds(0.2 * half, 0.5 * half, 0.0, 0.3 * half, -0.4 * half, -0.1 * half);
      vtkNew<vtkPolyDataMapper> boxMapper;
      boxMapper->SetInputConnection(cube->GetOutputPort());
      this->Box->SetMapper(boxMapper);
      this->Box->GetProperty()->SetDiffuse(1.0);
      this->Box->GetProperty()->SetAmbient(0.0);
      this->Renderer->AddActor(this->Box);
    }
    vtkNew<vtkLight> dark;
    dark->SetLightTypeToSceneLight();
    dark->SetIntensity(0.0);
    this->Renderer->AddLight(dark);
    this->Renderer->AutomaticLightCreationOff();
    this->Renderer->GetActiveCamera()->SetPosition(0, 3.0 * half, 0.5 * half);
    this->Renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
    this->Renderer->ResetCameraClippingRange();
    this->Pass->SetDelegatePass(this->Steps);
    this->Pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
    this->Pass->SetAreaLightVisibility(vtkMRGIPass::VisibilityOff);
    this->Pass->AddAreaLight(this->Light);
    this->Renderer->SetPass(this->Pass);
  }

  vtkMRGIReflectiveShadowMapPass* RSM() { return this->Pass->GetReflectiveShadowMapPass(); }

  // Views of area light 0.
  std::vector<int> AreaViews()
  {
    std::vector<int> views;
    for (int i = 0; i < this->RSM()->GetNumberOfViews(); ++i)
    {
      if (this->RSM()->GetViewLight(i) == -2)
      {
        views.push_back(i);
      }
    }
    return views;
  }
};

// The samples the RSM pass lights its texels with (mrgi_area_light_rsm.h).
int RSMSamples(vtkMRGIAreaLight* light, mrgi_area_light_uniforms* uniforms,
  mrgi_area_light_sample samples[MRGI_AREA_LIGHT_RSM_SAMPLES])
{
  mrgi_area_light core;
  const mrgi_area_light_texture_pyramid* pyramid = nullptr;
  MRGI_TEST_CHECK(light->GetCoreLight(&core) && light->GetCorePyramid(&pyramid));
  MRGI_TEST_CHECK(light->GetCoreUniforms(uniforms));
  int32_t count = 0;
  MRGI_TEST_CHECK(mrgi_area_light_make_samples(&core, pyramid, MRGI_AREA_LIGHT_RSM_SAMPLES, 0, 0,
                    samples, MRGI_AREA_LIGHT_RSM_SAMPLES, &count, nullptr) == MRGI_OK);
  return count;
}

void TestParity()
{
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(20261202);
  auto next = [&](double lo, double hi) {
    random->Next();
    return random->GetRangeValue(lo, hi);
  };
  for (int config = 0; config < 6; ++config)
  {
    Scene scene(2.0, true);
    const double floorAlbedo[3] = { next(0.2, 1.0), next(0.2, 1.0), next(0.2, 1.0) };
    const double boxAlbedo[3] = { next(0.2, 1.0), next(0.2, 1.0), next(0.2, 1.0) };
    scene.Floor->GetProperty()->SetColor(floorAlbedo[0], floorAlbedo[1], floorAlbedo[2]);
    scene.Box->GetProperty()->SetColor(boxAlbedo[0], boxAlbedo[1], boxAlbedo[2]);
    // A light above the floor, tilted up to 40 degrees from facing down.
    const double tilt = vtkMath::RadiansFromDegrees(next(0.0, 40.0));
    const double spin = next(0.0, 2.0 * vtkMath::Pi());
    const double n[3] = { std::sin(tilt) * std::cos(spin), -std::cos(tilt),
      std::sin(tilt) * std::sin(spin) };
    double u[3], v[3];
    vtkMath::Perpendiculars(n, u, v, next(0.0, 2.0 * vtkMath::Pi()));
    // EdgeU x EdgeV must be n: Perpendiculars gives n, u, v right-handed.
    const double su = next(0.05, 0.6), sv = next(0.05, 0.6);
    scene.Light->SetCenter(next(-0.4, 0.4), next(0.6, 1.2), next(-0.4, 0.4));
    scene.Light->SetEdgeU(su * u[0], su * u[1], su * u[2]);
    scene.Light->SetEdgeV(sv * v[0], sv * v[1], sv * v[2]);
    scene.Light->SetColor(next(0.3, 1.0), next(0.3, 1.0), next(0.3, 1.0));
    scene.Light->SetIntensity(next(0.5, 4.0));
    const bool twoSided = config % 3 == 2;
    scene.Light->SetTwoSided(twoSided);
    vtkNew<vtkImageData> picture;
    if (config % 2 == 1)
    {
      picture->SetDimensions(8, 4, 1);
      picture->AllocateScalars(VTK_FLOAT, 3);
      auto* p = static_cast<float*>(picture->GetScalarPointer());
      for (int i = 0; i < 8 * 4 * 3; ++i)
      {
        p[i] = static_cast<float>(next(0.0, 2.0));
      }
      scene.Light->SetTextureData(picture);
    }
    scene.Pass->SetRSMResolution(64 + 32 * config);
    scene.Window->Render();

    mrgi_area_light_uniforms uniforms;
    mrgi_area_light_sample samples[MRGI_AREA_LIGHT_RSM_SAMPLES];
    const int count = RSMSamples(scene.Light, &uniforms, samples);
    MRGI_TEST_CHECK(count == MRGI_AREA_LIGHT_RSM_SAMPLES || (count >= 8 && count <= 16));
    const std::vector<int> views = scene.AreaViews();
    // The faces that reach the props (a side face sees the floor beyond 45
    // degrees from the light's plane); never a one-sided light's back face.
    MRGI_TEST_CHECK(views.size() >= 3u && views.size() <= (twoSided ? 6u : 5u));
    double num = 0.0, den = 0.0, total = 0.0;
    long texels = 0;
    for (int view : views)
    {
      vtkNew<vtkImageData> P, N, F;
      MRGI_TEST_CHECK(scene.RSM()->ReadView(scene.Window, view, P, N, F));
      vtkDataArray* pa = P->GetPointData()->GetScalars();
      vtkDataArray* na = N->GetPointData()->GetScalars();
      vtkDataArray* fa = F->GetPointData()->GetScalars();
      for (vtkIdType i = 0; i < pa->GetNumberOfTuples(); ++i)
      {
        if (!(pa->GetComponent(i, 3) > MRGI_VALID_THRESHOLD))
        {
          continue;
        }
        const float p[3] = { static_cast<float>(pa->GetComponent(i, 0)),
          static_cast<float>(pa->GetComponent(i, 1)), static_cast<float>(pa->GetComponent(i, 2)) };
        const float nn[3] = { static_cast<float>(na->GetComponent(i, 0)),
          static_cast<float>(na->GetComponent(i, 1)), static_cast<float>(na->GetComponent(i, 2)) };
        const bool onFloor = std::fabs(p[1]) < 1e-4f;
        const double* a = onFloor ? floorAlbedo : boxAlbedo;
        const float albedo[3] = { static_cast<float>(a[0]), static_cast<float>(a[1]),
          static_cast<float>(a[2]) };
        const float area = static_cast<float>(fa->GetComponent(i, 3));
        MRGI_TEST_CHECK(std::isfinite(area) && area > 0.0f);
        float expected[3];
        mrgi_area_light_rsm_texel(&uniforms, samples, count, p, nn, albedo, area, expected);
        for (int k = 0; k < 3; ++k)
        {
          const double got = fa->GetComponent(i, k);
          MRGI_TEST_CHECK(std::isfinite(got) && got >= 0.0);
          num += (got - expected[k]) * (got - expected[k]);
          den += static_cast<double>(expected[k]) * expected[k];
          total += got;
        }
        ++texels;
      }
    }
    const double error = std::sqrt(num / (den > 0 ? den : 1.0));
    std::printf("config %d (%s, %s, RSM %d): %zu views, %ld valid texels, total flux %.4g, "
                "relative RMS against the C twin %.2e\n",
      config, twoSided ? "two-sided" : "one-sided", config % 2 ? "textured" : "untextured",
      64 + 32 * config, views.size(), texels, total, error);
    MRGI_TEST_CHECK(texels > 1000 && den > 0.0 && error <= 2e-3);
    scene.Pass->ReleaseGraphicsResources(scene.Window);
  }
}

// Hottel's view factor from a differential area to a parallel rectangle
// whose corner lies on its normal (Howell's catalogue, B-3), and any
// parallel rectangle [x0, x1] x [z0, z1] by signed corner sums.
double CornerFactor(double a, double b, double h)
{
  const double A = a / h, B = b / h;
  const double sa = std::sqrt(1.0 + A * A), sb = std::sqrt(1.0 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0 * vtkMath::Pi());
}

double RectFactor(double x0, double x1, double z0, double z1, double h)
{
  const double xs[2] = { x0, x1 }, zs[2] = { z0, z1 };
  double f = 0.0;
  for (int i = 0; i < 2; ++i)
  {
    for (int j = 0; j < 2; ++j)
    {
      const double sign =
        ((i == j) ? 1.0 : -1.0) * (xs[i] < 0 ? -1.0 : 1.0) * (zs[j] < 0 ? -1.0 : 1.0);
      f += sign * CornerFactor(std::fabs(xs[i]), std::fabs(zs[j]), h);
    }
  }
  return f;
}

void TestEnergy()
{
  // A 0.2 x 0.2 light of radiance 1 at height 1 facing down over a white
  // floor of half-size 4: power onto the floor (VTK flux units) =
  // L int_light F(y -> floor) dA_y.
  const double half = 4.0, h = 1.0, side = 0.2;
  Scene scene(half, false);
  scene.Floor->GetProperty()->SetColor(1.0, 1.0, 1.0);
  scene.Light->SetCenter(0.0, h, 0.0);
  // Facing down: u x v must be -y.
  scene.Light->SetEdgeU(side, 0.0, 0.0);
  scene.Light->SetEdgeV(0.0, 0.0, side); // (s,0,0) x (0,0,s) = (0, -s^2, 0)
  scene.Light->SetColor(1.0, 1.0, 1.0);
  scene.Light->SetIntensity(1.0);
  scene.Pass->SetRSMResolution(512);
  scene.Window->Render();
  const std::vector<int> views = scene.AreaViews();
  MRGI_TEST_CHECK(views.size() == 5u);
  double sum = 0.0;
  std::vector<double> perView;
  for (int view : views)
  {
    vtkNew<vtkImageData> P, N, F;
    MRGI_TEST_CHECK(scene.RSM()->ReadView(scene.Window, view, P, N, F));
    vtkDataArray* pa = P->GetPointData()->GetScalars();
    vtkDataArray* fa = F->GetPointData()->GetScalars();
    double s = 0.0;
    for (vtkIdType i = 0; i < pa->GetNumberOfTuples(); ++i)
    {
      if (pa->GetComponent(i, 3) > MRGI_VALID_THRESHOLD)
      {
        s += fa->GetComponent(i, 1);
      }
    }
    perView.push_back(s);
    sum += s;
  }
  const int cells = 40;
  double expected = 0.0;
  for (int j = 0; j < cells; ++j)
  {
    for (int i = 0; i < cells; ++i)
    {
      const double x = side * ((i + 0.5) / cells - 0.5), z = side * ((j + 0.5) / cells - 0.5);
      expected += RectFactor(-half - x, half - x, -half - z, half - z, h);
    }
  }
  expected *= side * side / (cells * cells);
  std::ostringstream faces;
  for (double s : perView)
  {
    faces << ' ' << s;
  }
  std::printf("energy: RSM flux %.6f (faces:%s), analytic power onto the floor %.6f, ratio %.4f\n",
    sum, faces.str().c_str(), expected, sum / expected);
  MRGI_TEST_CHECK(std::fabs(sum / expected - 1.0) <= 0.03);
  scene.Pass->ReleaseGraphicsResources(scene.Window);
}

void TestViewsAndCache()
{
  Scene scene(3.0, true);
  // A ceiling above the light, for a two-sided light's back face to see.
  vtkNew<vtkPlaneSource> ceilingPlane;
  ceilingPlane->SetOrigin(-3, 2, -3);
  ceilingPlane->SetPoint1(3, 2, -3);
  ceilingPlane->SetPoint2(-3, 2, 3);
  vtkNew<vtkPolyDataMapper> ceilingMapper;
  ceilingMapper->SetInputConnection(ceilingPlane->GetOutputPort());
  vtkNew<vtkActor> ceiling;
  ceiling->SetMapper(ceilingMapper);
  scene.Renderer->AddActor(ceiling);
  // Under the ceiling, looking at the box and the floor.
  scene.Renderer->GetActiveCamera()->SetPosition(-1.0, 1.5, 2.8);
  scene.Renderer->GetActiveCamera()->SetFocalPoint(0.8, 0.2, -0.8);
  scene.Renderer->ResetCameraClippingRange();
  scene.Light->SetCenter(0.0, 1.0, 0.0);
  scene.Light->SetEdgeU(0.4, 0.0, 0.0);
  scene.Light->SetEdgeV(0.0, 0.0, 0.3);
  scene.Light->SetColor(1.0, 0.8, 0.6);
  scene.Light->SetIntensity(2.0);
  scene.Pass->SetRSMResolution(64);
  MRGI_TEST_CHECK(scene.Pass->GetAreaLightIndirect()); // the default
  scene.Window->Render();
  std::printf("%zu area views of %d\n", scene.AreaViews().size(), scene.RSM()->GetNumberOfViews());
  MRGI_TEST_CHECK(scene.AreaViews().size() == 5u && scene.RSM()->GetNumberOfViews() == 5);
  MRGI_TEST_CHECK(scene.Pass->GetIndirectComputed());
  const vtkIdType renders = scene.RSM()->GetNumberOfRenders();
  scene.Window->Render();
  MRGI_TEST_CHECK(scene.RSM()->GetNumberOfRenders() == renders); // nothing changed
  // The bounce reaches the image: the indirect buffer holds light.
  vtkNew<vtkImageData> indirect;
  MRGI_TEST_CHECK(scene.Pass->GetIndirectBuffer(scene.Window, indirect));
  double total = 0.0;
  vtkDataArray* ia = indirect->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < ia->GetNumberOfValues(); ++i)
  {
    const double value = ia->GetVariantValue(i).ToDouble();
    MRGI_TEST_CHECK(std::isfinite(value));
    total += value;
  }
  std::printf("indirect buffer sum %.4g with the area light's bounce only\n", total);
  MRGI_TEST_CHECK(total > 0.0);

  scene.Light->SetIntensity(3.0);
  scene.Window->Render();
  MRGI_TEST_CHECK(scene.RSM()->GetNumberOfRenders() == renders + 5);
  scene.Light->SetTwoSided(true); // the back face, looking up at the ceiling
  scene.Window->Render();
  MRGI_TEST_CHECK(scene.AreaViews().size() == 6u);

  scene.Pass->AreaLightIndirectOff();
  scene.Window->Render();
  MRGI_TEST_CHECK(scene.AreaViews().empty() && !scene.Pass->GetIndirectComputed());
  scene.Pass->AreaLightIndirectOn();
  scene.Pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  scene.Window->Render();
  MRGI_TEST_CHECK(!scene.Pass->GetIndirectComputed());
  std::ostringstream os;
  scene.Pass->PrintSelf(os, vtkIndent());
  MRGI_TEST_CHECK(os.str().find("AreaLightIndirect: On") != std::string::npos);
  scene.Pass->ReleaseGraphicsResources(scene.Window);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestParity), MRGI_TEST_CASE(TestEnergy),
      MRGI_TEST_CASE(TestViewsAndCache) });
}
