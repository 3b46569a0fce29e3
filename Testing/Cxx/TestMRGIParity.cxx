// GPU / C parity of MRGI's indirect-light stages on random scenes (DESIGN.md,
// "One source of truth for C and GLSL": exact for integer and mask outputs,
// relative error under 1e-4 for float outputs).
//
// Every scene is random but seeded: boxes and spheres with random albedos and
// transforms (non-uniform scales included) on a floor, one to three random
// lights (narrow spot, wide spot = cube faces with some skipped, point light
// = six cube faces, directional, headlight), a random camera in perspective
// or parallel projection, NPOT windows (one with the renderer in part of it),
// NPOT RSM resolutions, grid blocks from 1 texel to a whole 2048 x 2048 map. For each scene, after a
// vtkMRGIPass render (IndirectFull):
//
// 1. grid VPL selection: the RSM views read back through ReadView() and fed
//    to mrgi_vpl_select_grid() (the pass's per-light request, NumberOfVPLs /
//    lights) give the GPU's VPL texture: the same counts and layout, the same
//    positions and normals bit for bit, flux and area within 1e-4 relative;
// 2. importance selection: the uploaded texture equals a fresh
//    mrgi_vpl_select_importance() run bit for bit;
// 3. gather: mrgi_gather_full() on the read-back G-buffer and VPLs gives the
//    GPU irradiance within 1e-4 relative RMS, with an identical validity mask
//    (irradiance alpha = 1 exactly where the G-buffer holds geometry), both
//    with the receivers brought to world space in double (matrix NULL) and
//    with the VPLs brought to eye space by the inverse of GetLastViewToWorld();
// 4. composite: Indirect = strength * albedo * E, and the final colour is the
//    IndirectOff colour plus the indirect buffer.
//
// The measured errors are printed (worst over all scenes at the end) so that
// they can be quoted in the documentation.
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include "mrgi_gather.h"
#include "mrgi_vpl.h"

#include <algorithm>
#include <cinttypes>
#include <cstring>
#include <map>
#include <vector>

// The pass, with the gather's alpha (its validity mask) readable: the public
// GetIrradianceBuffer() returns RGB only.
class vtkMRGIParityPass : public vtkMRGIPass
{
public:
  static vtkMRGIParityPass* New();
  vtkTypeMacro(vtkMRGIParityPass, vtkMRGIPass);
  bool GetIrradianceRGBA(vtkRenderWindow* window, vtkImageData* image)
  {
    return this->ReadViewport(window, this->IndirectComputed ? this->GetIrradianceTexture() : nullptr,
      4, image, "IrradianceRGBA");
  }

protected:
  vtkMRGIParityPass() = default;
  ~vtkMRGIParityPass() override = default;

private:
  vtkMRGIParityPass(const vtkMRGIParityPass&) = delete;
  void operator=(const vtkMRGIParityPass&) = delete;
};
vtkStandardNewMacro(vtkMRGIParityPass);

namespace
{
// Deterministic on every platform (std:: distributions are not).
struct Random
{
  uint64_t State;
  uint64_t Next()
  {
    uint64_t z = (this->State += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double Uniform() { return static_cast<double>(this->Next() >> 11) * 0x1.0p-53; }
  double Range(double a, double b) { return a + (b - a) * this->Uniform(); }
  int Int(int n) { return static_cast<int>(this->Next() % static_cast<uint64_t>(n)); }
};

float* Floats(vtkImageData* image)
{
  return vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars())->GetPointer(0);
}

const char* LightKind(vtkLight* light)
{
  if (light->LightTypeIsHeadlight())
  {
    return "headlight";
  }
  if (!light->GetPositional())
  {
    return "directional";
  }
  if (light->GetConeAngle() >= 90.0)
  {
    return "point";
  }
  return light->GetConeAngle() > MRGI_RSM_MAX_SPOT_HALF_ANGLE_DEG ? "wide spot" : "spot";
}

struct SceneSetup
{
  int Width;
  int Height;
  int RSMResolution;
  int NumberOfVPLs;
  bool Parallel;
  int Lights;      // number of lights
  int ForceKind;   // -1 random, else the kind of the first light (0 spot, 1 wide spot, 2 point, 3 directional, 4 headlight)
  double Strength; // IndirectStrength
  bool SubViewport = false; // the renderer covers only part of the window
};

void AddActor(vtkRenderer* renderer, vtkPolyDataMapper* mapper, Random& rng, const double position[3],
  const double scale[3], const double orientation[3])
{
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->SetPosition(position[0], position[1], position[2]);
  actor->SetScale(scale[0], scale[1], scale[2]);
  actor->SetOrientation(orientation[0], orientation[1], orientation[2]);
  actor->GetProperty()->SetColor(rng.Range(0.1, 1.0), rng.Range(0.1, 1.0), rng.Range(0.1, 1.0));
  actor->GetProperty()->SetDiffuse(rng.Range(0.5, 1.0));
  actor->GetProperty()->SetAmbient(0.0);
  actor->GetProperty()->SetSpecular(rng.Uniform() < 0.5 ? 0.0 : 0.3);
  renderer->AddActor(actor);
}

// A floor and 3..6 random boxes and spheres; 1..3 random lights; a random camera.
void BuildRandomScene(vtkRenderer* renderer, Random& rng, const SceneSetup& setup)
{
  vtkNew<vtkCubeSource> cube;
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(16);
  vtkNew<vtkPolyDataMapper> cubeMapper;
  cubeMapper->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphere->GetOutputPort());

  const double floorPosition[3] = { 0, -0.1, 0 };
  const double floorScale[3] = { 12, 0.2, 12 };
  const double none[3] = { 0, 0, 0 };
  AddActor(renderer, cubeMapper, rng, floorPosition, floorScale, none);
  const int objects = 3 + rng.Int(4);
  for (int i = 0; i < objects; ++i)
  {
    const bool box = rng.Uniform() < 0.5;
    double scale[3] = { rng.Range(0.5, 3.0), rng.Range(0.5, 3.0), rng.Range(0.5, 3.0) };
    if (!box && rng.Uniform() < 0.5)
    {
      scale[1] = scale[2] = scale[0]; // some round spheres, some ellipsoids
    }
    const double position[3] = { rng.Range(-4, 4), rng.Range(0.0, 2.0), rng.Range(-4, 4) };
    const double orientation[3] = { rng.Range(-40, 40), rng.Range(0, 360), rng.Range(-40, 40) };
    AddActor(renderer, box ? cubeMapper.Get() : sphereMapper.Get(), rng, position, scale, orientation);
  }

  renderer->AutomaticLightCreationOff();
  renderer->RemoveAllLights();
  for (int l = 0; l < setup.Lights; ++l)
  {
    const int kind = (l == 0 && setup.ForceKind >= 0) ? setup.ForceKind : rng.Int(4);
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetColor(rng.Range(0.3, 1.0), rng.Range(0.3, 1.0), rng.Range(0.3, 1.0));
    light->SetIntensity(rng.Range(0.4, 1.5));
    const double focal[3] = { rng.Range(-2, 2), 0.0, rng.Range(-2, 2) };
    light->SetFocalPoint(focal);
    if (kind == 4)
    {
      // A headlight: placed by VTK's lights pass at the camera every frame.
      light->SetLightTypeToHeadlight();
    }
    else if (kind == 3)
    {
      light->SetPositional(false);
      light->SetPosition(rng.Range(-1, 1), rng.Range(0.6, 1.0), rng.Range(-1, 1));
      light->SetFocalPoint(0, 0, 0);
    }
    else
    {
      light->SetPositional(true);
      if (kind == 2)
      {
        // A point light inside the scene, lighting all around.
        light->SetPosition(rng.Range(-3, 3), rng.Range(3.5, 6), rng.Range(-3, 3));
        light->SetConeAngle(90.0);
        if (rng.Uniform() < 0.5)
        {
          light->SetAttenuationValues(1.0, 0.05, 0.01);
        }
      }
      else
      {
        light->SetPosition(rng.Range(-6, 6), rng.Range(6, 10), rng.Range(-6, 6));
        light->SetConeAngle(kind == 0 ? rng.Range(15, 60) : rng.Range(82, 88));
        light->SetExponent(rng.Range(0.5, 4.0));
      }
    }
    renderer->AddLight(light);
  }

  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(rng.Range(-1, 1), rng.Range(0, 1), rng.Range(-1, 1));
  const double azimuth = rng.Range(0, 2 * vtkMath::Pi());
  const double elevation = rng.Range(0.25, 1.2);
  const double distance = rng.Range(14, 22);
  const double* f = camera->GetFocalPoint();
  camera->SetPosition(f[0] + distance * std::cos(elevation) * std::cos(azimuth),
    f[1] + distance * std::sin(elevation), f[2] + distance * std::cos(elevation) * std::sin(azimuth));
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(rng.Range(30, 50));
  camera->SetParallelProjection(setup.Parallel);
  camera->SetParallelScale(rng.Range(5, 9));
  renderer->ResetCameraClippingRange();
}

struct Worst
{
  double GridFlux = 0;      // max relative error of VPL flux (grid)
  double GridArea = 0;      // max relative error of VPL area (grid)
  double GatherRMSWorld = 0; // relative RMS, receivers to world in double
  double GatherRMSEye = 0;   // relative RMS, VPLs to eye by inverse(view->world)
  double GatherMaxRel = 0;   // max relative error per pixel channel (above 1e-3 of the max)
  double GatherMaxAbs = 0;   // max absolute error over max E
  double Indirect = 0;       // max relative error of Indirect vs strength * albedo * E
  double Composite = 0;      // max |Color - (ColorOff + Indirect)| / max(1, |Color|)
};

// The views of each light, in view order, as the VPL selection groups them.
void GroupViews(vtkMRGIReflectiveShadowMapPass* rsm, std::vector<int>& lightOrder,
  std::map<int, std::vector<int>>& lightViews)
{
  lightOrder.clear();
  lightViews.clear();
  for (int v = 0; v < rsm->GetNumberOfViews(); ++v)
  {
    const int light = rsm->GetViewLight(v);
    if (lightViews.find(light) == lightViews.end())
    {
      lightOrder.push_back(light);
    }
    lightViews[light].push_back(v);
  }
}

// A light's views, read back and concatenated as mrgi_rsm wants them.
struct LightRSM
{
  std::vector<float> Position, Normal, Flux;
  mrgi_rsm Map;
};

void ReadLightRSM(vtkRenderWindow* window, vtkMRGIReflectiveShadowMapPass* rsm,
  const std::vector<int>& views, LightRSM& out)
{
  const int S = rsm->GetResolution();
  const size_t texels = static_cast<size_t>(S) * S * 4;
  out.Position.assign(texels * views.size(), 0.0f);
  out.Normal.assign(texels * views.size(), 0.0f);
  out.Flux.assign(texels * views.size(), 0.0f);
  for (size_t i = 0; i < views.size(); ++i)
  {
    vtkNew<vtkImageData> p, n, f;
    MRGI_TEST_CHECK(rsm->ReadView(window, views[i], p, n, f));
    int dims[3];
    p->GetDimensions(dims);
    MRGI_TEST_CHECK(dims[0] == S && dims[1] == S);
    std::copy(Floats(p), Floats(p) + texels, out.Position.begin() + static_cast<long>(i * texels));
    std::copy(Floats(n), Floats(n) + texels, out.Normal.begin() + static_cast<long>(i * texels));
    std::copy(Floats(f), Floats(f) + texels, out.Flux.begin() + static_cast<long>(i * texels));
  }
  out.Map = { S, static_cast<int32_t>(views.size()), out.Position.data(), out.Normal.data(),
    out.Flux.data() };
}

double RelativeError(double gpu, double c)
{
  if (c == 0.0)
  {
    return gpu == 0.0 ? 0.0 : 1.0;
  }
  return std::fabs(gpu - c) / std::fabs(c);
}

// 1. Grid selection: GPU texture vs mrgi_vpl_select_grid() per light.
void CheckGrid(vtkMRGIPass* pass, vtkRenderWindow* window, const std::vector<mrgi_vpl>& gpu, Worst& worst)
{
  vtkMRGIReflectiveShadowMapPass* rsm = pass->GetReflectiveShadowMapPass();
  std::vector<int> order;
  std::map<int, std::vector<int>> views;
  GroupViews(rsm, order, views);
  const int perLight = std::max(1, pass->GetNumberOfVPLs() / static_cast<int>(order.size()));
  int row = 0;
  int empty = 0;
  int64_t usable = 0;
  double fluxError = 0, areaError = 0;
  for (int light : order)
  {
    LightRSM map;
    ReadLightRSM(window, rsm, views[light], map);
    int32_t side = 0, count = 0;
    mrgi_error err;
    MRGI_TEST_CHECK(mrgi_vpl_grid_layout(perLight, map.Map.view_count, map.Map.size, &side, &count, &err) == MRGI_OK);
    std::vector<mrgi_vpl> c(static_cast<size_t>(count));
    mrgi_vpl_selection_info info;
    if (mrgi_vpl_select_grid(&map.Map, perLight, c.data(), count, &info, &err) != MRGI_OK)
    {
      std::fprintf(stderr, "mrgi_vpl_select_grid: %s\n", err.message);
      std::exit(1);
    }
    MRGI_TEST_CHECK(info.vpl_count == count);
    MRGI_TEST_CHECK(info.rejected_texel_count == 0); // a well-formed scene gives well-formed maps
    MRGI_TEST_CHECK(row + count <= static_cast<int>(gpu.size()));
    empty += info.empty_vpl_count;
    usable += info.usable_texel_count;
    for (int k = 0; k < count; ++k)
    {
      const mrgi_vpl& g = gpu[static_cast<size_t>(row + k)];
      const mrgi_vpl& r = c[static_cast<size_t>(k)];
      for (int a = 0; a < 3; ++a)
      {
        if (g.position[a] != r.position[a] || g.normal[a] != r.normal[a])
        {
          std::fprintf(stderr, "grid VPL %d (light %d, local %d): position/normal differ: GPU "
                       "(%.9g %.9g %.9g | %.9g %.9g %.9g) C (%.9g %.9g %.9g | %.9g %.9g %.9g)\n",
            row + k, light, k, g.position[0], g.position[1], g.position[2], g.normal[0],
            g.normal[1], g.normal[2], r.position[0], r.position[1], r.position[2], r.normal[0],
            r.normal[1], r.normal[2]);
          // Which RSM texels were picked (view, x, y), to tell a wrong block from a wrong rule.
          const size_t texels = static_cast<size_t>(map.Map.size) * map.Map.size * map.Map.view_count;
          for (size_t t = 0; t < texels; ++t)
          {
            const float* p = map.Position.data() + 4 * t;
            const char* who = (p[0] == g.position[0] && p[1] == g.position[1] && p[2] == g.position[2]) ? "GPU"
              : (p[0] == r.position[0] && p[1] == r.position[1] && p[2] == r.position[2]) ? "C" : nullptr;
            if (who)
            {
              std::fprintf(stderr, "  %s picked view %zu texel (%zu, %zu)\n", who,
                t / (texels / map.Map.view_count), t % map.Map.size, (t / map.Map.size) % map.Map.size);
            }
          }
          std::fprintf(stderr, "  GPU flux %g %g %g area %g; C flux %g %g %g area %g\n", g.flux[0],
            g.flux[1], g.flux[2], g.area, r.flux[0], r.flux[1], r.flux[2], r.area);
          std::exit(1);
        }
        fluxError = std::max(fluxError, RelativeError(g.flux[a], r.flux[a]));
      }
      areaError = std::max(areaError, RelativeError(g.area, r.area));
      MRGI_TEST_CHECK(g.pad0 == 0.0f && g.pad1 == 0.0f);
    }
    row += count;
  }
  std::printf("  grid: %zu VPLs (%d lights x request %d), %d empty, %" PRId64
              " usable texels; max relative error flux %.3g, area %.3g\n",
    gpu.size(), static_cast<int>(order.size()), perLight, empty, usable, fluxError, areaError);
  MRGI_TEST_CHECK(row == static_cast<int>(gpu.size()));
  MRGI_TEST_CHECK(row == pass->GetVPLSelection()->GetVPLCount());
  MRGI_TEST_CHECK(empty < row); // something is lit in every scene
  MRGI_TEST_CHECK(fluxError < 1e-4 && areaError < 1e-4);
  worst.GridFlux = std::max(worst.GridFlux, fluxError);
  worst.GridArea = std::max(worst.GridArea, areaError);
}

// 2. Importance selection: the uploaded texture is the C core's output, bit for bit.
void CheckImportance(vtkMRGIPass* pass, vtkRenderWindow* window, const std::vector<mrgi_vpl>& gpu)
{
  vtkMRGIReflectiveShadowMapPass* rsm = pass->GetReflectiveShadowMapPass();
  std::vector<int> order;
  std::map<int, std::vector<int>> views;
  GroupViews(rsm, order, views);
  const int perLight = std::max(1, pass->GetNumberOfVPLs() / static_cast<int>(order.size()));
  MRGI_TEST_CHECK(gpu.size() == order.size() * static_cast<size_t>(perLight));
  size_t row = 0;
  for (int light : order)
  {
    LightRSM map;
    ReadLightRSM(window, rsm, views[light], map);
    std::vector<mrgi_vpl> c(static_cast<size_t>(perLight));
    mrgi_error err;
    const uint64_t seed = pass->GetVPLSelection()->GetSeed() + static_cast<uint64_t>(light);
    MRGI_TEST_CHECK(mrgi_vpl_select_importance(&map.Map, perLight, seed, nullptr, 0, c.data(),
                      perLight, nullptr, &err) == MRGI_OK);
    if (std::memcmp(c.data(), gpu.data() + row, sizeof(mrgi_vpl) * c.size()) != 0)
    {
      std::fprintf(stderr, "importance VPLs of light %d differ from the C core's\n", light);
      std::exit(1);
    }
    row += c.size();
  }
  std::printf("  importance: %zu VPLs identical to mrgi_vpl_select_importance()\n", gpu.size());
}

struct GatherErrors
{
  double RMS = 0, MaxRel = 0, MaxAbs = 0;
};

GatherErrors CompareIrradiance(const float* gpuRGBA, const mrgi_image& c, const float* position, size_t pixels)
{
  double maxC = 0;
  for (size_t p = 0; p < pixels; ++p)
  {
    for (int k = 0; k < 3; ++k)
    {
      maxC = std::max(maxC, static_cast<double>(c.pixels[3 * p + k]));
    }
  }
  double num = 0, den = 0;
  GatherErrors e;
  for (size_t p = 0; p < pixels; ++p)
  {
    if (!(position[4 * p + 3] > MRGI_VALID_THRESHOLD))
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      const double g = gpuRGBA[4 * p + k], r = c.pixels[3 * p + k];
      num += (g - r) * (g - r);
      den += r * r;
      e.MaxAbs = std::max(e.MaxAbs, std::fabs(g - r) / std::max(maxC, 1e-300));
      if (r > 1e-3 * maxC)
      {
        e.MaxRel = std::max(e.MaxRel, std::fabs(g - r) / r);
      }
    }
  }
  e.RMS = den > 0 ? std::sqrt(num / den) : (num > 0 ? 1.0 : 0.0);
  return e;
}

// 3. and 4. Gather and composite.
void CheckGather(vtkMRGIParityPass* pass, vtkRenderWindow* window, const std::vector<mrgi_vpl>& vpls,
  const char* what, Worst& worst, vtkImageData* indirectOut)
{
  vtkNew<vtkImageData> position, normal, albedo, irradiance, indirect;
  MRGI_TEST_CHECK(pass->GetGBuffer(window, position, normal, albedo));
  MRGI_TEST_CHECK(pass->GetIrradianceRGBA(window, irradiance));
  MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, indirect));
  int dims[3];
  position->GetDimensions(dims);
  MRGI_TEST_CHECK(dims[0] == pass->GetBufferSize()[0] && dims[1] == pass->GetBufferSize()[1]);
  const size_t pixels = static_cast<size_t>(dims[0]) * dims[1];
  const float* P = Floats(position);
  const float* N = Floats(normal);
  const float* A = Floats(albedo);
  const float* E = Floats(irradiance);
  const float* I = Floats(indirect);

  // Validity masks: identical (the gather writes alpha 1 exactly where it gathered).
  size_t valid = 0;
  for (size_t p = 0; p < pixels; ++p)
  {
    const bool g = P[4 * p + 3] > MRGI_VALID_THRESHOLD;
    valid += g;
    if (E[4 * p + 3] != (g ? 1.0f : 0.0f) || (!g && (E[4 * p] != 0 || E[4 * p + 1] != 0 || E[4 * p + 2] != 0)))
    {
      std::fprintf(stderr, "%s: validity mask differs at pixel %zu\n", what, p);
      std::exit(1);
    }
  }
  MRGI_TEST_CHECK(valid > 0);

  // (a) receivers to world in double, VPLs as they are (matrix NULL).
  const double* m = pass->GetLastViewToWorld();
  std::vector<float> worldP(4 * pixels), worldN(4 * pixels);
  for (size_t p = 0; p < pixels; ++p)
  {
    for (int r = 0; r < 3; ++r)
    {
      worldP[4 * p + r] = static_cast<float>(m[r] * P[4 * p] + m[4 + r] * P[4 * p + 1] +
        m[8 + r] * P[4 * p + 2] + m[12 + r]);
      worldN[4 * p + r] =
        static_cast<float>(m[r] * N[4 * p] + m[4 + r] * N[4 * p + 1] + m[8 + r] * N[4 * p + 2]);
    }
    worldP[4 * p + 3] = P[4 * p + 3];
    worldN[4 * p + 3] = N[4 * p + 3];
  }
  mrgi_gather_receivers world = { dims[0], dims[1], worldP.data(), worldN.data() };
  mrgi_image cWorld{}, cEye{};
  mrgi_gather_info info;
  mrgi_error err;
  const int32_t count = static_cast<int32_t>(vpls.size());
  MRGI_TEST_CHECK(mrgi_gather_full(&world, vpls.data(), count, nullptr, &cWorld, &info, &err) == MRGI_OK);
  MRGI_TEST_CHECK(info.vpls_malformed == 0 && info.receivers_malformed == 0);
  MRGI_TEST_CHECK(info.receivers_gathered == static_cast<int64_t>(valid));

  // (b) receivers in eye space, VPLs brought over by inverse(view -> world).
  float w2r[16];
  mrgitest::WorldToViewColumnMajor(m, w2r);
  mrgi_gather_receivers eye = { dims[0], dims[1], P, N };
  MRGI_TEST_CHECK(mrgi_gather_full(&eye, vpls.data(), count, w2r, &cEye, &info, &err) == MRGI_OK);

  const GatherErrors a = CompareIrradiance(E, cWorld, P, pixels);
  const GatherErrors b = CompareIrradiance(E, cEye, P, pixels);
  std::printf("  gather (%s, %zu valid pixels, %d VPLs used): relative RMS %.3g (world) %.3g (eye); "
              "max relative %.3g / %.3g (pixels above 1e-3 of the max), max |error| / max E %.3g / %.3g\n",
    what, valid, info.vpls_used, a.RMS, b.RMS, a.MaxRel, b.MaxRel, a.MaxAbs, b.MaxAbs);
  MRGI_TEST_CHECK(a.RMS < 1e-4 && b.RMS < 1e-4);
  MRGI_TEST_CHECK(a.MaxAbs < 1e-3 && b.MaxAbs < 1e-3);
  MRGI_TEST_CHECK(a.MaxRel < 2e-3 && b.MaxRel < 2e-3);
  worst.GatherRMSWorld = std::max(worst.GatherRMSWorld, a.RMS);
  worst.GatherRMSEye = std::max(worst.GatherRMSEye, b.RMS);
  worst.GatherMaxRel = std::max({ worst.GatherMaxRel, a.MaxRel, b.MaxRel });
  worst.GatherMaxAbs = std::max({ worst.GatherMaxAbs, a.MaxAbs, b.MaxAbs });
  mrgi_image_destroy(&cWorld);
  mrgi_image_destroy(&cEye);

  // Indirect = strength * albedo * E, in float on the GPU.
  const double strength = static_cast<float>(pass->GetIndirectStrength());
  double indirectError = 0, maxIndirect = 0;
  for (size_t p = 0; p < pixels; ++p)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double expected = strength * A[4 * p + k] * E[4 * p + k];
      indirectError = std::max(indirectError, RelativeError(I[3 * p + k], expected));
      maxIndirect = std::max(maxIndirect, static_cast<double>(I[3 * p + k]));
      MRGI_TEST_CHECK(std::isfinite(I[3 * p + k]) && I[3 * p + k] >= 0);
    }
  }
  std::printf("  indirect = %.3g * albedo * E: max relative error %.3g (max indirect %.3g)\n",
    strength, indirectError, maxIndirect);
  MRGI_TEST_CHECK(indirectError < 1e-5);
  MRGI_TEST_CHECK(maxIndirect > 0);
  worst.Indirect = std::max(worst.Indirect, indirectError);
  if (indirectOut)
  {
    indirectOut->DeepCopy(indirect);
  }
}

void RunScene(int index, uint64_t seed, const SceneSetup& setup, Worst& worst)
{
  Random rng{ seed };
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(setup.Width, setup.Height);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  if (setup.SubViewport)
  {
    renderer->SetViewport(0.15, 0.1, 0.9, 0.95);
  }
  BuildRandomScene(renderer, rng, setup);
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIParityPass> pass;
  pass->SetDelegatePass(steps);
  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  pass->SetNumberOfVPLs(setup.NumberOfVPLs);
  pass->SetRSMResolution(setup.RSMResolution);
  pass->SetIndirectStrength(setup.Strength);
  pass->GetVPLSelection()->SetSeed(seed * 7 + 3);
  renderer->SetPass(pass);

  std::printf("scene %d (seed %" PRIu64 "): %dx%d, %s, RSM %d, %d VPLs asked, strength %.3g, lights:",
    index, seed, setup.Width, setup.Height, setup.Parallel ? "parallel" : "perspective",
    setup.RSMResolution, setup.NumberOfVPLs, setup.Strength);
  vtkLightCollection* lights = renderer->GetLights();
  lights->InitTraversal();
  while (vtkLight* light = lights->GetNextItem())
  {
    std::printf(" %s", LightKind(light));
  }
  std::printf("\n");

  // Grid selection.
  pass->SetVPLSelectionMode(vtkMRGIVPLSelection::Grid);
  window->Render();
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  std::printf("  %d RSM views, viewport %d x %d\n", pass->GetReflectiveShadowMapPass()->GetNumberOfViews(),
    pass->GetBufferSize()[0], pass->GetBufferSize()[1]);
  const std::vector<mrgi_vpl> grid = mrgitest::ReadVPLs(pass, window);
  CheckGrid(pass, window, grid, worst);
  vtkNew<vtkImageData> indirect, color;
  CheckGather(pass, window, grid, "grid VPLs", worst, indirect);
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, color));

  // Composite: colour = colour without indirect light + indirect buffer
  // (additive blending in float; the RSMs are not re-rendered).
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  window->Render();
  MRGI_TEST_CHECK(!pass->GetIndirectComputed());
  vtkNew<vtkImageData> direct;
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, direct));
  const float* C = Floats(color);
  const float* D = Floats(direct);
  const float* I = Floats(indirect);
  const size_t pixels = static_cast<size_t>(pass->GetBufferSize()[0]) * pass->GetBufferSize()[1];
  double compositeError = 0;
  for (size_t p = 0; p < pixels; ++p)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double expected = static_cast<double>(D[4 * p + k]) + I[3 * p + k];
      compositeError = std::max(compositeError,
        std::fabs(C[4 * p + k] - expected) / std::max(1.0, std::fabs(expected)));
    }
    MRGI_TEST_CHECK(C[4 * p + 3] == D[4 * p + 3]); // indirect light leaves alpha alone
  }
  std::printf("  colour = colour(indirect off) + indirect: max error %.3g\n", compositeError);
  MRGI_TEST_CHECK(compositeError < 1e-5);
  worst.Composite = std::max(worst.Composite, compositeError);

  // Importance selection (the RSMs are unchanged; the VPLs are re-selected).
  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  pass->SetVPLSelectionMode(vtkMRGIVPLSelection::FluxImportance);
  const vtkIdType rsmRenders = pass->GetReflectiveShadowMapPass()->GetNumberOfRenders();
  window->Render();
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  MRGI_TEST_CHECK(pass->GetReflectiveShadowMapPass()->GetNumberOfRenders() == rsmRenders);
  const std::vector<mrgi_vpl> importance = mrgitest::ReadVPLs(pass, window);
  CheckImportance(pass, window, importance);
  CheckGather(pass, window, importance, "importance VPLs", worst, nullptr);

  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
}
}

int main()
{
  // Window sizes (NPOT, both aspects), RSM resolutions (NPOT ones make
  // uneven grid blocks), VPL requests (not squares, not multiples of the
  // number of lights), projections, light mixes.
  const SceneSetup setups[] = {
    { 97, 61, 64, 256, false, 1, 0, 1.0 },   // one narrow spot
    { 61, 97, 100, 100, true, 2, 3, 0.7 },   // directional + random, parallel projection
    { 97, 61, 37, 37, false, 1, 2, 1.0 },    // point light: six cube faces, 1 VPL each
    { 128, 77, 256, 1000, false, 3, 1, 2.5 }, // wide spot (some cube faces skipped) + 2 random
    { 45, 33, 50, 300, true, 2, 2, 1.0 },     // point + random, parallel
    { 97, 61, 16, 4096, false, 1, 0, 1.0 },  // grid side capped by the RSM size (G = S)
    { 80, 80, 128, 256, false, 2, 4, 1.0 },   // headlight + random
    { 101, 67, 73, 500, true, 3, -1, 1.3 },   // three random lights, parallel
    { 67, 101, 200, 64, false, 2, -1, 1.0 },  // two random lights, few VPLs
    { 97, 61, 512, 6, false, 1, 2, 1.0 },     // point light, one VPL per cube face: 512 x 512 texel blocks
    { 61, 61, 2048, 1, false, 1, 0, 1.0 },    // one spot, one VPL: the whole 2048 x 2048 map in one block
    { 131, 89, 96, 256, false, 2, -1, 1.0, true }, // the renderer covers part of the window
  };
  Worst worst;
  int index = 0;
  for (const SceneSetup& setup : setups)
  {
    RunScene(index, 1000 + 17 * static_cast<uint64_t>(index), setup, worst);
    ++index;
  }
  std::printf("\nworst over %d scenes:\n", index);
  std::printf("  grid VPL flux relative error   %.3g (tolerance 1e-4)\n", worst.GridFlux);
  std::printf("  grid VPL area relative error   %.3g (tolerance 1e-4)\n", worst.GridArea);
  std::printf("  gather relative RMS (world)    %.3g (tolerance 1e-4)\n", worst.GatherRMSWorld);
  std::printf("  gather relative RMS (eye)      %.3g (tolerance 1e-4)\n", worst.GatherRMSEye);
  std::printf("  gather max relative per pixel  %.3g (pixels above 1e-3 of the max; tolerance 2e-3)\n", worst.GatherMaxRel);
  std::printf("  gather max |error| / max E     %.3g (tolerance 1e-3)\n", worst.GatherMaxAbs);
  std::printf("  indirect vs s * albedo * E     %.3g (tolerance 1e-5)\n", worst.Indirect);
  std::printf("  colour vs direct + indirect    %.3g (tolerance 1e-5)\n", worst.Composite);
  return 0;
}
