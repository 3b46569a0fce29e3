// vtkMRGIPass composed with VTK 9.1's own passes, in every nesting a user
// might try; Documentation/Composition.md is the table these cases prove.
// "X(Y)" below means Y is X's delegate. Scene: cornell-spot, 160 x 120,
// full-resolution gather with 64 VPLs (the indirect light brightens the
// ceiling, which the spot light does not reach).
//
// A nesting that works must show both effects against the two passes
// alone: MRGI's indirect light (>= kEffectPixels pixels brighter than X
// alone by > kStep/255) and X's effect (SSAO, shadows: >= kEffectPixels
// pixels darker than MRGI alone; tone mapping / FXAA: >= kEdgePixels
// pixels differ from MRGI alone). A nesting that cannot work must give
// one error naming the classes and the fix (caught, once over two frames)
// and the image of X alone (max difference <= 2/255), never garbage.
// Exposure and anti-aliasing of the pass itself are here too: the output
// transform against its C twin (mrgi_exposure_apply), automatic exposure
// against mrgi_exposure_auto_ev, FXAA (smooths edges, keeps flat areas,
// refused with MSAA), and MSAA's error.
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkCameraPass.h"
#include "vtkDualDepthPeelingPass.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIImageIO.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkOpenGLFXAAPass.h"
#include "vtkOrderIndependentTranslucentPass.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderPassCollection.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkSSAOPass.h"
#include "vtkSequencePass.h"
#include "vtkShadowMapBakerPass.h"
#include "vtkShadowMapPass.h"
#include "vtkSphereSource.h"
#include "vtkToneMappingPass.h"

#include "mrgi_exposure.h"

#include <cmath>
#include <set>

namespace
{
const int W = 160, H = 120;
const double kStep = 8.0;      // a visible change, /255
const int kEffectPixels = 500; // ~2.6% of the image
const int kEdgePixels = 50;

// The scene, a headless window, and an error catcher on every pass made.
struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<mrgitest::ErrorCatcher> Errors;
  Scene()
  {
    this->Window = mrgitest::HeadlessWindow(W, H);
    this->Window->AddRenderer(this->Renderer);
    vtkNew<vtkMRGISceneBuilder> builder;
    builder->SetScene("cornell-spot");
    MRGI_TEST_CHECK(builder->Build(this->Renderer));
  }
  ~Scene()
  {
    this->Renderer->SetPass(nullptr);
    this->Window->Finalize();
  }
  // Renders `frames` frames through `pass` (nullptr: VTK without passes),
  // keeps the last image (also as composition-NAME.png in the test's
  // scratch folder), then frees the nesting's GL resources.
  vtkSmartPointer<vtkImageData> Render(vtkRenderPass* pass, const char* name, int frames = 1)
  {
    this->Renderer->SetPass(pass);
    for (int f = 0; f < frames; ++f)
    {
      this->Window->Render();
    }
    vtkSmartPointer<vtkImageData> image = mrgitest::GrabRGB(this->Window);
    vtkNew<vtkMRGIImageIO> io;
    io->WritePNG(image, mrgitest::TempPath(std::string("composition-") + name + ".png").c_str());
    this->Renderer->SetPass(nullptr);
    if (pass)
    {
      pass->ReleaseGraphicsResources(this->Window);
    }
    return image;
  }
  vtkSmartPointer<vtkMRGIPass> NewMRGI(vtkRenderPass* delegate)
  {
    auto gi = vtkSmartPointer<vtkMRGIPass>::New();
    gi->SetIndirectMode(vtkMRGIPass::IndirectFull);
    gi->SetNumberOfVPLs(64);
    gi->SetDelegatePass(delegate);
    gi->AddObserver(vtkCommand::ErrorEvent, this->Errors);
    return gi;
  }
};

// Pixels where `b` is darker than `a` by more than t/255 (mean of RGB).
int Darker(vtkImageData* a, vtkImageData* b, double t)
{
  vtkDataArray* sa = a->GetPointData()->GetScalars();
  vtkDataArray* sb = b->GetPointData()->GetScalars();
  int n = 0;
  for (vtkIdType p = 0; p < sa->GetNumberOfTuples(); ++p)
  {
    double d = 0;
    for (int c = 0; c < 3; ++c)
    {
      d += sa->GetComponent(p, c) - sb->GetComponent(p, c);
    }
    n += d / 3 > t ? 1 : 0;
  }
  return n;
}

// Pixels that differ by more than t/255 in some channel; the largest difference.
int Differ(vtkImageData* a, vtkImageData* b, double t, double* worst = nullptr)
{
  vtkDataArray* sa = a->GetPointData()->GetScalars();
  vtkDataArray* sb = b->GetPointData()->GetScalars();
  int n = 0;
  double w = 0;
  for (vtkIdType p = 0; p < sa->GetNumberOfTuples(); ++p)
  {
    double d = 0;
    for (int c = 0; c < 3; ++c)
    {
      d = std::max(d, std::fabs(sa->GetComponent(p, c) - sb->GetComponent(p, c)));
    }
    n += d > t ? 1 : 0;
    w = std::max(w, d);
  }
  if (worst)
  {
    *worst = w;
  }
  return n;
}

// Both effects, or say which is missing.
void ExpectBoth(const char* what, vtkImageData* image, vtkImageData* mrgiAlone,
  vtkImageData* xAlone, bool xDarkens)
{
  const int indirect = Darker(image, xAlone, kStep);
  const int effect = xDarkens ? Darker(mrgiAlone, image, kStep) : Differ(mrgiAlone, image, 2.0);
  std::printf("%-22s %5d pixels brighter than X alone (indirect light), %5d %s MRGI alone\n", what,
    indirect, effect, xDarkens ? "darker than" : "differ from");
  MRGI_TEST_CHECK(indirect >= kEffectPixels);
  MRGI_TEST_CHECK(effect >= (xDarkens ? kEffectPixels : kEdgePixels));
}

// X alone's image and one error naming `fragment`.
void ExpectRefused(
  const char* what, Scene& s, vtkImageData* image, vtkImageData* xAlone, const char* fragment)
{
  double worst = 0;
  Differ(image, xAlone, 2.0, &worst);
  std::printf("%-22s refused; max difference to X alone %.0f / 255, %d error(s)\n", what, worst,
    s.Errors->Count);
  MRGI_TEST_CHECK(s.Errors->Count == 1); // once over two frames
  MRGI_TEST_CHECK(s.Errors->Caught(fragment));
  MRGI_TEST_CHECK(worst <= 2.0);
}

vtkSmartPointer<vtkSSAOPass> NewSSAO(vtkRenderPass* delegate)
{
  auto ssao = vtkSmartPointer<vtkSSAOPass>::New();
  ssao->SetRadius(0.1);
  ssao->SetKernelSize(64);
  ssao->SetDelegatePass(delegate);
  return ssao;
}

// VTK's shadow-map recipe: camera(sequence(baker, shadows(opaque))).
vtkSmartPointer<vtkRenderPass> NewShadowCamera(vtkRenderPass* opaque)
{
  vtkNew<vtkShadowMapPass> shadows;
  if (opaque)
  {
    shadows->SetOpaqueSequence(opaque);
  }
  vtkNew<vtkRenderPassCollection> passes;
  passes->AddItem(shadows->GetShadowMapBakerPass());
  passes->AddItem(shadows);
  vtkNew<vtkSequencePass> sequence;
  sequence->SetPasses(passes);
  auto camera = vtkSmartPointer<vtkCameraPass>::New();
  camera->SetDelegatePass(sequence);
  return camera;
}

void TestSSAO()
{
  Scene s;
  vtkNew<vtkRenderStepsPass> steps;
  auto mrgiAlone = s.Render(s.NewMRGI(steps), "mrgi");
  auto plain = s.Render(nullptr, "plain");
  auto ssaoAlone = s.Render(NewSSAO(steps), "ssao");
  MRGI_TEST_CHECK(Darker(plain, ssaoAlone, kStep) >= kEffectPixels / 2); // SSAO does something
  // SSAO(MRGI): the occlusion over MRGI's image, indirect light included
  // (MRGI hands SSAO its position and normal).
  auto around = s.Render(NewSSAO(s.NewMRGI(steps)), "ssao(mrgi)", 2);
  ExpectBoth("ssao(mrgi)", around, mrgiAlone, ssaoAlone, true);
  // The same with the multiresolution gather (every stage of it inside SSAO).
  auto multires = s.NewMRGI(steps);
  multires->SetIndirectMode(vtkMRGIPass::IndirectMultires);
  auto multiresAlone = s.Render(multires, "mrgi-multires");
  auto inner = s.NewMRGI(steps);
  inner->SetIndirectMode(vtkMRGIPass::IndirectMultires);
  auto aroundMultires = s.Render(NewSSAO(inner), "ssao(mrgi-multires)", 2);
  ExpectBoth("ssao(mrgi multires)", aroundMultires, multiresAlone, ssaoAlone, true);
  MRGI_TEST_CHECK(s.Errors->Count == 0);
  // MRGI(SSAO): refused; SSAO alone.
  auto inside = s.Render(s.NewMRGI(NewSSAO(steps)), "mrgi(ssao)", 2);
  ExpectRefused("mrgi(ssao)", s, inside, ssaoAlone, "vtkSSAOPass as the delegate of vtkMRGIPass");
}

void TestShadowMap()
{
  Scene s;
  vtkNew<vtkRenderStepsPass> steps;
  auto mrgiAlone = s.Render(s.NewMRGI(steps), "mrgi");
  auto shadowAlone = s.Render(NewShadowCamera(nullptr), "shadow");
  // Shadows(MRGI): MRGI as the shadow pass's opaque sequence.
  auto around = s.Render(NewShadowCamera(s.NewMRGI(steps)), "shadow(mrgi)");
  ExpectBoth("shadow(mrgi)", around, mrgiAlone, shadowAlone, true);
  // MRGI(camera(baker, shadows)).
  auto inside = s.Render(s.NewMRGI(NewShadowCamera(nullptr)), "mrgi(shadow)");
  ExpectBoth("mrgi(shadow)", inside, mrgiAlone, shadowAlone, true);
  // The two nestings agree but for a few pixels at the shadow map's edges
  // (Documentation/Composition.md): fewer than 5% of the pixels differ by
  // more than kStep, where either nesting losing VTK's shadows would change
  // the pixels they darken (4230 of 19200 in this scene).
  double worst = 0;
  const int differ = Differ(inside, around, 0.0, &worst);
  const int visibly = Differ(inside, around, kStep);
  std::printf("%-22s %5d pixels differ from shadow(mrgi) (%d by more than %.0f / 255), by at "
              "most %.0f / 255\n",
    "mrgi(shadow)", differ, visibly, kStep, worst);
  MRGI_TEST_CHECK(visibly < W * H / 20);
  MRGI_TEST_CHECK(s.Errors->Count == 0);
}

void TestToneMapping()
{
  Scene s;
  vtkNew<vtkRenderStepsPass> steps;
  auto mrgiAlone = s.Render(s.NewMRGI(steps), "mrgi");
  vtkNew<vtkToneMappingPass> alone;
  alone->SetDelegatePass(steps);
  auto toneAlone = s.Render(alone, "tonemap");
  vtkNew<vtkToneMappingPass> outer;
  outer->SetDelegatePass(s.NewMRGI(steps));
  auto around = s.Render(outer, "tonemap(mrgi)");
  ExpectBoth("tonemap(mrgi)", around, mrgiAlone, toneAlone, false);
  MRGI_TEST_CHECK(s.Errors->Count == 0);
  vtkNew<vtkToneMappingPass> inner;
  inner->SetDelegatePass(steps);
  auto inside = s.Render(s.NewMRGI(inner), "mrgi(tonemap)", 2);
  ExpectRefused("mrgi(tonemap)", s, inside, toneAlone, "vtkToneMappingPass as the delegate");
  // MRGI's own tone mapping keeps every value up to the shoulder (0.5):
  // those pixels are unchanged (VTK's darkens them), brighter ones are
  // rolled off (never above what clipping gives).
  auto own = s.NewMRGI(steps);
  own->ToneMappingOn();
  auto ownImage = s.Render(own, "mrgi-tonemapped");
  vtkDataArray* a = mrgiAlone->GetPointData()->GetScalars();
  vtkDataArray* b = ownImage->GetPointData()->GetScalars();
  vtkNew<vtkToneMappingPass> vtkCurve;
  vtkCurve->SetDelegatePass(s.NewMRGI(steps));
  auto vtkImage = s.Render(vtkCurve, "tonemap(mrgi)-again");
  vtkDataArray* t = vtkImage->GetPointData()->GetScalars();
  int midtones = 0, kept = 0, vtkDarker = 0, rolledOff = 0;
  for (vtkIdType p = 0; p < a->GetNumberOfValues(); ++p)
  {
    const double plainValue = a->GetVariantValue(p).ToDouble();
    const double mine = b->GetVariantValue(p).ToDouble();
    if (plainValue > 8 && plainValue <= 0.5 * 255 - 1)
    {
      ++midtones;
      kept += std::fabs(mine - plainValue) <= 1.0 ? 1 : 0;
      vtkDarker += t->GetVariantValue(p).ToDouble() < plainValue - 2 ? 1 : 0;
    }
    rolledOff += mine > plainValue + 1 ? 1 : 0; // must stay 0
  }
  std::printf(
    "own tone curve: %d of %d mid-tone values kept; vtkToneMappingPass darkens %d of them\n", kept,
    midtones, vtkDarker);
  MRGI_TEST_CHECK(midtones > 1000 && kept == midtones && rolledOff == 0);
  MRGI_TEST_CHECK(vtkDarker > midtones / 2);
}

void TestFXAAPass()
{
  Scene s;
  vtkNew<vtkRenderStepsPass> steps;
  auto mrgiAlone = s.Render(s.NewMRGI(steps), "mrgi");
  vtkNew<vtkOpenGLFXAAPass> alone;
  alone->SetDelegatePass(steps);
  auto fxaaAlone = s.Render(alone, "fxaapass");
  vtkNew<vtkOpenGLFXAAPass> outer;
  outer->SetDelegatePass(s.NewMRGI(steps));
  auto around = s.Render(outer, "fxaapass(mrgi)");
  ExpectBoth("fxaapass(mrgi)", around, mrgiAlone, fxaaAlone, false);
  MRGI_TEST_CHECK(s.Errors->Count == 0);
  vtkNew<vtkOpenGLFXAAPass> inner;
  inner->SetDelegatePass(steps);
  auto inside = s.Render(s.NewMRGI(inner), "mrgi(fxaapass)", 2);
  ExpectRefused("mrgi(fxaapass)", s, inside, fxaaAlone, "vtkOpenGLFXAAPass as the delegate");
}

// renderer->UseFXAAOn() with MRGI: FXAA on MRGI's display image.
void TestUseFXAA()
{
  Scene s;
  vtkNew<vtkRenderStepsPass> steps;
  auto mrgiAlone = s.Render(s.NewMRGI(steps), "mrgi");
  s.Renderer->UseFXAAOn();
  auto fxaa = s.Render(s.NewMRGI(steps), "mrgi-fxaa");
  // Edges change; flat areas (away from any edge of the unfiltered image) do not.
  const int changed = Differ(mrgiAlone, fxaa, 2.0);
  vtkDataArray* a = mrgiAlone->GetPointData()->GetScalars();
  vtkDataArray* b = fxaa->GetPointData()->GetScalars();
  int flat = 0, flatChanged = 0;
  std::set<int> edgeValuesBefore, edgeValuesAfter;
  for (int y = 2; y < H - 2; ++y)
  {
    for (int x = 2; x < W - 2; ++x)
    {
      double spread = 0; // largest difference within the 5 x 5 neighbourhood
      const vtkIdType p = static_cast<vtkIdType>(y) * W + x;
      for (int dy = -2; dy <= 2; ++dy)
      {
        for (int dx = -2; dx <= 2; ++dx)
        {
          const vtkIdType q = static_cast<vtkIdType>(y + dy) * W + x + dx;
          for (int c = 0; c < 3; ++c)
          {
            spread = std::max(spread, std::fabs(a->GetComponent(p, c) - a->GetComponent(q, c)));
          }
        }
      }
      double d = 0;
      for (int c = 0; c < 3; ++c)
      {
        d = std::max(d, std::fabs(a->GetComponent(p, c) - b->GetComponent(p, c)));
      }
      if (spread == 0)
      {
        ++flat;
        flatChanged += d > 0 ? 1 : 0;
      }
      else if (spread > 32)
      {
        edgeValuesBefore.insert(static_cast<int>(a->GetComponent(p, 1)));
        edgeValuesAfter.insert(static_cast<int>(b->GetComponent(p, 1)));
      }
    }
  }
  std::printf(
    "FXAA: %d pixels changed; flat pixels %d, changed %d; distinct edge values %zu -> %zu\n",
    changed, flat, flatChanged, edgeValuesBefore.size(), edgeValuesAfter.size());
  MRGI_TEST_CHECK(changed >= kEdgePixels);
  MRGI_TEST_CHECK(flat > 1000 && flatChanged == 0);
  MRGI_TEST_CHECK(edgeValuesAfter.size() > edgeValuesBefore.size());
  // With a multisampled window: one error naming MSAA and FXAA; the image
  // is MRGI's (no FXAA, no MSAA), not VTK 9.1's black.
  s.Window->SetMultiSamples(8);
  auto multisampled = s.Render(s.NewMRGI(steps), "mrgi-fxaa-msaa", 2);
  double worst = 0;
  Differ(mrgiAlone, multisampled, 2.0, &worst);
  std::printf("FXAA with 8 multisamples: max difference to MRGI without FXAA %.0f / 255\n", worst);
  MRGI_TEST_CHECK(s.Errors->Count == 1);
  MRGI_TEST_CHECK(s.Errors->Caught("multisamples"));
  MRGI_TEST_CHECK(worst <= 2.0);
  s.Window->SetMultiSamples(0);
}

// Translucency through the vtkRenderStepsPass's translucent pass (OIT, dual
// depth peeling) inside MRGI: the sphere shows and the indirect light too.
void TestTranslucentPasses()
{
  Scene s;
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(278.0, 400.0, 200.0); // in the middle of the box (millimetres)
  sphere->SetRadius(80.0);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> glass;
  glass->SetMapper(mapper);
  glass->GetProperty()->SetColor(0.2, 0.4, 1.0);
  glass->GetProperty()->SetOpacity(0.5);
  s.Renderer->AddActor(glass);
  vtkNew<vtkRenderStepsPass> plainSteps;
  auto noGlass = [&](vtkRenderPass* pass, const char* name) {
    glass->SetVisibility(false);
    auto image = s.Render(pass, name);
    glass->SetVisibility(true);
    return image;
  };
  auto plainNoGlass = noGlass(plainSteps, "steps-noglass");
  for (int kind = 0; kind < 2; ++kind)
  {
    vtkNew<vtkRenderStepsPass> steps;
    vtkSmartPointer<vtkRenderPass> translucent;
    if (kind == 0)
    {
      auto oit = vtkSmartPointer<vtkOrderIndependentTranslucentPass>::New();
      oit->SetTranslucentPass(steps->GetTranslucentPass());
      translucent = oit;
    }
    else
    {
      auto ddp = vtkSmartPointer<vtkDualDepthPeelingPass>::New();
      ddp->SetTranslucentPass(steps->GetTranslucentPass());
      translucent = ddp;
    }
    steps->SetTranslucentPass(translucent);
    const char* name = kind == 0 ? "mrgi(steps+oit)" : "mrgi(steps+ddp)";
    auto xAlone = s.Render(steps, kind == 0 ? "steps+oit" : "steps+ddp");
    auto both = s.Render(s.NewMRGI(steps), name);
    auto mrgiNoGlass = noGlass(s.NewMRGI(steps), "mrgi-noglass");
    const int glassPixels = Differ(both, mrgiNoGlass, 2.0);
    const int indirect = Darker(both, xAlone, kStep);
    const int glassAlone = Differ(xAlone, plainNoGlass, 2.0);
    std::printf("%-22s %5d pixels brighter than X alone, the sphere changes %d pixels (%d without "
                "MRGI)\n",
      name, indirect, glassPixels, glassAlone);
    MRGI_TEST_CHECK(indirect >= kEffectPixels);
    MRGI_TEST_CHECK(glassPixels >= 200 && glassAlone >= 100);
  }
  MRGI_TEST_CHECK(s.Errors->Count == 0);
}

// The output transform on the GPU against its C twin: the window's 8-bit
// pixel of each HDR colour, exposed by +1.5 EV and tone mapped, within
// rounding (0.5/255) plus float noise; automatic exposure against the twin
// on the same HDR buffer (background = no geometry in the G-buffer, which
// in this scene is where nothing was drawn).
void TestExposureParity()
{
  Scene s;
  vtkNew<vtkRenderStepsPass> steps;
  auto gi = s.NewMRGI(steps);
  gi->SetExposure(1.5);
  gi->ToneMappingOn();
  s.Renderer->SetPass(gi);
  s.Window->Render();
  vtkNew<vtkImageData> hdr;
  MRGI_TEST_CHECK(gi->GetColorBuffer(s.Window, hdr));
  auto ldr = mrgitest::GrabRGB(s.Window);
  MRGI_TEST_CHECK(gi->GetLastExposure() == 1.5);
  const float* colour =
    vtkFloatArray::SafeDownCast(hdr->GetPointData()->GetScalars())->GetPointer(0);
  vtkDataArray* out = ldr->GetPointData()->GetScalars();
  const float scale = mrgi_exposure_scale(1.5);
  double worst = 0;
  int above = 0; // pixels whose exposed value exceeds the shoulder: the curve is exercised
  for (vtkIdType p = 0; p < static_cast<vtkIdType>(W) * H; ++p)
  {
    float expected[3];
    mrgi_exposure_apply(colour + 4 * p, scale, 1, expected);
    for (int c = 0; c < 3; ++c)
    {
      worst = std::max(worst, std::fabs(expected[c] * 255.0 - out->GetComponent(p, c)));
      above += (c == 0 && colour[4 * p] * scale > float(MRGI_TONE_SHOULDER)) ? 1 : 0;
    }
  }
  std::printf("exposure +1.5 EV, tone mapped: GPU vs C twin max %.3f / 255 (%d pixels past the "
              "shoulder)\n",
    worst, above);
  MRGI_TEST_CHECK(worst <= 0.51);
  MRGI_TEST_CHECK(above >= 100);

  gi->AutoExposureOn();
  s.Window->Render();
  MRGI_TEST_CHECK(gi->GetColorBuffer(s.Window, hdr));
  vtkNew<vtkImageData> position, normal, albedo;
  MRGI_TEST_CHECK(gi->GetGBuffer(s.Window, position, normal, albedo));
  const float* pos =
    vtkFloatArray::SafeDownCast(position->GetPointData()->GetScalars())->GetPointer(0);
  colour = vtkFloatArray::SafeDownCast(hdr->GetPointData()->GetScalars())->GetPointer(0);
  std::vector<float> depth(static_cast<size_t>(W) * H);
  for (size_t p = 0; p < depth.size(); ++p)
  {
    depth[p] = pos[4 * p + 3] > 0.5f ? 0.5f : 1.0f;
  }
  double lw = 0, lh = 0;
  MRGI_TEST_CHECK(
    mrgi_exposure_log_average(colour, 4, depth.data(), W * H, &lw, nullptr, nullptr) == MRGI_OK);
  MRGI_TEST_CHECK(mrgi_exposure_quantile(colour, 4, depth.data(), W * H,
                    MRGI_EXPOSURE_HIGHLIGHT_FRACTION, &lh, nullptr) == MRGI_OK);
  const double ev = mrgi_exposure_auto_ev(lw, lh, MRGI_EXPOSURE_KEY);
  std::printf("auto exposure: pass %.4f EV, C twin %.4f EV (Lw %.4f, Lh %.4f)\n",
    gi->GetLastExposure(), ev, lw, lh);
  MRGI_TEST_CHECK(std::fabs(gi->GetLastExposure() - ev) < 1e-9);
  MRGI_TEST_CHECK(ev != 0.0);
  s.Renderer->SetPass(nullptr);
  gi->ReleaseGraphicsResources(s.Window);
  MRGI_TEST_CHECK(s.Errors->Count == 0);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestSSAO), MRGI_TEST_CASE(TestShadowMap), MRGI_TEST_CASE(TestToneMapping),
      MRGI_TEST_CASE(TestFXAAPass), MRGI_TEST_CASE(TestUseFXAA),
      MRGI_TEST_CASE(TestTranslucentPasses), MRGI_TEST_CASE(TestExposureParity) });
}
