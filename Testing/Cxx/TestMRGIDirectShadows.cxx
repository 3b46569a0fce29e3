// The GPU's shadow factors (vtkMRGIDirectShadows) against the C twin
// (mrgi_direct_shadow_gbuffer) on the GPU's own inputs: the G-buffer and
// the RSM views a vtkMRGIPass rendered, read back.
// (1) SpotAndDirectional: cornell-spot's spot light in slot 0 and a
//     directional light through the open front in slot 1 (both channels);
// (2) PointCube: cornell's point light (six cube faces) in slot 0, slot 1
//     empty (its channel must stay exactly 1);
// (3) SubViewport: a renderer on a tile of the window: texels outside the
//     tile keep what the texture held; a slot naming a light without views
//     stays 1; the depth maps are derived again only when the RSMs are
//     re-rendered (then the factors still match the twin).
// (4) Levels: the multiresolution path's level draws
//     (vtkMRGIDirectShadows::ComputeLevels, levels 1..3, under the stencils
//     ComputeMultiresolution built) against mrgi_direct_shadow_level() on
//     the same G-buffer: each stenciled texel is 1 - the factor of its
//     block's centre pixel, every other texel 0; for (1) and (2).
// Each in hard (3 x 3 PCF) and soft (PCSS, 196 taps) mode, on a non-square
// window. Compared per pixel: within 1e-4 on >= 99.9% of the pixels; the
// rest may differ where float (GPU) and double (twin) put a tap on the
// other side of a texel boundary: the taps of one grid row (or column)
// share their offset, so a whole row moves to the neighbouring texel row
// together (n taps; seen at 512 x 384: 14 taps on 2 to 4 pixels of 137,000).
// Bounded by one row and one column of the grid (2 / n) and counted. Channels without a
// light and the blue and alpha channels are exactly 1. Both scenes must
// have shadowed and lit pixels, so the comparison is not vacuous.
//
// `TestMRGIDirectShadows --bench` instead times Compute() at 256^2 and
// 1024^2 on cornell-spot (wall time with the window's WaitForCompletion()
// around it, and the stage timer's "MRGI shadows" event; medians of 5);
// not run by ctest. `--fidelity` multiplies VTK's direct light by the
// factor (one-light scenes) and compares it with the ground truth's direct
// light with shadows (4 x 4 boxes, the metric); not run by ctest.
#include "mrgiTestUtilities.h"

#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIBMRLevels.h"
#include "vtkMRGIDirectShadows.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReferenceRenderer.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderTimerLog.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"

#include "mrgi_buffers.h"
#include "mrgi_box_filter.h"
#include "mrgi_direct_shadow.h"
#include "mrgi_metrics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <vector>

namespace
{
// What the factor texture holds before Compute(), outside the viewport after it.
const float MarkerValue = 0.25f;

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkSmartPointer<vtkRenderer> Renderer;
  vtkSmartPointer<vtkMRGIPass> Pass;
  vtkSmartPointer<vtkTextureObject> Factors;
  vtkMRGIFrameContext Frame;
};

// Render `sceneName` (plus a directional light through the open front when
// asked) and prepare the frame context and a window-sized factor texture.
void Build(Scene& s, const char* sceneName, bool directional, int width, int height, int rsm,
  const double* viewport = nullptr)
{
  s.Window = mrgitest::HeadlessWindow(width, height);
  s.Renderer = vtkSmartPointer<vtkRenderer>::New();
  if (viewport)
  {
    s.Renderer->SetViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  }
  s.Window->AddRenderer(s.Renderer);
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene(sceneName);
  MRGI_TEST_CHECK(builder->Build(s.Renderer));
  if (directional)
  {
    vtkNew<vtkLight> sun;
    sun->SetLightTypeToSceneLight();
    sun->SetPositional(false);
    sun->SetPosition(578.0, 773.0, -800.0);
    sun->SetFocalPoint(278.0, 273.0, 279.5);
    sun->SetIntensity(0.5);
    s.Renderer->AddLight(sun);
  }
  vtkNew<vtkRenderStepsPass> steps;
  s.Pass = vtkSmartPointer<vtkMRGIPass>::New();
  s.Pass->SetDelegatePass(steps);
  s.Pass->SetNumberOfVPLs(16);
  s.Pass->SetRSMResolution(rsm);
  s.Renderer->SetPass(s.Pass);
  s.Window->Render();

  vtkOpenGLRenderWindow* glWindow = vtkOpenGLRenderWindow::SafeDownCast(s.Window);
  vtkTextureObject* position = s.Pass->GetPositionTexture();
  MRGI_TEST_CHECK(glWindow && position);
  s.Factors = vtkSmartPointer<vtkTextureObject>::New();
  s.Factors->SetContext(glWindow);
  // Default internal format of 4 float components: RGBA32F. Filled with
  // MarkerValue, which texels outside the viewport must keep.
  std::vector<float> fill(4 * static_cast<size_t>(position->GetWidth()) * position->GetHeight(), MarkerValue);
  MRGI_TEST_CHECK(s.Factors->Create2DFromRaw(
    position->GetWidth(), position->GetHeight(), 4, VTK_FLOAT, fill.data()));
  vtkMRGIFrameContext& frame = s.Frame;
  frame.Window = glWindow;
  frame.Renderer = s.Renderer;
  frame.Position = position;
  frame.Normal = s.Pass->GetNormalTexture();
  const int* vp = s.Pass->GetViewport();
  std::copy(vp, vp + 4, frame.Viewport);
  const double* v2w = s.Pass->GetLastViewToWorld();
  for (int k = 0; k < 16; ++k)
  {
    frame.ViewToWorld[k] = static_cast<float>(v2w[k]);
    frame.ViewToWorldDouble[k] = v2w[k];
  }
}

// The twin's description of RSM view i (positions read back into `store`).
mrgi_direct_shadow_view TwinView(
  vtkRenderWindow* window, vtkMRGIReflectiveShadowMapPass* rsm, int i, vtkImageData* store)
{
  vtkNew<vtkImageData> normal, flux;
  MRGI_TEST_CHECK(rsm->ReadView(window, i, store, normal, flux));
  mrgi_direct_shadow_view view;
  double m[16], p[16];
  MRGI_TEST_CHECK(rsm->GetViewWorldToView(i, m) && rsm->GetViewProjection(i, p));
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      view.world_to_view[4 * c + r] = m[4 * r + c];
    }
  }
  view.perspective = rsm->GetViewPerspective(i) ? 1 : 0;
  view.scale[0] = p[0];
  view.scale[1] = p[5];
  view.near_plane = view.perspective ? p[11] / (p[10] - 1.0) : 0.0;
  view.size = rsm->GetResolution();
  view.positions = static_cast<const float*>(store->GetScalarPointer());
  return view;
}

// The twin's views of light `light` (positions read back into `stores`).
std::vector<mrgi_direct_shadow_view> LightViews(Scene& s, int light,
  std::vector<vtkSmartPointer<vtkImageData>>& stores)
{
  vtkMRGIReflectiveShadowMapPass* rsm = s.Pass->GetReflectiveShadowMapPass();
  std::vector<mrgi_direct_shadow_view> views;
  for (int i = 0; i < rsm->GetNumberOfViews(); ++i)
  {
    if (rsm->GetViewLight(i) == light)
    {
      stores.push_back(vtkSmartPointer<vtkImageData>::New());
      views.push_back(TwinView(s.Window, rsm, i, stores.back()));
    }
  }
  return views;
}

void Compare(Scene& s, const int slots[MRGI_SHADOW_SLOTS], int mode, const char* label)
{
  mrgi_direct_shadow_params params;
  mrgi_direct_shadow_params_default(&params);
  params.mode = mode;
  params.samples_side = MRGI_DIRECT_SHADOW_MAX_SIDE;
  params.light_radius = 10.0; // world units (mm): about 2% of the box's bounding radius
  vtkMRGIReflectiveShadowMapPass* rsm = s.Pass->GetReflectiveShadowMapPass();
  vtkNew<vtkMRGIDirectShadows> gpu;
  MRGI_TEST_CHECK(gpu->Compute(s.Frame, rsm, slots, params, s.Factors));
  vtkNew<vtkFloatArray> factors;
  MRGI_TEST_CHECK(vtkMRGIDirectShadows::ReadFactors(s.Window, s.Factors, factors));
  const int texW = s.Factors->GetWidth();

  vtkNew<vtkImageData> position, normal, albedo;
  MRGI_TEST_CHECK(s.Pass->GetGBuffer(s.Window, position, normal, albedo));
  const int x0 = s.Frame.Viewport[0], y0 = s.Frame.Viewport[1];
  const int W = s.Frame.Viewport[2], H = s.Frame.Viewport[3];
  const float* P = static_cast<const float*>(position->GetScalarPointer());
  const float* N = static_cast<const float*>(normal->GetScalarPointer());
  const double taps = mode == MRGI_DIRECT_SHADOW_HARD
    ? MRGI_DIRECT_SHADOW_HARD_SIDE * MRGI_DIRECT_SHADOW_HARD_SIDE
    : params.samples_side * params.samples_side;

  int expectedDraws = 0;
  for (int slot = 0; slot < MRGI_SHADOW_SLOTS; ++slot)
  {
    std::vector<float> twin(static_cast<size_t>(W) * H, 1.0f);
    std::vector<vtkSmartPointer<vtkImageData>> stores;
    const std::vector<mrgi_direct_shadow_view> views =
      slots[slot] >= 0 ? LightViews(s, slots[slot], stores) : std::vector<mrgi_direct_shadow_view>();
    if (slots[slot] >= 0)
    {
      MRGI_TEST_CHECK(!views.empty());
      expectedDraws += static_cast<int>(views.size());
      mrgi_direct_shadow_stats stats = { 0, 0, 0 };
      mrgi_error err;
      MRGI_TEST_CHECK(mrgi_direct_shadow_gbuffer(W, H, P, N, s.Frame.ViewToWorldDouble,
                        views.data(), static_cast<int>(views.size()), &params, twin.data(),
                        &stats, &err) == MRGI_OK);
      MRGI_TEST_CHECK(stats.invalid_receivers == 0 && stats.invalid_views == 0);
    }
    size_t pixels = 0, close = 0, shadowed = 0, lit = 0, geometry = 0;
    double worst = 0.0;
    for (int y = 0; y < H; ++y)
    {
      for (int x = 0; x < W; ++x)
      {
        const size_t t = static_cast<size_t>(y) * W + x;
        const float* g = factors->GetPointer(4 * ((static_cast<size_t>(y0 + y)) * texW + x0 + x));
        MRGI_TEST_CHECK(g[2] == 1.0f && g[3] == 1.0f);
        const double e = std::fabs(static_cast<double>(g[slot]) - twin[t]);
        MRGI_TEST_CHECK(std::isfinite(g[slot]) && g[slot] >= 0.0f && g[slot] <= 1.0f);
        if (slots[slot] < 0)
        {
          MRGI_TEST_CHECK(g[slot] == 1.0f);
        }
        ++pixels;
        close += e <= 1e-4;
        worst = std::max(worst, e);
        if (P[4 * t + 3] > MRGI_GBUFFER_VALID_THRESHOLD)
        {
          ++geometry;
          shadowed += twin[t] < 0.5f;
          lit += twin[t] > 0.99f;
        }
      }
    }
    const double fraction = static_cast<double>(close) / static_cast<double>(pixels);
    std::printf("%s slot %d (light %d, %zu views): %zu pixels, %zu with geometry, %zu shadowed, "
                "%zu lit; within 1e-4: %.5f; largest difference %.4g (%.2f taps)\n",
      label, slot, slots[slot], views.size(), pixels, geometry, shadowed, lit, fraction, worst,
      worst * taps);
    MRGI_TEST_CHECK(fraction >= 0.999);
    MRGI_TEST_CHECK(worst <= 2.0 * std::sqrt(taps) / taps + 1e-5);
    if (slots[slot] >= 0)
    {
      MRGI_TEST_CHECK(shadowed >= geometry / 100 && lit >= geometry / 100);
    }
  }
  MRGI_TEST_CHECK(gpu->GetNumberOfDraws() == expectedDraws);
  // Texels outside the viewport are left as they were.
  size_t outside = 0, touched = 0;
  const int texH = s.Factors->GetHeight();
  for (int y = 0; y < texH; ++y)
  {
    for (int x = 0; x < texW; ++x)
    {
      if (x >= x0 && x < x0 + W && y >= y0 && y < y0 + H)
      {
        continue;
      }
      ++outside;
      const float* g = factors->GetPointer(4 * (static_cast<size_t>(y) * texW + x));
      touched += g[0] != MarkerValue || g[1] != MarkerValue || g[2] != MarkerValue || g[3] != MarkerValue;
    }
  }
  std::printf("%s: viewport (%d, %d, %d, %d) of %d x %d; %zu texels outside it, %zu written\n",
    label, x0, y0, W, H, texW, texH, outside, touched);
  MRGI_TEST_CHECK(touched == 0);
  gpu->ReleaseGraphicsResources(s.Window);
}

// (4): the level draws of both modes against the twin, levels 1..3.
void CompareLevels(Scene& s, const int slots[MRGI_SHADOW_SLOTS], const char* label)
{
  vtkMRGIReflectiveShadowMapPass* rsm = s.Pass->GetReflectiveShadowMapPass();
  vtkNew<vtkMRGIDirectShadows> gpu;
  mrgi_direct_shadow_params params;
  mrgi_direct_shadow_params_default(&params);
  params.samples_side = MRGI_DIRECT_SHADOW_MAX_SIDE;
  params.light_radius = 10.0;
  // Prepares the levels and builds their masks and stencils.
  MRGI_TEST_CHECK(gpu->ComputeMultiresolution(s.Frame, rsm, slots, params, s.Factors));
  vtkMRGIBMRLevels* levels = gpu->GetBMRLevels();
  vtkNew<vtkImageData> position, normal, albedo;
  MRGI_TEST_CHECK(s.Pass->GetGBuffer(s.Window, position, normal, albedo));
  const int W = s.Frame.Viewport[2], H = s.Frame.Viewport[3];
  const float* P = static_cast<const float*>(position->GetScalarPointer());
  const float* N = static_cast<const float*>(normal->GetScalarPointer());
  for (int mode : { MRGI_DIRECT_SHADOW_HARD, MRGI_DIRECT_SHADOW_SOFT })
  {
    params.mode = mode;
    const double taps = mode == MRGI_DIRECT_SHADOW_HARD
      ? MRGI_DIRECT_SHADOW_HARD_SIDE * MRGI_DIRECT_SHADOW_HARD_SIDE
      : params.samples_side * params.samples_side;
    MRGI_TEST_CHECK(gpu->ComputeLevels(s.Frame, rsm, slots, params, levels));
    for (int level = 1; level <= 3; ++level)
    {
      int size[2];
      MRGI_TEST_CHECK(levels->GetLevelSize(level, size));
      vtkNew<vtkFloatArray> colour;
      vtkNew<vtkUnsignedCharArray> stencil;
      MRGI_TEST_CHECK(levels->ReadColor(s.Window, level, colour) &&
        levels->ReadStencil(s.Window, level, stencil));
      const size_t texels = static_cast<size_t>(size[0]) * size[1];
      MRGI_TEST_CHECK(static_cast<size_t>(stencil->GetNumberOfTuples()) == texels &&
        static_cast<size_t>(colour->GetNumberOfValues()) >= 4 * texels);
      for (int slot = 0; slot < MRGI_SHADOW_SLOTS; ++slot)
      {
        std::vector<float> twin(texels, 0.0f);
        if (slots[slot] >= 0)
        {
          std::vector<vtkSmartPointer<vtkImageData>> stores;
          const std::vector<mrgi_direct_shadow_view> views = LightViews(s, slots[slot], stores);
          mrgi_error err;
          MRGI_TEST_CHECK(mrgi_direct_shadow_level(W, H, level, P, N, s.Frame.ViewToWorldDouble,
                            views.data(), static_cast<int>(views.size()), &params, twin.data(),
                            nullptr, &err) == MRGI_OK);
        }
        size_t drawn = 0, close = 0, blank = 0, shadowed = 0, lit = 0;
        double worst = 0.0;
        for (size_t t = 0; t < texels; ++t)
        {
          const float g = colour->GetValue(static_cast<vtkIdType>(4 * t + slot));
          MRGI_TEST_CHECK(std::isfinite(g) && g >= 0.0f && g <= 1.0f);
          if (stencil->GetValue(static_cast<vtkIdType>(t)) == 0)
          {
            blank += g == 0.0f; // not drawn: the cleared 0
            continue;
          }
          ++drawn;
          const double e = std::fabs(static_cast<double>(g) - twin[t]);
          close += e <= 1e-4;
          worst = std::max(worst, e);
          shadowed += twin[t] > 0.5f;
          lit += twin[t] == 0.0f;
        }
        const double fraction =
          drawn ? static_cast<double>(close) / static_cast<double>(drawn) : 0.0;
        std::printf("%s %s level %d slot %d: %zu of %zu texels stenciled, %zu shadowed, %zu lit; "
                    "within 1e-4: %.5f; largest difference %.4g (%.2f taps)\n",
          label, mode == MRGI_DIRECT_SHADOW_HARD ? "hard" : "soft", level, slot, drawn, texels,
          shadowed, lit, fraction, worst, worst * taps);
        MRGI_TEST_CHECK(blank == texels - drawn);
        MRGI_TEST_CHECK(drawn > 0 && fraction >= 0.999);
        MRGI_TEST_CHECK(worst <= 2.0 * std::sqrt(taps) / taps + 1e-5);
        if (slots[slot] < 0)
        {
          MRGI_TEST_CHECK(worst == 0.0); // no light: every texel lit, 0
        }
        else if (level == 1)
        {
          MRGI_TEST_CHECK(shadowed > 0 && lit > 0); // not vacuous
        }
      }
    }
  }
  gpu->ReleaseGraphicsResources(s.Window);
}

void SpotAndDirectional()
{
  Scene s;
  Build(s, "cornell-spot", true, 128, 96, 128);
  MRGI_TEST_CHECK(s.Renderer->GetLights()->GetNumberOfItems() == 2);
  const int slots[MRGI_SHADOW_SLOTS] = { 0, 1 };
  Compare(s, slots, MRGI_DIRECT_SHADOW_HARD, "spot+directional hard");
  Compare(s, slots, MRGI_DIRECT_SHADOW_SOFT, "spot+directional soft");
  CompareLevels(s, slots, "spot+directional");
}

void PointCube()
{
  Scene s;
  Build(s, "cornell", false, 128, 96, 128);
  vtkMRGIReflectiveShadowMapPass* rsm = s.Pass->GetReflectiveShadowMapPass();
  MRGI_TEST_CHECK(rsm->GetNumberOfViews() > 1); // cube faces
  const int slots[MRGI_SHADOW_SLOTS] = { 0, -1 };
  Compare(s, slots, MRGI_DIRECT_SHADOW_HARD, "point hard");
  Compare(s, slots, MRGI_DIRECT_SHADOW_SOFT, "point soft");
  CompareLevels(s, slots, "point");
}

// A renderer on part of a non-square window: the stage writes its tile only.
void SubViewport()
{
  Scene s;
  const double viewport[4] = { 0.2, 0.1, 0.9, 0.95 };
  Build(s, "cornell-spot", false, 144, 96, 128, viewport);
  MRGI_TEST_CHECK(s.Frame.Viewport[0] > 0 && s.Frame.Viewport[1] > 0);
  const int slots[MRGI_SHADOW_SLOTS] = { 0, -1 };
  Compare(s, slots, MRGI_DIRECT_SHADOW_HARD, "tile hard");
  Compare(s, slots, MRGI_DIRECT_SHADOW_SOFT, "tile soft");
  // A slot naming a light without views (no such light) stays lit.
  const int none[MRGI_SHADOW_SLOTS] = { 7, -1 };
  vtkNew<vtkMRGIDirectShadows> gpu;
  mrgi_direct_shadow_params params;
  mrgi_direct_shadow_params_default(&params);
  MRGI_TEST_CHECK(gpu->Compute(s.Frame, s.Pass->GetReflectiveShadowMapPass(), none, params, s.Factors));
  MRGI_TEST_CHECK(gpu->GetNumberOfDraws() == 0);
  vtkNew<vtkFloatArray> factors;
  MRGI_TEST_CHECK(vtkMRGIDirectShadows::ReadFactors(s.Window, s.Factors, factors));
  const int texW = s.Factors->GetWidth();
  for (int y = 0; y < s.Frame.Viewport[3]; ++y)
  {
    for (int x = 0; x < s.Frame.Viewport[2]; ++x)
    {
      const float* g = factors->GetPointer(
        4 * (static_cast<size_t>(s.Frame.Viewport[1] + y) * texW + s.Frame.Viewport[0] + x));
      MRGI_TEST_CHECK(g[0] == 1.0f && g[1] == 1.0f && g[2] == 1.0f && g[3] == 1.0f);
    }
  }
  // The depth maps are derived once per RSM render: not again for a frame
  // with nothing changed, again once the light moves.
  MRGI_TEST_CHECK(gpu->GetNumberOfDepthUpdates() == 1);
  MRGI_TEST_CHECK(gpu->Compute(s.Frame, s.Pass->GetReflectiveShadowMapPass(), slots, params, s.Factors));
  MRGI_TEST_CHECK(gpu->GetNumberOfDepthUpdates() == 1);
  s.Window->Render();
  MRGI_TEST_CHECK(gpu->Compute(s.Frame, s.Pass->GetReflectiveShadowMapPass(), slots, params, s.Factors));
  MRGI_TEST_CHECK(gpu->GetNumberOfDepthUpdates() == 1);
  vtkLight* light = vtkLight::SafeDownCast(s.Renderer->GetLights()->GetItemAsObject(0));
  MRGI_TEST_CHECK(light);
  double p[3];
  light->GetPosition(p);
  light->SetPosition(p[0] + 60.0, p[1] - 20.0, p[2]);
  s.Window->Render();
  MRGI_TEST_CHECK(gpu->Compute(s.Frame, s.Pass->GetReflectiveShadowMapPass(), slots, params, s.Factors));
  MRGI_TEST_CHECK(gpu->GetNumberOfDepthUpdates() == 2);
  gpu->ReleaseGraphicsResources(s.Window);
  Compare(s, slots, MRGI_DIRECT_SHADOW_SOFT, "tile soft, light moved");
}

void BadInput()
{
  Scene s;
  Build(s, "cornell-spot", false, 64, 48, 64);
  vtkNew<vtkMRGIDirectShadows> gpu;
  mrgi_direct_shadow_params params;
  mrgi_direct_shadow_params_default(&params);
  const int slots[MRGI_SHADOW_SLOTS] = { 0, -1 };
  vtkMRGIReflectiveShadowMapPass* rsm = s.Pass->GetReflectiveShadowMapPass();
  params.samples_side = 0;
  MRGI_TEST_CHECK(!gpu->Compute(s.Frame, rsm, slots, params, s.Factors));
  mrgi_direct_shadow_params_default(&params);
  MRGI_TEST_CHECK(!gpu->Compute(s.Frame, nullptr, slots, params, s.Factors));
  MRGI_TEST_CHECK(!gpu->Compute(s.Frame, rsm, slots, params, nullptr));
  vtkMRGIFrameContext big = s.Frame;
  big.Viewport[2] = 10000;
  MRGI_TEST_CHECK(!gpu->Compute(big, rsm, slots, params, s.Factors));
  MRGI_TEST_CHECK(gpu->Compute(s.Frame, rsm, slots, params, s.Factors));
  gpu->ReleaseGraphicsResources(s.Window);
}

int Bench()
{
  for (int size : { 256, 1024 })
  {
    Scene s;
    Build(s, "cornell-spot", false, size, size, 256);
    vtkMRGIReflectiveShadowMapPass* rsm = s.Pass->GetReflectiveShadowMapPass();
    const int slots[MRGI_SHADOW_SLOTS] = { 0, -1 };
    vtkNew<vtkMRGIDirectShadows> gpu;
    struct Setting
    {
      const char* Name;
      int Mode, Side;
    } settings[] = { { "hard", MRGI_DIRECT_SHADOW_HARD, 1 },
      { "soft-64", MRGI_DIRECT_SHADOW_SOFT, 8 }, { "soft-196", MRGI_DIRECT_SHADOW_SOFT, 14 } };
    for (const Setting& setting : settings)
    {
      mrgi_direct_shadow_params params;
      mrgi_direct_shadow_params_default(&params);
      params.mode = setting.Mode;
      params.samples_side = setting.Side;
      params.light_radius = 10.0;
      // Wall time around the call, and the stage's own timer event
      // ("MRGI shadows") when the driver has timer queries.
      vtkRenderTimerLog* log = s.Window->GetRenderTimer();
      const bool timed = log && log->IsSupported();
      std::vector<double> ms, stage;
      for (int k = 0; k < 6; ++k)
      {
        s.Frame.Window->WaitForCompletion();
        if (timed)
        {
          log->SetLoggingEnabled(true);
          log->MarkFrame();
        }
        s.Frame.Timer = timed ? log : nullptr;
        const auto start = std::chrono::steady_clock::now();
        MRGI_TEST_CHECK(gpu->Compute(s.Frame, rsm, slots, params, s.Factors));
        s.Frame.Window->WaitForCompletion();
        const auto end = std::chrono::steady_clock::now();
        s.Frame.Timer = nullptr;
        if (timed)
        {
          log->MarkFrame();
          s.Frame.Window->WaitForCompletion();
        }
        while (timed && log->FrameReady())
        {
          for (const vtkRenderTimerLog::Event& event : log->PopFirstReadyFrame().Events)
          {
            if (event.Name == "MRGI shadows" && k > 0)
            {
              stage.push_back(event.ElapsedTimeMilliseconds());
            }
          }
        }
        if (k > 0) // the first builds the program
        {
          ms.push_back(std::chrono::duration<double, std::milli>(end - start).count());
        }
      }
      std::sort(ms.begin(), ms.end());
      std::sort(stage.begin(), stage.end());
      std::printf("bench %dx%d %s: %.2f ms wall, stage timer %.2f ms (medians of %zu, %zu)\n",
        size, size, setting.Name, ms[ms.size() / 2], stage.empty() ? -1.0 : stage[stage.size() / 2],
        ms.size(), stage.size());
    }
    gpu->ReleaseGraphicsResources(s.Window);
  }
  return 0;
}
}

// RGB of a float image (3 or 4 components) over its whole extent, as an mrgi_image.
void ToImage(vtkImageData* in, mrgi_image& out)
{
  int dims[3];
  in->GetDimensions(dims);
  const int c = in->GetNumberOfScalarComponents();
  MRGI_TEST_CHECK(mrgi_image_create(&out, dims[0], dims[1], 3, nullptr) == MRGI_OK);
  const float* p = static_cast<const float*>(in->GetScalarPointer());
  for (size_t t = 0; t < static_cast<size_t>(dims[0]) * dims[1]; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      out.pixels[3 * t + k] = p[c * t + k];
    }
  }
}

// Relative RMS of 4 x 4 box averages (the metric).
double BoxRelativeRMS(const mrgi_image& test, const mrgi_image& reference)
{
  mrgi_image a{}, b{};
  MRGI_TEST_CHECK(mrgi_box_downsample(&test, 4, &a, nullptr) == MRGI_OK);
  MRGI_TEST_CHECK(mrgi_box_downsample(&reference, 4, &b, nullptr) == MRGI_OK);
  mrgi_metrics m;
  MRGI_TEST_CHECK(mrgi_metrics_compare(&a, &b, nullptr, 1.0, &m, nullptr) == MRGI_OK);
  mrgi_image_destroy(&a);
  mrgi_image_destroy(&b);
  return m.relative_rms;
}

// VTK's direct light times the slot-0 factor against the ground truth's
// direct light with shadows, 256 x 256, for scenes with one light (the
// factor then scales that light's whole contribution; the Cornell
// materials have no ambient term). Not run by ctest.
int Fidelity()
{
  for (const char* name : { "cornell-spot", "cornell" })
  {
    Scene s;
    Build(s, name, false, 256, 256, 256);
    MRGI_TEST_CHECK(s.Renderer->GetLights()->GetNumberOfItems() == 1);
    vtkNew<vtkImageData> color, indirect;
    MRGI_TEST_CHECK(s.Pass->GetColorBuffer(s.Window, color) && s.Pass->GetIndirectBuffer(s.Window, indirect));
    mrgi_image direct{}, added{};
    ToImage(color, direct);
    ToImage(indirect, added);
    for (size_t i = 0; i < static_cast<size_t>(direct.width) * direct.height * 3; ++i)
    {
      direct.pixels[i] -= added.pixels[i]; // VTK's own direct light
    }
    mrgi_image truth[2] = { {}, {} };
    for (int shadows = 0; shadows < 2; ++shadows)
    {
      vtkNew<vtkMRGIReferenceRenderer> reference;
      reference->SetShadows(shadows == 1);
      reference->SetIndirectSamples(0);
      reference->SetMaxPasses(16);
      reference->SetTargetRelativeError(0.0);
      MRGI_TEST_CHECK(reference->Render(s.Renderer));
      ToImage(reference->GetDirectImage(), truth[shadows]);
    }
    MRGI_TEST_CHECK(truth[1].width == direct.width && truth[1].height == direct.height);
    std::printf("%s: VTK direct vs truth with shadows %.4f, without %.4f\n", name,
      BoxRelativeRMS(direct, truth[1]), BoxRelativeRMS(direct, truth[0]));
    double bounds[6];
    s.Renderer->ComputeVisiblePropBounds(bounds);
    const double sceneRadius = 0.5 *
      std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
        (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
        (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
    struct Setting
    {
      const char* Name;
      int Mode, Side;
      double Radius; // fraction of the scene radius
    } settings[] = { { "hard", MRGI_DIRECT_SHADOW_HARD, 1, 0.0 },
      { "soft-64 r=0.5%", MRGI_DIRECT_SHADOW_SOFT, 8, 0.005 },
      { "soft-64 r=1%", MRGI_DIRECT_SHADOW_SOFT, 8, 0.01 },
      { "soft-196 r=1%", MRGI_DIRECT_SHADOW_SOFT, 14, 0.01 },
      { "soft-64 r=2%", MRGI_DIRECT_SHADOW_SOFT, 8, 0.02 } };
    const int slots[MRGI_SHADOW_SLOTS] = { 0, -1 };
    vtkNew<vtkMRGIDirectShadows> gpu;
    const int x0 = s.Frame.Viewport[0], y0 = s.Frame.Viewport[1];
    for (const Setting& setting : settings)
    {
      mrgi_direct_shadow_params params;
      mrgi_direct_shadow_params_default(&params);
      params.mode = setting.Mode;
      params.samples_side = setting.Side;
      params.light_radius = setting.Radius * sceneRadius;
      MRGI_TEST_CHECK(gpu->Compute(s.Frame, s.Pass->GetReflectiveShadowMapPass(), slots, params, s.Factors));
      vtkNew<vtkFloatArray> factors;
      MRGI_TEST_CHECK(vtkMRGIDirectShadows::ReadFactors(s.Window, s.Factors, factors));
      const int texW = s.Factors->GetWidth();
      mrgi_image shadowed{};
      MRGI_TEST_CHECK(mrgi_image_create(&shadowed, direct.width, direct.height, 3, nullptr) == MRGI_OK);
      for (int y = 0; y < direct.height; ++y)
      {
        for (int x = 0; x < direct.width; ++x)
        {
          const float f = factors->GetValue(4 * ((static_cast<vtkIdType>(y0 + y)) * texW + x0 + x));
          for (int k = 0; k < 3; ++k)
          {
            const size_t i = 3 * (static_cast<size_t>(y) * direct.width + x) + k;
            shadowed.pixels[i] = f * direct.pixels[i];
          }
        }
      }
      std::printf("%s: VTK direct x factor (%s) vs truth with shadows %.4f\n", name, setting.Name,
        BoxRelativeRMS(shadowed, truth[1]));
      mrgi_image_destroy(&shadowed);
    }
    gpu->ReleaseGraphicsResources(s.Window);
    mrgi_image_destroy(&direct);
    mrgi_image_destroy(&added);
    mrgi_image_destroy(&truth[0]);
    mrgi_image_destroy(&truth[1]);
  }
  return 0;
}

int main(int argc, char* argv[])
{
  if (argc > 1 && std::strcmp(argv[1], "--bench") == 0)
  {
    return Bench();
  }
  if (argc > 1 && std::strcmp(argv[1], "--fidelity") == 0)
  {
    return Fidelity();
  }
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(SpotAndDirectional), MRGI_TEST_CASE(PointCube), MRGI_TEST_CASE(SubViewport),
      MRGI_TEST_CASE(BadInput) });
}
