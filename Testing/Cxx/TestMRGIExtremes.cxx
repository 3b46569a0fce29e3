// Numerical extremes of MRGI's one-bounce indirect light. Every case asserts
// that the colour, indirect and irradiance buffers hold no NaN or Inf, and a
// bounded, expected result:
//
// - scale: the same scene at 1e-4 .. 1e5 units (geometry, camera and lights
//   scaled) gives the same colour and indirect images (VTK lights do not
//   attenuate, and E is scale-free: flux ~ s^2, r^2 ~ s^2, A ~ s^2);
// - contact: a box standing on a lit floor (VPLs at r -> 0 from receivers):
//   E <= sum_j Phi_j / A_j (each VPL adds at most its radiance) and the C twin agrees;
// - back faces: a wall lit from behind gives exactly zero indirect light on
//   the other side (the same wall lit from the front gives some); a light
//   grazing the floor exactly and nearly (area clamp) stays finite and bounded;
// - degenerate input: zero-area and collinear triangles, NaN and Inf point
//   coordinates, NaN and zero point normals never poison the buffers;
// - a point light inside a closed box (camera inside and outside) and on a
//   surface: finite, bounded, equal to the C twin;
// - light intensity 1e-6 .. 1e6: indirect and colour scale linearly (ratio
//   within 1e-3), no overflow;
// - windows of 1 x 1, 1 x 61 and 97 x 1 with indirect light: right sizes,
//   finite, equal to the C twin;
// - zero VPLs, lights off, a light that reaches nothing: no indirect light
//   computed and the image equals IndirectMode Off bit for bit.
// The 4096 x 4096 window is TestMRGIExtremesLarge (label "extremes").
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCubeSource.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkPlaneSource.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include "mrgi_gather.h"
#include "mrgi_vpl.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <limits>
#include <vector>

namespace
{
float* Floats(vtkImageData* image)
{
  return vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars())->GetPointer(0);
}

size_t ValueCount(vtkImageData* image)
{
  return static_cast<size_t>(image->GetPointData()->GetScalars()->GetNumberOfValues());
}

// What one frame left in the pass's buffers.
struct Frame
{
  int Width = 0, Height = 0;
  bool Indirect = false;
  vtkNew<vtkImageData> Color, IndirectImage, Irradiance, Position, Normal, Albedo;
  std::vector<mrgi_vpl> VPLs;
};

// Render one frame with `pass` and read everything back; every buffer must be
// finite and of the viewport's size.
void RenderFrame(vtkRenderWindow* window, vtkMRGIPass* pass, Frame& frame, const char* what)
{
  window->Render();
  frame.Width = pass->GetBufferSize()[0];
  frame.Height = pass->GetBufferSize()[1];
  const int* size = window->GetSize();
  MRGI_TEST_CHECK(frame.Width == size[0] && frame.Height == size[1]);
  frame.Indirect = pass->GetIndirectComputed();
  std::vector<vtkImageData*> images = { frame.Color };
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, frame.Color));
  frame.VPLs.clear();
  if (frame.Indirect)
  {
    MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, frame.IndirectImage));
    MRGI_TEST_CHECK(pass->GetIrradianceBuffer(window, frame.Irradiance));
    MRGI_TEST_CHECK(pass->GetGBuffer(window, frame.Position, frame.Normal, frame.Albedo));
    images.insert(images.end(), { frame.IndirectImage, frame.Irradiance });
    vtkNew<vtkFloatArray> vpls;
    MRGI_TEST_CHECK(pass->GetVPLs(window, vpls));
    frame.VPLs.resize(static_cast<size_t>(vpls->GetNumberOfTuples()));
    std::memcpy(frame.VPLs.data(), vpls->GetPointer(0), sizeof(mrgi_vpl) * frame.VPLs.size());
  }
  bool failed = false;
  if (frame.Indirect)
  {
    // The G-buffer is the input as VTK shaded it (NaN normals in the data
    // stay NaN there); the gather must cope with it. Sizes checked, values reported.
    for (vtkImageData* image : { frame.Position.Get(), frame.Normal.Get(), frame.Albedo.Get() })
    {
      int dims[3];
      image->GetDimensions(dims);
      MRGI_TEST_CHECK(dims[0] == frame.Width && dims[1] == frame.Height);
      size_t bad = 0;
      const float* v = Floats(image);
      for (size_t i = 0; i < ValueCount(image); ++i)
      {
        bad += !std::isfinite(v[i]);
      }
      if (bad)
      {
        std::printf("  %s: note: %zu non-finite values in the G-buffer's %s (input data)\n", what, bad,
          image->GetPointData()->GetScalars()->GetName());
      }
    }
  }
  for (vtkImageData* image : images)
  {
    int dims[3];
    image->GetDimensions(dims);
    MRGI_TEST_CHECK(dims[0] == frame.Width && dims[1] == frame.Height);
    size_t bad = 0;
    const float* v = Floats(image);
    for (size_t i = 0; i < ValueCount(image); ++i)
    {
      bad += !std::isfinite(v[i]);
    }
    if (bad)
    {
      std::fprintf(stderr, "%s: %zu non-finite values in the %s buffer\n", what, bad,
        image->GetPointData()->GetScalars()->GetName());
      failed = true;
    }
  }
  size_t badVPLs = 0;
  for (const mrgi_vpl& vpl : frame.VPLs)
  {
    const float* f = reinterpret_cast<const float*>(&vpl);
    bool bad = false;
    for (int k = 0; k < MRGI_VPL_FLOATS; ++k)
    {
      bad = bad || !std::isfinite(f[k]);
    }
    badVPLs += bad;
  }
  if (badVPLs)
  {
    std::fprintf(stderr, "%s: %zu of %zu VPLs hold non-finite values\n", what, badVPLs, frame.VPLs.size());
    failed = true;
  }
  if (failed)
  {
    MRGI_TEST_FAIL("%s: non-finite values", what);
  }
  for (const mrgi_vpl& vpl : frame.VPLs)
  {
    MRGI_TEST_CHECK(vpl.area >= 0 && vpl.flux[0] >= 0 && vpl.flux[1] >= 0 && vpl.flux[2] >= 0);
  }
}

double MaxValue(vtkImageData* image, int components = 3)
{
  const int n = image->GetNumberOfScalarComponents();
  const float* v = Floats(image);
  double m = 0;
  for (size_t i = 0; i < ValueCount(image); ++i)
  {
    if (static_cast<int>(i % n) < components)
    {
      m = std::max(m, static_cast<double>(v[i]));
    }
  }
  return m;
}

// sum_j Phi_j / A_j per channel: no receiver can gather more (mrgi_gather.h).
void RadianceBound(const std::vector<mrgi_vpl>& vpls, double bound[3], double* maxRadiance = nullptr)
{
  bound[0] = bound[1] = bound[2] = 0;
  double m = 0;
  for (const mrgi_vpl& vpl : vpls)
  {
    if (vpl.area > 0)
    {
      for (int c = 0; c < 3; ++c)
      {
        bound[c] += vpl.flux[c] / static_cast<double>(vpl.area);
        m = std::max(m, vpl.flux[c] / static_cast<double>(vpl.area));
      }
    }
  }
  if (maxRadiance)
  {
    *maxRadiance = m;
  }
}

// E of every pixel within the radiance bound; returns max E / max VPL radiance.
double CheckBounded(const Frame& frame, const char* what)
{
  double bound[3], maxRadiance = 0;
  RadianceBound(frame.VPLs, bound, &maxRadiance);
  const float* E = Floats(frame.Irradiance);
  const size_t pixels = static_cast<size_t>(frame.Width) * frame.Height;
  double maxE = 0;
  for (size_t p = 0; p < pixels; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      MRGI_TEST_CHECK(E[3 * p + c] >= 0);
      if (E[3 * p + c] > bound[c] * (1 + 1e-5))
      {
        MRGI_TEST_FAIL("%s: E %g above the bound sum Phi/A = %g", what, E[3 * p + c], bound[c]);
      }
      maxE = std::max(maxE, static_cast<double>(E[3 * p + c]));
    }
  }
  const double ratio = maxRadiance > 0 ? maxE / maxRadiance : 0;
  std::printf("  %s: max E %.4g, max VPL radiance Phi/A %.4g (ratio %.3g), bound sum Phi/A %.4g\n",
    what, maxE, maxRadiance, ratio, std::max({ bound[0], bound[1], bound[2] }));
  return ratio;
}

// The C twin on the frame's G-buffer and VPLs; returns the relative RMS error
// of the GPU irradiance over valid pixels.
double CompareWithC(vtkMRGIPass* pass, const Frame& frame, const char* what)
{
  if (frame.VPLs.empty())
  {
    return 0;
  }
  const double* m = pass->GetLastViewToWorld();
  float w2r[16];
  mrgitest::WorldToViewColumnMajor(m, w2r);
  mrgi_gather_receivers receivers = { frame.Width, frame.Height, Floats(frame.Position),
    Floats(frame.Normal) };
  mrgi_image c{};
  mrgi_gather_info info;
  mrgi_error err;
  if (mrgi_gather_full(&receivers, frame.VPLs.data(), static_cast<int32_t>(frame.VPLs.size()), w2r,
        &c, &info, &err) != MRGI_OK)
  {
    MRGI_TEST_FAIL("%s: mrgi_gather_full: %s", what, err.message);
  }
  const float* E = Floats(frame.Irradiance);
  const float* P = Floats(frame.Position);
  double num = 0, den = 0;
  for (size_t p = 0; p < static_cast<size_t>(frame.Width) * frame.Height; ++p)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double d = static_cast<double>(E[3 * p + k]) - c.pixels[3 * p + k];
      num += d * d;
      den += static_cast<double>(c.pixels[3 * p + k]) * c.pixels[3 * p + k];
      if (!(P[4 * p + 3] > MRGI_VALID_THRESHOLD))
      {
        MRGI_TEST_CHECK(E[3 * p + k] == 0.0f);
      }
    }
  }
  mrgi_image_destroy(&c);
  const double rms = den > 0 ? std::sqrt(num / den) : std::sqrt(num);
  std::printf("  %s: C twin relative RMS %.3g (%d VPLs used, %d malformed, %lld receivers malformed)\n",
    what, rms, info.vpls_used, info.vpls_malformed, static_cast<long long>(info.receivers_malformed));
  return rms;
}

// Relative RMS and max relative error (pixels above 1e-3 of the max) of a vs b * scale.
void CompareImages(vtkImageData* a, vtkImageData* b, double scaleB, int components, double& rms,
  double& maxRel, double& differing)
{
  const int n = a->GetNumberOfScalarComponents();
  MRGI_TEST_CHECK(n == b->GetNumberOfScalarComponents() && ValueCount(a) == ValueCount(b));
  const float* va = Floats(a);
  const float* vb = Floats(b);
  double maxB = 0;
  for (size_t i = 0; i < ValueCount(b); ++i)
  {
    maxB = std::max(maxB, std::fabs(vb[i] * scaleB));
  }
  double num = 0, den = 0;
  size_t diff = 0, count = 0;
  maxRel = 0;
  for (size_t i = 0; i < ValueCount(a); ++i)
  {
    if (static_cast<int>(i % n) >= components)
    {
      continue;
    }
    const double x = va[i], y = vb[i] * scaleB;
    num += (x - y) * (x - y);
    den += y * y;
    ++count;
    if (std::fabs(y) > 1e-3 * maxB)
    {
      maxRel = std::max(maxRel, std::fabs(x - y) / std::fabs(y));
    }
    diff += std::fabs(x - y) > 1e-2 * std::max(maxB, 1e-300);
  }
  rms = den > 0 ? std::sqrt(num / den) : std::sqrt(num);
  differing = count ? static_cast<double>(diff) / count : 0;
}

vtkSmartPointer<vtkActor> MakeActor(vtkAlgorithmOutput* port, double r, double g, double b)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(port);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(r, g, b);
  actor->GetProperty()->SetAmbient(0.0);
  actor->GetProperty()->SetSpecular(0.0);
  actor->GetProperty()->SetDiffuse(1.0);
  return actor;
}

vtkSmartPointer<vtkActor> AddBox(vtkRenderer* renderer, double cx, double cy, double cz, double lx,
  double ly, double lz, double r, double g, double b)
{
  vtkNew<vtkCubeSource> cube;
  cube->SetCenter(cx, cy, cz);
  cube->SetXLength(lx);
  cube->SetYLength(ly);
  cube->SetZLength(lz);
  cube->Update();
  vtkSmartPointer<vtkActor> actor = MakeActor(cube->GetOutputPort(), r, g, b);
  renderer->AddActor(actor);
  return actor;
}

vtkSmartPointer<vtkActor> AddPlane(vtkRenderer* renderer, const double origin[3], const double p1[3],
  const double p2[3], double r, double g, double b)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(origin[0], origin[1], origin[2]);
  plane->SetPoint1(p1[0], p1[1], p1[2]);
  plane->SetPoint2(p2[0], p2[1], p2[2]);
  plane->SetResolution(4, 4);
  plane->Update();
  vtkSmartPointer<vtkActor> actor = MakeActor(plane->GetOutputPort(), r, g, b);
  renderer->AddActor(actor);
  return actor;
}

vtkSmartPointer<vtkLight> AddLight(vtkRenderer* renderer, const double position[3], const double focal[3],
  bool positional, double cone, double intensity)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->SetPosition(position[0], position[1], position[2]);
  light->SetFocalPoint(focal[0], focal[1], focal[2]);
  light->SetPositional(positional);
  light->SetConeAngle(cone);
  light->SetIntensity(intensity);
  renderer->AddLight(light);
  return light;
}

// A window, a renderer without automatic lights, and an MRGI pass.
struct Setup
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderStepsPass> Steps;
  vtkNew<vtkMRGIPass> Pass;
  Setup(int width, int height)
  {
    this->Window = mrgitest::HeadlessWindow(width, height);
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->AutomaticLightCreationOff();
    this->Pass->SetDelegatePass(this->Steps);
    // These cases check the full gather against its C twin at the extremes.
    this->Pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
    this->Renderer->SetPass(this->Pass);
  }
  ~Setup()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  void Camera(const double position[3], const double focal[3], double viewAngle = 40)
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetPosition(position[0], position[1], position[2]);
    camera->SetFocalPoint(focal[0], focal[1], focal[2]);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(viewAngle);
    this->Renderer->ResetCameraClippingRange();
  }
};

// The reference scene: floor, back wall, box, sphere; spot, point and directional lights.
struct ReferenceScene
{
  std::vector<vtkSmartPointer<vtkActor>> Actors;
  std::vector<vtkSmartPointer<vtkLight>> Lights;
  std::vector<std::array<double, 6>> LightPlaces;
  std::vector<double> Intensities;
  double CameraPosition[3] = { 0, 5, 14 };
  double CameraFocal[3] = { 0, 1, 0 };

  void Build(Setup& setup)
  {
    vtkRenderer* r = setup.Renderer;
    this->Actors.push_back(AddBox(r, 0, -0.1, 0, 10, 0.2, 10, 0.8, 0.8, 0.8));
    this->Actors.push_back(AddBox(r, 0, 3, -4.1, 10, 6, 0.2, 0.9, 0.9, 0.9));
    this->Actors.push_back(AddBox(r, -1.5, 1, 0, 2, 2, 2, 0.9, 0.2, 0.2));
    vtkNew<vtkSphereSource> sphere;
    sphere->SetCenter(1.8, 1, 1);
    sphere->SetRadius(1);
    sphere->SetThetaResolution(24);
    sphere->SetPhiResolution(16);
    this->Actors.push_back(MakeActor(sphere->GetOutputPort(), 0.2, 0.8, 0.3));
    r->AddActor(this->Actors.back());
    const double places[3][6] = { { 4, 7, 5, 0, 0, 0 }, { -3, 4, 3, -3, 0, 3 }, { 1, 2, 1, 0, 0, 0 } };
    const bool positional[3] = { true, true, false };
    const double cones[3] = { 35, 90, 30 };
    const double intensities[3] = { 1.0, 0.6, 0.3 };
    for (int l = 0; l < 3; ++l)
    {
      this->Lights.push_back(AddLight(r, places[l], places[l] + 3, positional[l], cones[l], intensities[l]));
      this->LightPlaces.push_back({ places[l][0], places[l][1], places[l][2], places[l][3], places[l][4], places[l][5] });
      this->Intensities.push_back(intensities[l]);
    }
    this->Lights[0]->SetExponent(2);
    this->Lights[1]->SetColor(1.0, 0.9, 0.8);
    this->Lights[2]->SetColor(0.8, 0.9, 1.0);
    setup.Camera(this->CameraPosition, this->CameraFocal);
  }

  // The whole scene scaled by s about the origin.
  void Scale(Setup& setup, double s)
  {
    vtkNew<vtkMatrix4x4> m;
    m->Identity();
    m->SetElement(0, 0, s);
    m->SetElement(1, 1, s);
    m->SetElement(2, 2, s);
    for (auto& actor : this->Actors)
    {
      actor->SetUserMatrix(m);
    }
    for (size_t l = 0; l < this->Lights.size(); ++l)
    {
      const auto& p = this->LightPlaces[l];
      this->Lights[l]->SetPosition(s * p[0], s * p[1], s * p[2]);
      this->Lights[l]->SetFocalPoint(s * p[3], s * p[4], s * p[5]);
    }
    const double position[3] = { s * this->CameraPosition[0], s * this->CameraPosition[1],
      s * this->CameraPosition[2] };
    const double focal[3] = { s * this->CameraFocal[0], s * this->CameraFocal[1], s * this->CameraFocal[2] };
    setup.Camera(position, focal);
  }

  void SetIntensityFactor(double k)
  {
    for (size_t l = 0; l < this->Lights.size(); ++l)
    {
      this->Lights[l]->SetIntensity(k * this->Intensities[l]);
    }
  }
};

//------------------------------------------------------------------------------
void TestScale()
{
  std::printf("scene scale 1e-4 .. 1e5\n");
  Setup setup(97, 61);
  ReferenceScene scene;
  scene.Build(setup);
  setup.Pass->SetNumberOfVPLs(256);
  Frame reference;
  scene.Scale(setup, 1.0);
  RenderFrame(setup.Window, setup.Pass, reference, "scale 1");
  MRGI_TEST_CHECK(reference.Indirect && MaxValue(reference.IndirectImage) > 0);
  double totalFlux = 0;
  for (const mrgi_vpl& vpl : reference.VPLs)
  {
    totalFlux += vpl.flux[0] + vpl.flux[1] + vpl.flux[2];
  }
  for (double s : { 1e-4, 1e-3, 1e-2, 1e2, 1e3, 1e5 })
  {
    Frame frame;
    char what[64];
    std::snprintf(what, sizeof(what), "scale %g", s);
    scene.Scale(setup, s);
    RenderFrame(setup.Window, setup.Pass, frame, what);
    MRGI_TEST_CHECK(frame.Indirect);
    double flux = 0;
    for (const mrgi_vpl& vpl : frame.VPLs)
    {
      flux += vpl.flux[0] + vpl.flux[1] + vpl.flux[2];
    }
    double colorRMS, colorMax, colorDiff, indirectRMS, indirectMax, indirectDiff;
    CompareImages(frame.Color, reference.Color, 1.0, 3, colorRMS, colorMax, colorDiff);
    CompareImages(frame.IndirectImage, reference.IndirectImage, 1.0, 3, indirectRMS, indirectMax, indirectDiff);
    std::printf("  scale %-6g: colour relative RMS %.3g (%.2f%% values off by > 1%% of the max); "
                "indirect relative RMS %.3g (%.2f%%); VPL flux / s^2 vs scale 1: %.6f\n",
      s, colorRMS, 100 * colorDiff, indirectRMS, 100 * indirectDiff, flux / (s * s) / totalFlux);
    MRGI_TEST_CHECK(colorRMS < 1e-4 && indirectRMS < 1e-4);
    MRGI_TEST_CHECK(colorDiff < 1e-3 && indirectDiff < 1e-3);
    MRGI_TEST_CHECK(std::fabs(flux / (s * s) / totalFlux - 1) < 1e-4);
  }
}

//------------------------------------------------------------------------------
void TestContact()
{
  std::printf("a box standing on the lit floor (VPLs at r -> 0)\n");
  Setup setup(97, 61);
  vtkRenderer* r = setup.Renderer;
  AddBox(r, 0, -0.1, 0, 10, 0.2, 10, 0.9, 0.9, 0.9); // floor, top at y = 0
  AddBox(r, 0, 1, 0, 2, 2, 2, 0.9, 0.3, 0.2);        // standing on it
  const double light[3] = { 4, 6, 3 }, target[3] = { 1.2, 0, 1.2 };
  AddLight(r, light, target, true, 30, 1.0);
  const double eye[3] = { 3.5, 1.2, 4.5 }, focal[3] = { 0.8, 0.3, 1.0 };
  setup.Camera(eye, focal, 50);
  setup.Pass->SetNumberOfVPLs(4096);
  setup.Pass->SetRSMResolution(512);
  Frame frame;
  RenderFrame(setup.Window, setup.Pass, frame, "contact");
  MRGI_TEST_CHECK(frame.Indirect);

  // How close do receivers come to VPLs that light them (both cosines > 0)?
  const double* m = setup.Pass->GetLastViewToWorld();
  const float* P = Floats(frame.Position);
  const float* N = Floats(frame.Normal);
  double nearest = 1e300;
  for (size_t p = 0; p < static_cast<size_t>(frame.Width) * frame.Height; ++p)
  {
    if (!(P[4 * p + 3] > MRGI_VALID_THRESHOLD))
    {
      continue;
    }
    double w[3], n[3];
    for (int k = 0; k < 3; ++k)
    {
      w[k] = m[k] * P[4 * p] + m[4 + k] * P[4 * p + 1] + m[8 + k] * P[4 * p + 2] + m[12 + k];
      n[k] = m[k] * N[4 * p] + m[4 + k] * N[4 * p + 1] + m[8 + k] * N[4 * p + 2];
    }
    for (const mrgi_vpl& vpl : frame.VPLs)
    {
      if (vpl.area <= 0)
      {
        continue;
      }
      const double d[3] = { vpl.position[0] - w[0], vpl.position[1] - w[1], vpl.position[2] - w[2] };
      const double nd[3] = { vpl.normal[0], vpl.normal[1], vpl.normal[2] };
      if (vtkMath::Dot(n, d) > 0 && -vtkMath::Dot(nd, d) > 0)
      {
        nearest = std::min(nearest, vtkMath::Norm(d));
      }
    }
  }
  std::printf("  nearest lighting VPL to a receiver: %.3g (box side 2)\n", nearest);
  MRGI_TEST_CHECK(nearest < 0.05);
  CheckBounded(frame, "contact");
  const double rms = CompareWithC(setup.Pass, frame, "contact");
  MRGI_TEST_CHECK(rms < 1e-4);
}

//------------------------------------------------------------------------------
void TestBackFacing()
{
  std::printf("a wall lit from behind; lights grazing the floor\n");
  // A single-sided wall at x = 0 facing +x, a box on its +x side; the spot
  // light is on the -x side and sees only the wall.
  for (int front = 0; front < 2; ++front)
  {
    Setup setup(97, 61);
    vtkRenderer* r = setup.Renderer;
    const double o[3] = { 0, -2, -5 }, p1[3] = { 0, -2, 5 }, p2[3] = { 0, 6, -5 };
    AddPlane(r, o, p1, p2, 0.9, 0.9, 0.9);
    AddBox(r, 2.5, 1, front ? -3 : 0, 1.5, 1.5, 1.5, 0.8, 0.8, 0.8);
    const double behind[3] = { -5, 2, 0 }, inFront[3] = { 6, 2, 2.5 }, target[3] = { 0, 2, 0 };
    AddLight(r, front ? inFront : behind, target, true, 25, 1.0);
    const double eye[3] = { 9, 4, 4 }, focal[3] = { 1, 1.5, 0 };
    setup.Camera(eye, focal, 50);
    Frame frame;
    RenderFrame(setup.Window, setup.Pass, frame, front ? "wall lit from the front" : "wall lit from behind");
    MRGI_TEST_CHECK(frame.Indirect);
    int lit = 0;
    for (const mrgi_vpl& vpl : frame.VPLs)
    {
      if (vpl.flux[0] > 0)
      {
        ++lit;
        // VPL normals face the light.
        MRGI_TEST_CHECK(front ? vpl.normal[0] > 0.99f : vpl.normal[0] < -0.99f);
      }
    }
    const double maxIndirect = MaxValue(frame.IndirectImage);
    std::printf("  lit from %s: %d lit VPLs, max indirect %.4g\n", front ? "the front" : "behind", lit,
      maxIndirect);
    MRGI_TEST_CHECK(lit > 0);
    if (front)
    {
      MRGI_TEST_CHECK(maxIndirect > 1e-3);
      CheckBounded(frame, "lit from the front");
    }
    else
    {
      // Receivers off the wall's plane (the box): every VPL faces away,
      // exactly 0. Receivers on the wall's front: the VPLs are in their plane
      // (grazing, 0 in exact arithmetic); half-float normals leave a trace.
      const double* m = setup.Pass->GetLastViewToWorld();
      const float* P = Floats(frame.Position);
      const float* E = Floats(frame.Irradiance);
      double offPlane = 0, onPlane = 0, maxRadiance = 0, bound[3];
      size_t boxPixels = 0;
      RadianceBound(frame.VPLs, bound, &maxRadiance);
      for (size_t p = 0; p < static_cast<size_t>(frame.Width) * frame.Height; ++p)
      {
        if (!(P[4 * p + 3] > MRGI_VALID_THRESHOLD))
        {
          continue;
        }
        const double x = m[0] * P[4 * p] + m[4] * P[4 * p + 1] + m[8] * P[4 * p + 2] + m[12];
        const double e = std::max({ E[3 * p], E[3 * p + 1], E[3 * p + 2] });
        if (x > 0.01)
        {
          offPlane = std::max(offPlane, e);
          ++boxPixels;
        }
        else
        {
          onPlane = std::max(onPlane, e);
        }
      }
      std::printf("  lit from behind: max E on the box (%zu pixels) %.3g, on the wall's front %.3g "
                  "(%.3g of the max VPL radiance)\n",
        boxPixels, offPlane, onPlane, onPlane / maxRadiance);
      MRGI_TEST_CHECK(boxPixels > 100);
      MRGI_TEST_CHECK(offPlane == 0.0);
      MRGI_TEST_CHECK(onPlane < 1e-5 * maxRadiance);
    }
  }

  // Directional light exactly along the floor (edge-on: no floor texels),
  // nearly so (cos theta = 0.02 < MRGI_RSM_MIN_COS: area clamped), and at a
  // low angle, onto a wall that faces it.
  for (double dy : { 0.0, 1e-3, 0.02, 0.05 })
  {
    Setup setup(97, 61);
    vtkRenderer* r = setup.Renderer;
    const double f0[3] = { -5, 0, -5 }, f1[3] = { 5, 0, -5 }, f2[3] = { -5, 0, 5 };
    AddPlane(r, f0, f2, f1, 0.8, 0.8, 0.8); // floor, normal +y
    const double w0[3] = { -5, 0, -5 }, w1[3] = { 5, 0, -5 }, w2[3] = { -5, 5, -5 };
    AddPlane(r, w0, w1, w2, 0.9, 0.6, 0.3); // wall at z = -5 facing +z
    const double from[3] = { 0, dy, 1 }, to[3] = { 0, 0, 0 };
    AddLight(r, from, to, false, 30, 1.0);
    const double eye[3] = { 0, 6, 9 }, focal[3] = { 0, 0.5, -1 };
    setup.Camera(eye, focal, 50);
    Frame frame;
    char what[64];
    std::snprintf(what, sizeof(what), "grazing light (dy %g)", dy);
    RenderFrame(setup.Window, setup.Pass, frame, what);
    MRGI_TEST_CHECK(frame.Indirect);
    // The RSM texels: floor texels (if any) have cos theta = light elevation,
    // their area is the wall's (cos theta = 1) over max(cos theta, MRGI_RSM_MIN_COS).
    vtkMRGIReflectiveShadowMapPass* rsm = setup.Pass->GetReflectiveShadowMapPass();
    MRGI_TEST_CHECK(rsm->GetNumberOfViews() == 1);
    vtkNew<vtkImageData> rp, rn, rf;
    MRGI_TEST_CHECK(rsm->ReadView(setup.Window, 0, rp, rn, rf));
    const float* RP = Floats(rp);
    const float* RN = Floats(rn);
    const float* RF = Floats(rf);
    double floorFlux = 0, floorArea = 0, wallFlux = 0, wallArea = 0;
    size_t floorTexels = 0, wallTexels = 0;
    for (size_t t = 0; t < ValueCount(rp) / 4; ++t)
    {
      if (!(RP[4 * t + 3] > MRGI_VALID_THRESHOLD))
      {
        continue;
      }
      for (int k = 0; k < 4; ++k)
      {
        MRGI_TEST_CHECK(std::isfinite(RF[4 * t + k]) && RF[4 * t + k] >= 0);
      }
      if (RN[4 * t + 1] > 0.9f)
      {
        floorFlux += RF[4 * t];
        floorArea += RF[4 * t + 3];
        ++floorTexels;
      }
      else if (RN[4 * t + 2] > 0.9f)
      {
        wallFlux += RF[4 * t];
        wallArea += RF[4 * t + 3];
        ++wallTexels;
      }
    }
    const double areaRatio = floorTexels && wallTexels
      ? (floorArea / floorTexels) / (wallArea / wallTexels) : 0.0;
    std::printf("  %s: %zu floor texels (flux %.4g, area per texel %.3g x the wall's), %zu wall "
                "texels (flux %.4g); max indirect %.4g\n",
      what, floorTexels, floorFlux, areaRatio, wallTexels, wallFlux, MaxValue(frame.IndirectImage));
    MRGI_TEST_CHECK(wallFlux > 0);
    MRGI_TEST_CHECK(MaxValue(frame.IndirectImage) > 0); // the wall lights the floor
    MRGI_TEST_CHECK(areaRatio <= 1.0 / MRGI_RSM_MIN_COS * 1.01);
    if (dy == 0)
    {
      MRGI_TEST_CHECK(floorFlux == 0); // cos theta = 0 (or edge-on: no texels)
    }
    CheckBounded(frame, what);
    MRGI_TEST_CHECK(CompareWithC(setup.Pass, frame, what) < 1e-4);
  }
}

//------------------------------------------------------------------------------
// Zero-area, collinear, NaN/Inf coordinates, NaN/zero normals.
vtkSmartPointer<vtkPolyData> BadGeometry(int kind)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  auto tri = [&](const double a[3], const double b[3], const double c[3]) {
    const vtkIdType ids[3] = { points->InsertNextPoint(a), points->InsertNextPoint(b),
      points->InsertNextPoint(c) };
    polys->InsertNextCell(3, ids);
  };
  // A standing quad in front of the box (x = 0.5 .. 2.5, y = 0 .. 2, z = 1.5).
  const double q0[3] = { 0.5, 0, 1.5 }, q1[3] = { 2.5, 0, 1.5 }, q2[3] = { 2.5, 2, 1.5 },
               q3[3] = { 0.5, 2, 1.5 };
  const double bad[3] = { kind == 1 ? nan : inf, 1, 1.5 };
  switch (kind)
  {
    case 0: // zero-area and collinear triangles only
      tri(q0, q0, q0);
      tri(q0, q1, q1);
      tri(q0, q1, q0);
      {
        const double mid[3] = { 1.5, 0, 1.5 };
        tri(q0, mid, q1);
      }
      break;
    case 1: // NaN coordinate
    case 2: // Inf coordinate
      tri(q0, q1, bad);
      tri(bad, q2, q3);
      tri(bad, bad, bad);
      break;
    default: // NaN (3) or zero (4) point normals on a regular quad
      tri(q0, q1, q2);
      tri(q0, q2, q3);
      break;
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(polys);
  if (kind >= 3)
  {
    vtkNew<vtkFloatArray> normals;
    normals->SetNumberOfComponents(3);
    normals->SetName("Normals");
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
    {
      // Half the points bad, half good: interpolation mixes them.
      const bool badNormal = (i % 2) == 0;
      const float v = kind == 3 ? std::numeric_limits<float>::quiet_NaN() : 0.0f;
      const float n[3] = { badNormal ? v : 0.0f, badNormal ? v : 0.0f, badNormal ? v : 1.0f };
      normals->InsertNextTuple(n);
    }
    poly->GetPointData()->SetNormals(normals);
  }
  return poly;
}

void TestDegenerateInput()
{
  std::printf("degenerate input polydata\n");
  const char* names[] = { "zero-area and collinear triangles", "NaN point coordinates",
    "Inf point coordinates", "NaN point normals", "zero point normals" };
  Frame clean;
  for (int kind = -1; kind < 5; ++kind)
  {
    Setup setup(97, 61);
    vtkRenderer* r = setup.Renderer;
    AddBox(r, 0, -0.1, 0, 10, 0.2, 10, 0.8, 0.8, 0.8);
    AddBox(r, -1, 1, 0, 2, 2, 2, 0.9, 0.3, 0.2);
    const double light[3] = { 3, 7, 6 }, target[3] = { 0, 0, 0 };
    AddLight(r, light, target, true, 40, 1.0);
    if (kind >= 0)
    {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(BadGeometry(kind));
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      actor->GetProperty()->SetColor(0.3, 0.5, 0.9);
      actor->GetProperty()->SetAmbient(0.0);
      actor->GetProperty()->SetSpecular(0.0);
      r->AddActor(actor);
    }
    const double eye[3] = { 2, 5, 11 }, focal[3] = { 0, 1, 0 };
    setup.Camera(eye, focal, 45);
    // A fixed clipping range: non-finite bounds must not decide what this test sees.
    setup.Renderer->GetActiveCamera()->SetClippingRange(5.0, 25.0);
    Frame frame;
    const char* what = kind < 0 ? "clean scene" : names[kind];
    RenderFrame(setup.Window, setup.Pass, kind < 0 ? clean : frame, what);
    Frame& f = kind < 0 ? clean : frame;
    MRGI_TEST_CHECK(f.Indirect);
    const double maxIndirect = MaxValue(f.IndirectImage);
    MRGI_TEST_CHECK(maxIndirect > 0);
    if (kind < 0)
    {
      std::printf("  clean scene: max indirect %.4g\n", maxIndirect);
      continue;
    }
    // Away from the bad prop's pixels (same G-buffer position), the image is the clean one.
    double rms, maxRel, differing;
    CompareImages(f.Color, clean.Color, 1.0, 3, rms, maxRel, differing);
    double irms, imaxRel, idiffering;
    CompareImages(f.IndirectImage, clean.IndirectImage, 1.0, 3, irms, imaxRel, idiffering);
    std::printf("  %s: finite; max indirect %.4g; vs clean scene: colour relative RMS %.3g, "
                "indirect relative RMS %.3g\n",
      what, maxIndirect, rms, irms);
    if (kind <= 2)
    {
      // Nothing of the bad prop is drawn or reflects: the clean image, exactly.
      MRGI_TEST_CHECK(rms == 0.0 && irms == 0.0);
    }
    CheckBounded(f, what);
    MRGI_TEST_CHECK(CompareWithC(setup.Pass, f, what) < 1e-4);
  }
}

//------------------------------------------------------------------------------
void TestLightInside()
{
  std::printf("a point light inside a closed box, and on a surface\n");
  for (int variant = 0; variant < 3; ++variant)
  {
    Setup setup(97, 61);
    vtkRenderer* r = setup.Renderer;
    AddBox(r, 0, 0, 0, 4, 4, 4, 0.8, 0.7, 0.6); // closed: six faces
    AddBox(r, 0, -2.1, 0, 12, 0.2, 12, 0.8, 0.8, 0.8); // floor under it, touching
    const double inside[3] = { 0.3, 0.5, -0.2 }, onFloor[3] = { 4, -2, 4 };
    const double target[3] = { 0, -1, 0 };
    AddLight(r, variant == 2 ? onFloor : inside, target, true, 90, 1.0);
    const char* what = variant == 0 ? "camera inside" : (variant == 1 ? "camera outside" : "light on the floor");
    if (variant == 0)
    {
      const double eye[3] = { 0, 0, 1.8 }, focal[3] = { 0, -0.3, -1 };
      setup.Camera(eye, focal, 100);
    }
    else
    {
      const double eye[3] = { 6, 5, 12 }, focal[3] = { 0, -1, 0 };
      setup.Camera(eye, focal, 45);
    }
    Frame frame;
    RenderFrame(setup.Window, setup.Pass, frame, what);
    MRGI_TEST_CHECK(frame.Indirect);
    std::printf("  %s: %d RSM views, max indirect %.4g\n", what,
      setup.Pass->GetReflectiveShadowMapPass()->GetNumberOfViews(), MaxValue(frame.IndirectImage));
    if (variant != 1)
    {
      MRGI_TEST_CHECK(MaxValue(frame.IndirectImage) > 0);
    }
    CheckBounded(frame, what);
    MRGI_TEST_CHECK(CompareWithC(setup.Pass, frame, what) < 1e-4);
  }
}

//------------------------------------------------------------------------------
void TestIntensity()
{
  std::printf("light intensity 1e-6 .. 1e6\n");
  Setup setup(97, 61);
  ReferenceScene scene;
  scene.Build(setup);
  Frame reference;
  scene.SetIntensityFactor(1.0);
  RenderFrame(setup.Window, setup.Pass, reference, "intensity x1");
  for (double k : { 1e-6, 1e-3, 1e3, 1e6 })
  {
    Frame frame;
    char what[64];
    std::snprintf(what, sizeof(what), "intensity x%g", k);
    scene.SetIntensityFactor(k);
    RenderFrame(setup.Window, setup.Pass, frame, what);
    MRGI_TEST_CHECK(frame.Indirect);
    double rms, maxRel, differing, crms, cmaxRel, cdiffering;
    CompareImages(frame.IndirectImage, reference.IndirectImage, k, 3, rms, maxRel, differing);
    CompareImages(frame.Color, reference.Color, k, 3, crms, cmaxRel, cdiffering);
    std::printf("  x%-6g: indirect / k vs x1: relative RMS %.3g, max relative %.3g; colour / k: "
                "relative RMS %.3g, max relative %.3g; max colour %.4g\n",
      k, rms, maxRel, crms, cmaxRel, MaxValue(frame.Color));
    MRGI_TEST_CHECK(maxRel < 1e-3 && rms < 1e-3);
    MRGI_TEST_CHECK(cmaxRel < 1e-3 && crms < 1e-3);
  }
}

//------------------------------------------------------------------------------
void TestTinyWindows()
{
  std::printf("windows of 1 x 1, 1 x 61, 97 x 1\n");
  const int sizes[3][2] = { { 1, 1 }, { 1, 61 }, { 97, 1 } };
  for (const auto& size : sizes)
  {
    Setup setup(size[0], size[1]);
    ReferenceScene scene;
    scene.Build(setup);
    // Look at the lit floor so that the pixel(s) gather something.
    const double eye[3] = { 0, 6, 6 }, focal[3] = { 0.5, 0, 1.5 };
    setup.Camera(eye, focal, 20);
    Frame frame;
    char what[64];
    std::snprintf(what, sizeof(what), "%d x %d", size[0], size[1]);
    RenderFrame(setup.Window, setup.Pass, frame, what);
    MRGI_TEST_CHECK(frame.Indirect);
    std::printf("  %s: max indirect %.4g\n", what, MaxValue(frame.IndirectImage));
    MRGI_TEST_CHECK(MaxValue(frame.IndirectImage) > 0);
    MRGI_TEST_CHECK(CompareWithC(setup.Pass, frame, what) < 1e-4);
  }
}

//------------------------------------------------------------------------------
bool SameValues(vtkImageData* a, vtkImageData* b)
{
  return ValueCount(a) == ValueCount(b) &&
    std::memcmp(Floats(a), Floats(b), sizeof(float) * ValueCount(a)) == 0;
}

void TestNoIndirect()
{
  std::printf("zero VPLs, lights off, a light that reaches nothing\n");
  Setup setup(97, 61);
  ReferenceScene scene;
  scene.Build(setup);
  vtkMRGIPass* pass = setup.Pass;

  auto expectOff = [&](const char* what) {
    Frame frame;
    const vtkIdType renders = pass->GetReflectiveShadowMapPass()->GetNumberOfRenders();
    RenderFrame(setup.Window, pass, frame, what);
    MRGI_TEST_CHECK(!frame.Indirect);
    MRGI_TEST_CHECK(!pass->GetIndirectComputed());
    pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
    Frame off;
    RenderFrame(setup.Window, pass, off, "indirect off");
    pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
    MRGI_TEST_CHECK(SameValues(frame.Color, off.Color));
    std::printf("  %s: no indirect light, image identical to IndirectMode Off (%lld RSM renders)\n",
      what, static_cast<long long>(pass->GetReflectiveShadowMapPass()->GetNumberOfRenders() - renders));
  };

  pass->SetNumberOfVPLs(0);
  expectOff("SetNumberOfVPLs(0)");
  MRGI_TEST_CHECK(pass->GetNumberOfVPLs() == 0);

  // Fewer VPLs than lights: each light still gets its request of 1, and the
  // grid gives every view at least one VPL (mrgi_vpl_grid_layout()): one per view.
  pass->SetNumberOfVPLs(1);
  Frame one;
  RenderFrame(setup.Window, pass, one, "one VPL, three lights");
  MRGI_TEST_CHECK(one.Indirect);
  const int views = pass->GetReflectiveShadowMapPass()->GetNumberOfViews();
  std::printf("  SetNumberOfVPLs(1) with 3 lights: %zu VPLs, one per RSM view (%d)\n", one.VPLs.size(), views);
  MRGI_TEST_CHECK(one.VPLs.size() == static_cast<size_t>(views));
  MRGI_TEST_CHECK(MaxValue(one.IndirectImage) > 0);
  pass->SetNumberOfVPLs(256);

  for (auto& light : scene.Lights)
  {
    light->SwitchOff();
  }
  expectOff("all lights off");
  for (auto& light : scene.Lights)
  {
    light->SetIntensity(0.0);
    light->SwitchOn();
  }
  expectOff("all intensities 0");

  // Only a spot light pointing away from everything.
  scene.Lights[1]->SwitchOff();
  scene.Lights[2]->SwitchOff();
  scene.Lights[0]->SetIntensity(1.0);
  scene.Lights[0]->SetPosition(0, 20, 0);
  scene.Lights[0]->SetFocalPoint(0, 40, 0);
  scene.Lights[0]->SetConeAngle(20);
  expectOff("a spot light pointing away");
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestScale), MRGI_TEST_CASE(TestContact), MRGI_TEST_CASE(TestBackFacing),
      MRGI_TEST_CASE(TestDegenerateInput), MRGI_TEST_CASE(TestLightInside),
      MRGI_TEST_CASE(TestIntensity), MRGI_TEST_CASE(TestTinyWindows),
      MRGI_TEST_CASE(TestNoIndirect) });
}
