// Direct shadows (and SSAO) of vtkMRGIPass under the compositions that
// users of vtkShadowMapPass / vtkSSAOPass report broken (issue 14,
// "Composition"): non-square windows, a viewport that is a sub-tile of
// the window, parallel projection, depth peeling with a translucent prop,
// a second renderer layer, renderer->UseFXAAOn(), PBR actors, two shadowed
// lights plus a third one.
//
// The scene has a shadow computable by hand: a spot light at (0, 5, 0)
// aiming down, a 1 x 0.1 x 1 plate at heights 2..2.1 over the floor y = 0,
// so the plate's shadow on the floor is the square |x|, |z| <= 0.5 * 5 /
// 2.9 = 0.862 (0.833 for the plate's bottom face). The camera sits below
// the plate (y = 1.8), so the plate never hides the floor from it. Floor
// points on a 0.1 grid are projected through the renderer
// (vtkRenderer::WorldToDisplay) to window pixels:
// - umbra points (max(|x|, |z|) <= 0.72) must be dark: at most a quarter
//   of the same pixel in the render with DirectShadows Off;
// - lit points (max(|x|, |z|) >= 1.0) must equal that render's pixel.
// A shadow stretched or shifted by a wrong aspect or viewport puts lit
// points in the shadow or umbra points in the light. A small box on the
// floor gives SSAO a crease; points near it are left out.
//
// LightRadius: the automatic light radius (ShadowLightRadius 0) is
// MRGI_SHADOW_AUTO_LIGHT_RADIUS of the visible props' bounding radius,
// computed again only when the reflective shadow maps are re-rendered
// (an actor moved), not for an unchanged frame nor a camera move.
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGIShadowedDirectLight.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include "mrgi_direct_shadow.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
// The analytic shadow of the plate under light A (see the header comment).
const double kUmbra = 0.72; // inside: full shadow (edge at 0.833..0.862)
const double kLit = 1.0;    // outside: fully lit (penumbra well inside)

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderStepsPass> Steps;
  vtkNew<vtkMRGIPass> Pass;
  vtkSmartPointer<vtkLight> Light;
  std::vector<vtkSmartPointer<vtkActor>> Actors;

  Scene(int width, int height, bool pbr = false)
  {
    this->Window = mrgitest::HeadlessWindow(width, height);
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->AutomaticLightCreationOff();
    this->Renderer->SetBackground(0.1, 0.1, 0.3);
    vtkNew<vtkPlaneSource> floor;
    floor->SetOrigin(-2, 0, -2);
    floor->SetPoint1(-2, 0, 2);
    floor->SetPoint2(2, 0, -2);
    floor->SetResolution(16, 16);
    this->Add(floor, 0.8, 0.8, 0.8, pbr);
    vtkNew<vtkCubeSource> plate;
    plate->SetBounds(-0.5, 0.5, 2.0, 2.1, -0.5, 0.5);
    this->Add(plate, 0.9, 0.5, 0.3, pbr);
    vtkNew<vtkCubeSource> box;
    box->SetBounds(1.25, 1.75, 0, 0.5, -1.75, -1.25);
    this->Add(box, 0.3, 0.6, 0.9, pbr);
    this->Light = this->AddLight(0, 5, 0, 0, 0, 0, true, 1.0);
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetPosition(0, 1.8, 5);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(40);
    this->Renderer->ResetCameraClippingRange();
    this->Pass->SetDelegatePass(this->Steps);
    // Direct light only: the shadowed pixels are then exactly the ambient.
    this->Pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
    this->Renderer->SetPass(this->Pass);
  }
  ~Scene()
  {
    this->Pass->ReleaseGraphicsResources(this->Window);
    this->Renderer->SetPass(nullptr);
    this->Window->Finalize();
  }
  vtkActor* Add(vtkAlgorithm* source, double r, double g, double b, bool pbr)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(source->GetOutputPort());
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(r, g, b);
    actor->GetProperty()->SetAmbient(0.05);
    if (pbr)
    {
      actor->GetProperty()->SetInterpolationToPBR();
      actor->GetProperty()->SetMetallic(0.2);
      actor->GetProperty()->SetRoughness(0.5);
    }
    this->Renderer->AddActor(actor);
    this->Actors.push_back(actor);
    return actor;
  }
  vtkSmartPointer<vtkLight> AddLight(
    double x, double y, double z, double fx, double fy, double fz, bool positional, double intensity)
  {
    auto light = vtkSmartPointer<vtkLight>::New();
    light->SetLightTypeToSceneLight();
    light->SetPosition(x, y, z);
    light->SetFocalPoint(fx, fy, fz);
    light->SetPositional(positional);
    light->SetConeAngle(45);
    light->SetIntensity(intensity);
    this->Renderer->AddLight(light);
    return light;
  }
  vtkSmartPointer<vtkImageData> Render(int mode)
  {
    this->Pass->SetDirectShadows(mode);
    this->Window->Render();
    return mrgitest::GrabRGB(this->Window);
  }
};

// A floor point of the 0.1 grid and its window pixel.
struct Sample
{
  double X, Z;
  int Pixel[2];
};

// The grid's floor points that land inside the renderer's viewport (2
// pixels from its border) and away from the small box's shadow and crease.
std::vector<Sample> VisibleSamples(vtkRenderer* renderer)
{
  std::vector<Sample> samples;
  const int* size = renderer->GetRenderWindow()->GetSize();
  const double* vp = renderer->GetViewport();
  const double x0 = vp[0] * size[0] + 2, x1 = vp[2] * size[0] - 3;
  const double y0 = vp[1] * size[1] + 2, y1 = vp[3] * size[1] - 3;
  for (int i = -19; i <= 19; ++i)
  {
    for (int j = -19; j <= 19; ++j)
    {
      const double x = 0.1 * i, z = 0.1 * j;
      if (std::fabs(x - 1.5) < 0.8 && std::fabs(z + 1.5) < 0.8)
      {
        continue;
      }
      renderer->SetWorldPoint(x, 0, z, 1);
      renderer->WorldToDisplay();
      const double* d = renderer->GetDisplayPoint();
      if (d[0] < x0 || d[0] > x1 || d[1] < y0 || d[1] > y1)
      {
        continue;
      }
      samples.push_back({ x, z, { static_cast<int>(d[0]), static_cast<int>(d[1]) } });
    }
  }
  return samples;
}

double Channel(vtkImageData* image, const int pixel[2], int c)
{
  int dims[3];
  image->GetDimensions(dims);
  return image->GetPointData()->GetScalars()->GetComponent(
    static_cast<vtkIdType>(pixel[1]) * dims[0] + pixel[0], c);
}

double Sum(vtkImageData* image, const int pixel[2])
{
  return Channel(image, pixel, 0) + Channel(image, pixel, 1) + Channel(image, pixel, 2);
}

// Umbra points dark against `unshadowed`, lit points within `tolerance`
// (per channel, of 255) of it. `skip` (optional, window-sized) marks
// pixels that another prop covers. Fails the test unless enough of both
// kinds were visible.
void ExpectShadow(const char* what, vtkRenderer* renderer, vtkImageData* shadowed,
  vtkImageData* unshadowed, double tolerance, const std::vector<char>* skip = nullptr)
{
  int umbra = 0, lit = 0, badUmbra = 0, badLit = 0;
  double worstLit = 0;
  const int width = renderer->GetRenderWindow()->GetSize()[0];
  for (const Sample& s : VisibleSamples(renderer))
  {
    if (skip && (*skip)[static_cast<size_t>(s.Pixel[1]) * width + s.Pixel[0]])
    {
      continue;
    }
    const double r = std::max(std::fabs(s.X), std::fabs(s.Z));
    if (r <= kUmbra)
    {
      ++umbra;
      const double on = Sum(shadowed, s.Pixel), off = Sum(unshadowed, s.Pixel);
      // The spot light reaches the floor there, and the shadow removes it.
      if (!(off > 60 && on <= 0.25 * off + 3))
      {
        if (++badUmbra <= 3)
        {
          std::fprintf(stderr, "%s: umbra point (%.1f, %.1f) at pixel (%d, %d): %.0f vs %.0f off\n",
            what, s.X, s.Z, s.Pixel[0], s.Pixel[1], on, off);
        }
      }
    }
    else if (r >= kLit)
    {
      ++lit;
      double d = 0;
      for (int c = 0; c < 3; ++c)
      {
        d = std::max(d, std::fabs(Channel(shadowed, s.Pixel, c) - Channel(unshadowed, s.Pixel, c)));
      }
      worstLit = std::max(worstLit, d);
      if (d > tolerance && ++badLit <= 3)
      {
        std::fprintf(stderr, "%s: lit point (%.1f, %.1f) at pixel (%d, %d) differs by %.0f\n", what,
          s.X, s.Z, s.Pixel[0], s.Pixel[1], d);
      }
    }
  }
  std::printf("%s: %d umbra points (%d wrong), %d lit points (%d wrong, largest difference %.0f)\n",
    what, umbra, badUmbra, lit, badLit, worstLit);
  MRGI_TEST_CHECK(umbra >= 40);
  MRGI_TEST_CHECK(lit >= 100);
  MRGI_TEST_CHECK(badUmbra == 0);
  MRGI_TEST_CHECK(badLit == 0);
}

// Number of pixels whose channels differ by more than `step` (of 255).
int Differ(vtkImageData* a, vtkImageData* b, double step, std::vector<char>* mask = nullptr)
{
  vtkDataArray* pa = a->GetPointData()->GetScalars();
  vtkDataArray* pb = b->GetPointData()->GetScalars();
  if (mask)
  {
    mask->assign(static_cast<size_t>(pa->GetNumberOfTuples()), 0);
  }
  int n = 0;
  for (vtkIdType p = 0; p < pa->GetNumberOfTuples(); ++p)
  {
    bool differs = false;
    for (int c = 0; c < 3; ++c)
    {
      differs = differs || std::fabs(pa->GetComponent(p, c) - pb->GetComponent(p, c)) > step;
    }
    n += differs;
    if (mask && differs)
    {
      (*mask)[static_cast<size_t>(p)] = 1;
    }
  }
  return n;
}

// Every pixel whose shadow factors are all 1 is the DirectShadows Off
// render's pixel, bit for bit (the design's guarantee). Full-window
// renderers only (the factor buffer is the viewport's).
void ExpectLitPixelsExact(const char* what, Scene& s, vtkImageData* shadowed, vtkImageData* off)
{
  vtkNew<vtkImageData> factors;
  MRGI_TEST_CHECK(s.Pass->GetShadowFactorBuffer(s.Window, factors));
  int dims[3];
  factors->GetDimensions(dims);
  const int* size = s.Window->GetSize();
  MRGI_TEST_CHECK(dims[0] == size[0] && dims[1] == size[1]);
  const float* f =
    vtkFloatArray::SafeDownCast(factors->GetPointData()->GetScalars())->GetPointer(0);
  vtkDataArray* a = shadowed->GetPointData()->GetScalars();
  vtkDataArray* b = off->GetPointData()->GetScalars();
  int litPixels = 0, differ = 0, shadowedPixels = 0;
  for (vtkIdType p = 0; p < a->GetNumberOfTuples(); ++p)
  {
    if (f[4 * p] < 1.0f || f[4 * p + 1] < 1.0f)
    {
      ++shadowedPixels;
      continue;
    }
    ++litPixels;
    for (int c = 0; c < 3; ++c)
    {
      differ += a->GetComponent(p, c) != b->GetComponent(p, c);
    }
  }
  std::printf("%s: %d pixels lit by every slot (%d channels differ from Off), %d shadowed\n", what,
    litPixels, differ, shadowedPixels);
  MRGI_TEST_CHECK(litPixels > size[0] * size[1] / 4);
  MRGI_TEST_CHECK(shadowedPixels > 100);
  MRGI_TEST_CHECK(differ == 0);
}

// Non-square windows, hard and soft: the shadow where geometry puts it.
// With SSAO on as well: shadows still right, and SSAO darkens the box's
// crease.
void NonSquare()
{
  const int sizes[2][2] = { { 320, 160 }, { 160, 320 } };
  for (const auto& size : sizes)
  {
    Scene s(size[0], size[1]);
    auto off = s.Render(vtkMRGIPass::DirectShadowsOff);
    for (int mode : { vtkMRGIPass::DirectShadowsHard, vtkMRGIPass::DirectShadowsSoft })
    {
      char what[64];
      std::snprintf(what, sizeof(what), "%dx%d %s", size[0], size[1], mode == 1 ? "hard" : "soft");
      auto on = s.Render(mode);
      ExpectShadow(what, s.Renderer, on, off, 0);
      ExpectLitPixelsExact(what, s, on, off);
    }
    auto soft = s.Render(vtkMRGIPass::DirectShadowsSoft);
    s.Pass->SSAOOn();
    auto aoOff = s.Render(vtkMRGIPass::DirectShadowsOff);
    auto aoSoft = s.Render(vtkMRGIPass::DirectShadowsSoft);
    // SSAO's darkening is multiplicative: flat floor away from the box keeps
    // its colour, so the lit points still match within a step of rounding.
    ExpectShadow("ssao + soft", s.Renderer, aoSoft, aoOff, 1);
    const int occluded = Differ(soft, aoSoft, 4);
    std::printf("ssao: %d pixels differ from soft shadows without SSAO\n", occluded);
    MRGI_TEST_CHECK(occluded >= 30);
  }
}

// A renderer viewport that is a sub-tile of the window, and parallel
// projection: the pixels outside the viewport are untouched.
void Viewport()
{
  for (bool parallel : { false, true })
  {
    Scene s(300, 200);
    s.Renderer->SetViewport(0.4, 0.1, 0.95, 0.8);
    if (parallel)
    {
      s.Renderer->GetActiveCamera()->ParallelProjectionOn();
      s.Renderer->GetActiveCamera()->SetParallelScale(1.3);
    }
    auto off = s.Render(vtkMRGIPass::DirectShadowsOff);
    for (int mode : { vtkMRGIPass::DirectShadowsHard, vtkMRGIPass::DirectShadowsSoft })
    {
      auto on = s.Render(mode);
      ExpectShadow(parallel ? "sub-tile, parallel" : "sub-tile, perspective", s.Renderer, on, off, 0);
      // Outside the viewport: the same pixels as the Off render.
      vtkDataArray* a = on->GetPointData()->GetScalars();
      vtkDataArray* b = off->GetPointData()->GetScalars();
      int outside = 0, changed = 0;
      for (int y = 0; y < 200; ++y)
      {
        for (int x = 0; x < 300; ++x)
        {
          if (x >= 120 && x < 285 && y >= 20 && y < 160)
          {
            continue;
          }
          ++outside;
          const vtkIdType p = static_cast<vtkIdType>(y) * 300 + x;
          for (int c = 0; c < 3; ++c)
          {
            changed += a->GetComponent(p, c) != b->GetComponent(p, c);
          }
        }
      }
      MRGI_TEST_CHECK(outside > 20000);
      MRGI_TEST_CHECK(changed == 0);
    }
  }
}

// A sub-tile viewport renders what a window of the tile's size renders:
// shadows and SSAO land on the same pixels, with nothing stretched or
// shifted (the tile is 165 x 140 pixels of a 300 x 200 window).
void TileEqualsWindow()
{
  for (bool ssao : { false, true })
  {
    vtkSmartPointer<vtkImageData> images[2];
    for (int tiled = 0; tiled < 2; ++tiled)
    {
      Scene s(tiled ? 300 : 165, tiled ? 200 : 140);
      if (tiled)
      {
        s.Renderer->SetViewport(0.4, 0.1, 0.95, 0.8);
      }
      s.Pass->SetSSAO(ssao);
      images[tiled] = s.Render(vtkMRGIPass::DirectShadowsSoft);
      if (!tiled)
      {
        // Not an empty comparison: the shadow is in the window's image.
        MRGI_TEST_CHECK(Differ(images[0], s.Render(vtkMRGIPass::DirectShadowsOff), 8) > 500);
      }
    }
    vtkDataArray* a = images[0]->GetPointData()->GetScalars();
    vtkDataArray* b = images[1]->GetPointData()->GetScalars();
    double worst = 0;
    int differ = 0;
    for (int y = 0; y < 140; ++y)
    {
      for (int x = 0; x < 165; ++x)
      {
        const vtkIdType p = static_cast<vtkIdType>(y) * 165 + x;
        const vtkIdType q = static_cast<vtkIdType>(y + 20) * 300 + x + 120;
        double d = 0;
        for (int c = 0; c < 3; ++c)
        {
          d = std::max(d, std::fabs(a->GetComponent(p, c) - b->GetComponent(q, c)));
        }
        worst = std::max(worst, d);
        differ += d > 1;
      }
    }
    std::printf("tile vs window%s: %d pixels differ by more than 1, largest difference %.0f\n",
      ssao ? " (SSAO on)" : "", differ, worst);
    MRGI_TEST_CHECK(differ == 0);
  }
}

// PBR receivers and casters: shadowed where expected, lit pixels VTK's own.
void PBR()
{
  Scene s(240, 180, true);
  auto off = s.Render(vtkMRGIPass::DirectShadowsOff);
  for (int mode : { vtkMRGIPass::DirectShadowsHard, vtkMRGIPass::DirectShadowsSoft })
  {
    auto on = s.Render(mode);
    ExpectShadow(mode == 1 ? "pbr hard" : "pbr soft", s.Renderer, on, off, 0);
    ExpectLitPixelsExact(mode == 1 ? "pbr hard" : "pbr soft", s, on, off);
  }
}

// Depth peeling with a translucent sphere in front: where it does not
// cover the floor the shadow is the opaque one; where it does, it is
// blended (neither absent nor opaque). With and without SSAO.
void DepthPeelingWith(bool ssao)
{
  std::printf("SSAO %s\n", ssao ? "on" : "off");
  Scene s(240, 180);
  s.Pass->SetSSAO(ssao);
  s.Renderer->SetUseDepthPeeling(1);
  s.Renderer->SetMaximumNumberOfPeels(4);
  auto without = s.Render(vtkMRGIPass::DirectShadowsSoft);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(-0.3, 0.5, 1.0);
  sphere->SetRadius(0.45);
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(24);
  vtkActor* glass = s.Add(sphere, 1.0, 0.1, 0.1, false);
  glass->GetProperty()->SetOpacity(0.4);
  auto off = s.Render(vtkMRGIPass::DirectShadowsOff);
  auto on = s.Render(vtkMRGIPass::DirectShadowsSoft);
  MRGI_TEST_CHECK(s.Renderer->GetLastRenderingUsedDepthPeeling());
  std::vector<char> covered;
  const int coveredPixels = Differ(without, on, 2, &covered);
  // Grow the covered mask by a pixel (anti-aliased, blended rims).
  std::vector<char> grown(covered);
  for (int y = 1; y < 179; ++y)
  {
    for (int x = 1; x < 239; ++x)
    {
      for (int d = -1; d <= 1; ++d)
      {
        grown[static_cast<size_t>(y) * 240 + x] |= covered[static_cast<size_t>(y + d) * 240 + x] |
          covered[static_cast<size_t>(y) * 240 + x + d];
      }
    }
  }
  ExpectShadow("depth peeling", s.Renderer, on, off, 0, &grown);
  // The sphere is drawn, and blended: its pixels differ from the opaque
  // sphere's as much as from the floor without it.
  glass->GetProperty()->SetOpacity(1.0);
  auto opaque = s.Render(vtkMRGIPass::DirectShadowsSoft);
  double fromFloor = 0, fromOpaque = 0;
  vtkDataArray* a = on->GetPointData()->GetScalars();
  for (size_t p = 0; p < covered.size(); ++p)
  {
    if (!covered[p])
    {
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      const double v = a->GetComponent(static_cast<vtkIdType>(p), c);
      fromFloor += std::fabs(v - without->GetPointData()->GetScalars()->GetComponent(p, c));
      fromOpaque += std::fabs(v - opaque->GetPointData()->GetScalars()->GetComponent(p, c));
    }
  }
  fromFloor /= 3.0 * std::max(coveredPixels, 1);
  fromOpaque /= 3.0 * std::max(coveredPixels, 1);
  std::printf("depth peeling: %d pixels covered by the translucent sphere; mean difference from "
              "the floor %.1f, from the opaque sphere %.1f\n",
    coveredPixels, fromFloor, fromOpaque);
  MRGI_TEST_CHECK(coveredPixels > 500);
  MRGI_TEST_CHECK(fromFloor > 10);
  MRGI_TEST_CHECK(fromOpaque > 10);
}

// A second renderer on layer 1 (an orientation-marker-like corner): its
// pixels are those of the same overlay over a plain VTK renderer; the main
// layer's shadow is there. SSAO on too.
void SecondLayer()
{
  Scene s(240, 180);
  s.Window->SetNumberOfLayers(2);
  vtkNew<vtkRenderer> overlay;
  overlay->SetLayer(1);
  overlay->SetViewport(0, 0, 0.3, 0.4);
  vtkNew<vtkSphereSource> ball;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(ball->GetOutputPort());
  vtkNew<vtkActor> marker;
  marker->SetMapper(mapper);
  marker->GetProperty()->SetColor(0.1, 0.9, 0.2);
  overlay->AddActor(marker);
  overlay->ResetCamera();
  s.Window->AddRenderer(overlay);
  s.Pass->SSAOOn();
  auto off = s.Render(vtkMRGIPass::DirectShadowsOff);
  auto on = s.Render(vtkMRGIPass::DirectShadowsSoft);
  std::vector<char> inOverlay(static_cast<size_t>(240) * 180, 0);
  for (int y = 0; y < 72; ++y)
  {
    for (int x = 0; x < 72; ++x)
    {
      inOverlay[static_cast<size_t>(y) * 240 + x] = 1;
    }
  }
  ExpectShadow("second layer", s.Renderer, on, off, 1, &inOverlay);
  // The overlay over a renderer without passes.
  s.Renderer->SetPass(nullptr);
  s.Window->Render();
  auto plain = mrgitest::GrabRGB(s.Window);
  int marked = 0, changed = 0;
  vtkDataArray* a = on->GetPointData()->GetScalars();
  vtkDataArray* b = plain->GetPointData()->GetScalars();
  for (int y = 0; y < 72; ++y)
  {
    for (int x = 0; x < 72; ++x)
    {
      const vtkIdType p = static_cast<vtkIdType>(y) * 240 + x;
      // The marker's pixels: green dominates (the floor is grey, the
      // background blue).
      if (b->GetComponent(p, 1) > b->GetComponent(p, 0) + 40 &&
        b->GetComponent(p, 1) > b->GetComponent(p, 2) + 40)
      {
        ++marked;
        for (int c = 0; c < 3; ++c)
        {
          changed += a->GetComponent(p, c) != b->GetComponent(p, c);
        }
      }
    }
  }
  std::printf("second layer: %d marker pixels, %d channels differ from the plain render\n", marked,
    changed);
  MRGI_TEST_CHECK(marked > 300);
  MRGI_TEST_CHECK(changed == 0);
}

// renderer->UseFXAAOn(): the shadow is there and its interior (and the lit
// floor) equals the render without FXAA; edges are smoothed. With and
// without SSAO.
void FXAAWith(bool ssao)
{
  std::printf("SSAO %s\n", ssao ? "on" : "off");
  Scene s(240, 180);
  s.Pass->SetSSAO(ssao);
  // Unblurred SSAO speckles the flat floor at this grazing angle (as
  // vtkSSAOPass does), and FXAA rightly smooths speckle: blur it first.
  s.Pass->SetSSAOBlur(ssao);
  auto plainOn = s.Render(vtkMRGIPass::DirectShadowsSoft);
  s.Renderer->UseFXAAOn();
  auto off = s.Render(vtkMRGIPass::DirectShadowsOff);
  auto on = s.Render(vtkMRGIPass::DirectShadowsSoft);
  ExpectShadow("fxaa", s.Renderer, on, off, 1);
  // Interior of the shadow and lit floor: FXAA leaves flat areas alone.
  int umbra = 0;
  double worst = 0;
  for (const Sample& p : VisibleSamples(s.Renderer))
  {
    const double r = std::max(std::fabs(p.X), std::fabs(p.Z));
    // Points more than a few pixels inside the floor's outline: FXAA
    // rightly smooths the floor's far edge against the background.
    if (r <= kUmbra || (r >= kLit && r <= 1.6))
    {
      umbra += r <= kUmbra;
      for (int c = 0; c < 3; ++c)
      {
        const double d = std::fabs(Channel(on, p.Pixel, c) - Channel(plainOn, p.Pixel, c));
        if (d > 2)
        {
          std::fprintf(stderr, "fxaa changed (%.1f, %.1f) at pixel (%d, %d) by %.0f\n", p.X, p.Z,
            p.Pixel[0], p.Pixel[1], d);
        }
        worst = std::max(worst, d);
      }
    }
  }
  const int edges = Differ(plainOn, on, 2);
  std::printf("fxaa: %d pixels differ from the render without FXAA; at the %d umbra and the lit "
              "points at most %.0f\n",
    edges, umbra, worst);
  MRGI_TEST_CHECK(edges >= 20);
  MRGI_TEST_CHECK(worst <= 2);
}

// Both with SSAO off and on.
void DepthPeeling()
{
  DepthPeelingWith(false);
  DepthPeelingWith(true);
}

void FXAA()
{
  FXAAWith(false);
  FXAAWith(true);
}

// Two shadowed lights (slots 0 and 1) and a third one: each slot's factor
// is 0 in its own light's umbra and 1 where that light reaches; the third
// light is unshadowed (the pixels in both umbrae are its light alone), with
// one warning over several frames.
void Lights()
{
  Scene s(240, 180);
  // Light B straight above x = 1.5: the plate's shadow is x in
  // [-1.948, -0.167], |z| <= 0.862.
  vtkSmartPointer<vtkLight> b = s.AddLight(1.5, 5, 0, 1.5, 0, 0, true, 0.7);
  vtkSmartPointer<vtkLight> c = s.AddLight(0, 3, 6, 0, 0, 0, false, 0.3);
  vtkNew<mrgitest::ErrorCatcher> warnings;
  s.Pass->AddObserver(vtkCommand::WarningEvent, warnings);
  auto on = s.Render(vtkMRGIPass::DirectShadowsSoft);
  on = s.Render(vtkMRGIPass::DirectShadowsSoft);
  MRGI_TEST_CHECK(warnings->Count == 1);
  MRGI_TEST_CHECK(warnings->Last.find("first 2 switched-on lights only") != std::string::npos);
  vtkNew<vtkImageData> factors;
  MRGI_TEST_CHECK(s.Pass->GetShadowFactorBuffer(s.Window, factors));
  const float* f =
    vtkFloatArray::SafeDownCast(factors->GetPointData()->GetScalars())->GetPointer(0);
  s.Light->SetIntensity(0);
  b->SetIntensity(0);
  auto thirdOnly = s.Render(vtkMRGIPass::DirectShadowsOff);
  int checked[2] = { 0, 0 }, bad = 0, both = 0;
  for (const Sample& p : VisibleSamples(s.Renderer))
  {
    const float* fp = f + 4 * (static_cast<size_t>(p.Pixel[1]) * 240 + p.Pixel[0]);
    const double ra = std::max(std::fabs(p.X), std::fabs(p.Z));
    const bool umbraA = ra <= kUmbra, litA = ra >= kLit;
    const bool umbraB = p.X >= -1.8 && p.X <= -0.35 && std::fabs(p.Z) <= kUmbra;
    const bool litB = p.X >= 0.05 || std::fabs(p.Z) >= kLit;
    const bool expect[2][2] = { { umbraA, litA }, { umbraB, litB } };
    for (int slot = 0; slot < 2; ++slot)
    {
      if (expect[slot][0] || expect[slot][1])
      {
        ++checked[slot];
        const bool ok = expect[slot][0] ? fp[slot] < 0.05f : fp[slot] == 1.0f;
        if (!ok && ++bad <= 3)
        {
          std::fprintf(stderr, "slot %d at (%.1f, %.1f): factor %g\n", slot, p.X, p.Z, fp[slot]);
        }
      }
    }
    if (umbraA && umbraB)
    {
      ++both;
      for (int k = 0; k < 3; ++k)
      {
        if (std::fabs(Channel(on, p.Pixel, k) - Channel(thirdOnly, p.Pixel, k)) > 1 && ++bad <= 3)
        {
          std::fprintf(stderr, "in both umbrae at (%.1f, %.1f): not the third light alone\n", p.X,
            p.Z);
        }
      }
      MRGI_TEST_CHECK(Sum(thirdOnly, p.Pixel) > 20);
    }
  }
  std::printf("lights: %d / %d points checked in slots 0 / 1, %d in both umbrae, %d wrong\n",
    checked[0], checked[1], both, bad);
  MRGI_TEST_CHECK(checked[0] > 200 && checked[1] > 200 && both >= 10);
  MRGI_TEST_CHECK(bad == 0);
  (void)c;
}

// MRGI_SHADOW_AUTO_LIGHT_RADIUS of the renderer's visible bounding radius.
double ExpectedAutoRadius(vtkRenderer* renderer)
{
  double b[6];
  renderer->ComputeVisiblePropBounds(b);
  const double dx = b[1] - b[0], dy = b[3] - b[2], dz = b[5] - b[4];
  return 0.5 * std::sqrt(dx * dx + dy * dy + dz * dz) * MRGI_SHADOW_AUTO_LIGHT_RADIUS;
}

// The automatic light radius follows the scene, computed once per
// re-render of the reflective shadow maps.
void LightRadius()
{
  Scene s(160, 120);
  vtkMRGIShadowedDirectLight* step = s.Pass->GetShadowedDirectLight();
  vtkMRGIReflectiveShadowMapPass* rsm = s.Pass->GetReflectiveShadowMapPass();
  MRGI_TEST_CHECK(step && step->GetNumberOfLightRadiusUpdates() == 0);
  s.Render(vtkMRGIPass::DirectShadowsSoft);
  const double first = step->GetLastLightRadius();
  const double expected = ExpectedAutoRadius(s.Renderer);
  std::printf("light radius: %.6g (expected %.6g), %lld update(s)\n", first, expected,
    static_cast<long long>(step->GetNumberOfLightRadiusUpdates()));
  vtkNew<vtkImageData> factors;
  MRGI_TEST_CHECK(s.Pass->GetShadowFactorBuffer(s.Window, factors)); // shadows were applied
  MRGI_TEST_CHECK(step->GetNumberOfLightRadiusUpdates() == 1);
  MRGI_TEST_CHECK(first > 0 && std::fabs(first - expected) <= 1e-12 * expected);
  // Unchanged frames and a camera move: the maps are kept, so is the radius.
  const vtkIdType renders = rsm->GetNumberOfRenders();
  s.Render(vtkMRGIPass::DirectShadowsSoft);
  s.Renderer->GetActiveCamera()->Azimuth(15);
  s.Renderer->ResetCameraClippingRange();
  s.Render(vtkMRGIPass::DirectShadowsSoft);
  MRGI_TEST_CHECK(rsm->GetNumberOfRenders() == renders);
  MRGI_TEST_CHECK(step->GetNumberOfLightRadiusUpdates() == 1);
  MRGI_TEST_CHECK(step->GetLastLightRadius() == first);
  // The small box moves 3 units out: the bounds and the radius grow.
  s.Actors[2]->SetPosition(3, 0, 0);
  s.Render(vtkMRGIPass::DirectShadowsSoft);
  const double moved = step->GetLastLightRadius();
  const double expectedMoved = ExpectedAutoRadius(s.Renderer);
  std::printf("light radius after the move: %.6g (expected %.6g), %lld update(s)\n", moved,
    expectedMoved, static_cast<long long>(step->GetNumberOfLightRadiusUpdates()));
  MRGI_TEST_CHECK(rsm->GetNumberOfRenders() > renders);
  MRGI_TEST_CHECK(step->GetNumberOfLightRadiusUpdates() == 2);
  MRGI_TEST_CHECK(moved > first * 1.05);
  MRGI_TEST_CHECK(std::fabs(moved - expectedMoved) <= 1e-12 * expectedMoved);
  // A radius set on the pass is used as it is; the bounds are not read.
  s.Pass->SetShadowLightRadius(0.05);
  s.Render(vtkMRGIPass::DirectShadowsSoft);
  MRGI_TEST_CHECK(step->GetLastLightRadius() == 0.05);
  MRGI_TEST_CHECK(step->GetNumberOfLightRadiusUpdates() == 2);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(NonSquare), MRGI_TEST_CASE(Viewport),
      MRGI_TEST_CASE(TileEqualsWindow), MRGI_TEST_CASE(PBR),
      MRGI_TEST_CASE(DepthPeeling), MRGI_TEST_CASE(SecondLayer), MRGI_TEST_CASE(FXAA),
      MRGI_TEST_CASE(Lights), MRGI_TEST_CASE(LightRadius) });
}
