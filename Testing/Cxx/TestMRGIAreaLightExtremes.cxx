// Area lights at the extremes: the scene and the light scaled together by
// 1e-4 .. 1e5 give the same area-light image (an area light's irradiance is
// scale-invariant, and so are the voxel visibility's bias and slices, which
// are in voxel units), with and without voxel shadows; light intensity 0 and
// 1e30; a light seen edge-on, one behind the camera, one cutting through the
// floor, one in the floor's plane; 1x1 and 1x1-voxel buffers. Every image is
// finite and non-negative.
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIVoxelization.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
vtkSmartPointer<vtkActor> AddBox(vtkRenderer* r, double cx, double cy, double cz, double sx, double sy,
  double sz)
{
  vtkNew<vtkCubeSource> cube;
  cube->SetCenter(cx, cy, cz);
  cube->SetXLength(sx);
  cube->SetYLength(sy);
  cube->SetZLength(sz);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(cube->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.8, 0.7, 0.6);
  actor->GetProperty()->SetAmbient(0.0);
  actor->GetProperty()->SetDiffuse(1.0);
  r->AddActor(actor);
  return actor;
}

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderStepsPass> Steps;
  vtkNew<vtkMRGIPass> Pass;
  vtkNew<vtkMRGIAreaLight> Light;
  std::vector<vtkSmartPointer<vtkActor>> Actors;

  Scene(int width, int height)
  {
    this->Window = mrgitest::HeadlessWindow(width, height);
    this->Window->AddRenderer(this->Renderer);
    this->Pass->SetDelegatePass(this->Steps);
    this->Pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
    this->Renderer->SetPass(this->Pass);
    this->Actors.push_back(AddBox(this->Renderer, 0, -0.1, 0, 10, 0.2, 10)); // floor
    this->Actors.push_back(AddBox(this->Renderer, -1, 1, 0, 2, 2, 2));       // occluder
    this->Actors.push_back(AddBox(this->Renderer, 0, 3, -4.1, 10, 6, 0.2));  // back wall
    this->Light->SetNumberOfSamples(64);
    this->Light->SetIntensity(2.0);
    this->Pass->AddAreaLight(this->Light);
    this->Place(1.0);
  }
  ~Scene()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  // Scene, light and camera scaled by s about the origin.
  void Place(double s)
  {
    vtkNew<vtkMatrix4x4> m;
    m->Identity();
    for (int k = 0; k < 3; ++k)
    {
      m->SetElement(k, k, s);
    }
    for (auto& actor : this->Actors)
    {
      actor->SetUserMatrix(m);
    }
    this->Light->SetCenter(0.5 * s, 4.0 * s, 0.5 * s);
    this->Light->SetEdgeU(2.0 * s, 0, 0);
    this->Light->SetEdgeV(0, 0, 1.5 * s); // u x v = (0, -3 s^2, 0): facing the floor
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetPosition(0, 5 * s, 14 * s);
    camera->SetFocalPoint(0, 1 * s, 0);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(40);
    this->Renderer->ResetCameraClippingRange();
  }
  vtkSmartPointer<vtkImageData> Render(const char* what)
  {
    this->Window->Render();
    auto image = vtkSmartPointer<vtkImageData>::New();
    if (!this->Pass->GetAreaLightsComputed())
    {
      std::printf("  %s: no area light drawn\n", what);
      return nullptr;
    }
    MRGI_TEST_CHECK(this->Pass->GetAreaLightBuffer(this->Window, image));
    vtkDataArray* a = image->GetPointData()->GetScalars();
    for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
    {
      const double v = a->GetVariantValue(i).ToDouble();
      if (!std::isfinite(v) || v < 0.0)
      {
        std::printf("  %s: value %g at %lld\n", what, v, static_cast<long long>(i));
      }
      MRGI_TEST_CHECK(std::isfinite(v) && v >= 0.0);
    }
    vtkNew<vtkImageData> color;
    MRGI_TEST_CHECK(this->Pass->GetColorBuffer(this->Window, color));
    vtkDataArray* c = color->GetPointData()->GetScalars();
    for (vtkIdType i = 0; i < c->GetNumberOfValues(); ++i)
    {
      MRGI_TEST_CHECK(std::isfinite(c->GetVariantValue(i).ToDouble()));
    }
    return image;
  }
};

double Sum(vtkImageData* image)
{
  vtkDataArray* a = image->GetPointData()->GetScalars();
  double sum = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    sum += a->GetVariantValue(i).ToDouble();
  }
  return sum;
}

double RelativeRMS(vtkImageData* a, vtkImageData* b)
{
  vtkDataArray* x = a->GetPointData()->GetScalars();
  vtkDataArray* y = b->GetPointData()->GetScalars();
  double num = 0, den = 0;
  for (vtkIdType i = 0; i < x->GetNumberOfValues(); ++i)
  {
    const double u = x->GetVariantValue(i).ToDouble(), v = y->GetVariantValue(i).ToDouble();
    num += (u - v) * (u - v);
    den += v * v;
  }
  return std::sqrt(num / (den > 0 ? den : 1));
}
}

int main()
{
  Scene scene(97, 61);
  double n[3];
  vtkMath::Cross(scene.Light->GetEdgeU(), scene.Light->GetEdgeV(), n);
  MRGI_TEST_CHECK(n[1] < 0);

  double unshadowed = 0;
  for (const int visibility : { vtkMRGIPass::VisibilityOff, vtkMRGIPass::VisibilityNaive })
  {
    scene.Pass->SetAreaLightVisibility(visibility);
    scene.Place(1.0);
    vtkSmartPointer<vtkImageData> reference = scene.Render("scale 1");
    MRGI_TEST_CHECK(reference && Sum(reference) > 0);
    if (visibility == vtkMRGIPass::VisibilityOff)
    {
      unshadowed = Sum(reference);
    }
    else
    {
      // The occluder casts a shadow on the floor: the scales compare shadows too.
      std::printf("shadows keep %.1f%% of the light\n", 100 * Sum(reference) / unshadowed);
      MRGI_TEST_CHECK(Sum(reference) < 0.97 * unshadowed);
    }
    for (const double s : { 1e-4, 1e-2, 1e3, 1e5 })
    {
      scene.Place(s);
      char what[64];
      std::snprintf(what, sizeof(what), "scale %g", s);
      vtkSmartPointer<vtkImageData> image = scene.Render(what);
      MRGI_TEST_CHECK(image);
      const double error = RelativeRMS(image, reference);
      std::printf("visibility %s, scale %-6g: relative RMS against scale 1: %.3g\n",
        visibility ? "naive" : "off", s, error);
      MRGI_TEST_CHECK(error < 1e-4);
    }
  }
  scene.Place(1.0);
  scene.Pass->SetAreaLightVisibility(vtkMRGIPass::VisibilityNaive);
  vtkSmartPointer<vtkImageData> base = scene.Render("base");
  const double baseSum = Sum(base);

  // Intensity 0: black; 1e30: scaled, finite (float holds 1e30 x X).
  scene.Light->SetIntensity(0.0);
  vtkSmartPointer<vtkImageData> dark = scene.Render("intensity 0");
  MRGI_TEST_CHECK(!dark || Sum(dark) == 0.0);
  scene.Light->SetIntensity(2e30);
  vtkSmartPointer<vtkImageData> bright = scene.Render("intensity 2e30");
  MRGI_TEST_CHECK(bright);
  std::printf("intensity 2e30: sum ratio to intensity 2: %.6g\n", Sum(bright) / baseSum);
  MRGI_TEST_CHECK(std::fabs(Sum(bright) / baseSum / 1e30 - 1.0) < 1e-3);
  scene.Light->SetIntensity(2.0);

  // Geometry cases: finite, non-negative images (checked in Render()).
  struct Place
  {
    const char* What;
    double Center[3], U[3], V[3];
  };
  const Place places[] = {
    { "edge-on to the camera", { 0, 2, 3 }, { 2, 0, 0 }, { 0, 1e-3, 0 } },
    { "behind the camera", { 0, 5, 20 }, { 2, 0, 0 }, { 0, 0, 1.5 } },
    { "through the floor", { 2, 0, 1 }, { 0, 2, 0 }, { 0, 0, 2 } },
    { "in the floor's plane", { 2, 0.0, 1 }, { 2, 0, 0 }, { 0, 0, 2 } },
    { "on the occluder's face", { -1, 2.0, 0 }, { 1, 0, 0 }, { 0, 0, -1 } },
    { "tiny (1e-6)", { 0.5, 4, 0.5 }, { 1e-6, 0, 0 }, { 0, 0, 1e-6 } },
    { "huge (1e6)", { 0.5, 40, 0.5 }, { 1e6, 0, 0 }, { 0, 0, 1e6 } },
  };
  for (const Place& p : places)
  {
    scene.Light->SetCenter(const_cast<double*>(p.Center));
    scene.Light->SetEdgeU(const_cast<double*>(p.U));
    scene.Light->SetEdgeV(const_cast<double*>(p.V));
    scene.Render(p.What);
    std::printf("%s: finite\n", p.What);
  }

  // 1x1 voxel buffer and a 1x1 window.
  scene.Place(1.0);
  scene.Pass->GetVoxelization()->SetVoxelSide(1);
  MRGI_TEST_CHECK(scene.Render("1x1 voxels"));
  scene.Pass->GetVoxelization()->SetVoxelSide(128);
  scene.Window->SetSize(1, 1);
  scene.Render("1x1 window");
  std::printf("1x1 voxels and 1x1 window: finite\n");
  return 0;
}
