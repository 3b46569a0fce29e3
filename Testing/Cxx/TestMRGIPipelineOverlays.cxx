// What vtkMRGIPass must leave alone, and what it must keep working:
// - volumes (vtkGPUVolumeRayCastMapper, vtkSmartVolumeMapper on a small
//   vtkImageData), depth-composited with the opaque scene as VTK does;
// - 2D overlays (vtkTextActor with an opaque background, vtkScalarBarActor)
//   over lit geometry: no indirect light on top of them, their pixels are the
//   same with indirect light on and off;
// - wherever no opaque surface is (background, volume over background),
//   nothing is added: the image equals the one with indirect light off;
// - with IndirectMode Off the image is VTK's own (max difference 1/255),
//   also with dual depth peeling of translucent props and volumes together;
// - FXAA (renderer->UseFXAAOn()): applied before the overlays as VTK applies
//   it: IndirectMode Off matches VTK's FXAA image closely, edges are smoothed
//   with indirect light on, overlays are not blurred (VTK 9.1 itself applies
//   FXAA only to renderers without a render pass; vtkMRGIPass applies it to
//   its exposed, tone-mapped display image in its output step, after the
//   volumes, then draws the overlays);
// - the lit image (room, volumes, overlays) matches its baseline (relative RMS 0.02).
//
// Volume mappers, text rendering and the scalar bar live in VTK modules the
// C++ tests do not link (RenderingVolumeOpenGL2, RenderingFreeType,
// RenderingAnnotation): they are loaded at run time (TestMRGIPipelineCommon.h).
#include "TestMRGIPipelineCommon.h"

#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkSmartVolumeMapper.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkColorTransferFunction.h"
#include "vtkCubeSource.h"
#include "vtkLight.h"
#include "vtkLookupTable.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPiecewiseFunction.h"
#include "vtkScalarBarActor.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

namespace
{
// A 24^3 blob: 1 at the centre, falling to 0 at radius 1 (world units 0..2 per axis).
vtkSmartPointer<vtkImageData> Blob()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(24, 24, 24);
  image->SetSpacing(2.0 / 23, 2.0 / 23, 2.0 / 23);
  image->AllocateScalars(VTK_FLOAT, 1);
  float* v = static_cast<float*>(image->GetScalarPointer());
  for (int k = 0; k < 24; ++k)
  {
    for (int j = 0; j < 24; ++j)
    {
      for (int i = 0; i < 24; ++i)
      {
        const double x = i / 11.5 - 1, y = j / 11.5 - 1, z = k / 11.5 - 1;
        *v++ = static_cast<float>(std::max(0.0, 1.0 - std::sqrt(x * x + y * y + z * z)));
      }
    }
  }
  return image;
}

vtkSmartPointer<vtkVolume> MakeVolume(vtkAbstractVolumeMapper* mapper, vtkImageData* data)
{
  mapper->SetInputDataObject(data);
  vtkNew<vtkColorTransferFunction> colour;
  colour->AddRGBPoint(0.0, 0.0, 0.0, 1.0);
  colour->AddRGBPoint(0.5, 1.0, 0.5, 0.0);
  colour->AddRGBPoint(1.0, 1.0, 1.0, 0.2);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(0.2, 0.0);
  opacity->AddPoint(1.0, 0.6);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(colour);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->ShadeOff();
  auto volume = vtkSmartPointer<vtkVolume>::New();
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  return volume;
}

// Max RGB difference over the pixels where `mask` (a G-buffer image) is
// valid (`valid` true) or invalid, inside [x0,x1) x [y0,y1).
double MaxDifferenceWhere(vtkImageData* a, vtkImageData* b, vtkImageData* mask, bool valid, int x0,
  int y0, int x1, int y1, int* count = nullptr)
{
  double worst = 0;
  int n = 0;
  for (int y = y0; y < y1; ++y)
  {
    for (int x = x0; x < x1; ++x)
    {
      if (mrgipipe::Valid(mask, x, y) != valid)
      {
        continue;
      }
      ++n;
      for (int c = 0; c < 3; ++c)
      {
        worst = std::max(worst,
          std::fabs(
            a->GetScalarComponentAsDouble(x, y, 0, c) - b->GetScalarComponentAsDouble(x, y, 0, c)));
      }
    }
  }
  if (count)
  {
    *count = n;
  }
  return worst;
}

// Sum of absolute differences between neighbouring pixels (total variation).
double TotalVariation(vtkImageData* image)
{
  int dims[3];
  image->GetDimensions(dims);
  double tv = 0;
  for (int y = 0; y + 1 < dims[1]; ++y)
  {
    for (int x = 0; x + 1 < dims[0]; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        const double v = image->GetScalarComponentAsDouble(x, y, 0, c);
        tv += std::fabs(image->GetScalarComponentAsDouble(x + 1, y, 0, c) - v) +
          std::fabs(image->GetScalarComponentAsDouble(x, y + 1, 0, c) - v);
      }
    }
  }
  return tv;
}
}

int main()
{
  using namespace mrgipipe;

  const int W = 200, H = 150;
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(W, H);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  renderer->SetBackground(0.05, 0.05, 0.1);

  // Lit room on the left: floor, wall, red box (indirect light between them).
  const double cf[3] = { -1.2, -1, 0 }, nf[3] = { 0, 1, 0 };
  const double cw[3] = { -1.2, 0.5, -1.5 }, nw[3] = { 0, 0, 1 };
  renderer->AddActor(MakeQuad(cf, nf, 3, 0.8, 0.8, 0.8, 4));
  renderer->AddActor(MakeQuad(cw, nw, 3, 0.8, 0.8, 0.8, 4));
  vtkNew<vtkCubeSource> cube;
  vtkSmartPointer<vtkActor> box = MakeActor(cube, 0.9, 0.15, 0.1);
  box->SetPosition(-1.4, -0.5, -0.5);
  renderer->AddActor(box);
  // Opaque cube partly in front of the volumes: depth compositing shows.
  vtkSmartPointer<vtkActor> front = MakeActor(cube, 0.3, 0.8, 0.9);
  front->SetPosition(0.6, -0.9, 1.2);
  front->SetScale(0.6);
  renderer->AddActor(front);

  // Two volumes over the background on the right.
  vtkSmartPointer<vtkImageData> blob = Blob();
  vtkSmartPointer<vtkAbstractVolumeMapper> gpuMapper =
    vtkSmartPointer<vtkGPUVolumeRayCastMapper>::New(); // the OpenGL override (autoinit)
  std::printf("GPU volume mapper: %s\n", gpuMapper->GetClassName());
  vtkSmartPointer<vtkVolume> gpuVolume = MakeVolume(gpuMapper, blob);
  gpuVolume->SetPosition(0.4, -0.4, 0);
  gpuVolume->SetScale(0.6);
  renderer->AddVolume(gpuVolume);
  vtkSmartPointer<vtkAbstractVolumeMapper> smartMapper = vtkSmartPointer<vtkSmartVolumeMapper>::New();
  vtkSmartPointer<vtkVolume> smartVolume = MakeVolume(smartMapper, blob);
  smartVolume->SetPosition(1.2, 0.3, -0.5);
  smartVolume->SetScale(0.5);
  renderer->AddVolume(smartVolume);

  // Overlays over the lit room: text with an opaque box, a scalar bar.
  vtkNew<vtkTextActor> text;
  text->SetInput("MRGI overlay");
  text->GetTextProperty()->SetFontSize(14);
  text->GetTextProperty()->SetColor(1, 1, 0.2);
  text->GetTextProperty()->SetBackgroundColor(0.1, 0.2, 0.5);
  text->GetTextProperty()->SetBackgroundOpacity(1.0);
  text->SetDisplayPosition(8, 12);
  renderer->AddActor2D(text);
  vtkNew<vtkLookupTable> lut;
  lut->SetHueRange(0.66, 0.0);
  lut->Build();
  vtkNew<vtkScalarBarActor> bar;
  bar->SetLookupTable(lut);
  bar->SetNumberOfLabels(0);
  bar->SetPosition(0.05, 0.45);
  bar->SetWidth(0.15);
  bar->SetBarRatio(0.6);
  bar->SetHeight(0.45);
  renderer->AddActor2D(bar);

  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetConeAngle(50);
  light->SetPosition(-0.5, 2.5, 2.0);
  light->SetFocalPoint(-1.2, -0.8, -0.5);
  renderer->AddLight(light);
  renderer->GetActiveCamera()->SetPosition(0, 0.3, 6);
  renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  renderer->ResetCameraClippingRange();

  // VTK alone, then MRGI with indirect light off and on.
  window->Render();
  vtkSmartPointer<vtkImageData> plain = mrgitest::GrabRGB(window);
  // The text's box, relative to its display position.
  double textBox[4];
  text->GetBoundingBox(renderer, textBox);
  textBox[0] += 8;
  textBox[1] += 8;
  textBox[2] += 12;
  textBox[3] += 12;
  std::printf("text box %.0f..%.0f x %.0f..%.0f\n", textBox[0], textBox[1], textBox[2], textBox[3]);
  vtkSmartPointer<vtkMRGIPass> pass = Install(renderer);
  pass->SetRSMResolution(128);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  window->Render();
  vtkSmartPointer<vtkImageData> off = mrgitest::GrabRGB(window);
  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  window->Render();
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  vtkSmartPointer<vtkImageData> full = mrgitest::GrabRGB(window);
  vtkNew<vtkImageData> position, normal, albedo;
  MRGI_TEST_CHECK(pass->GetGBuffer(window, position, normal, albedo));
  DebugWrite(plain, "TestMRGIPipelineOverlays-plain");
  DebugWrite(off, "TestMRGIPipelineOverlays-off");
  DebugWrite(full, "TestMRGIPipelineOverlays-full");
  MRGI_TEST_CHECK(mrgitest::CompareWithBaseline(full, "TestMRGIPipelineOverlays", 0.02));
  // Volumes blend over MRGI's float colour, VTK's over its 8-bit one (which
  // rounds the scene behind first): volume pixels may differ by 2 / 255.
  std::printf(
    "IndirectMode Off vs VTK: max difference %.0f / 255, %d pixels differ by more than 1\n",
    MaxDifference(plain, off), CountDifferent(plain, off, 1.0));
  MRGI_TEST_CHECK(MaxDifference(plain, off) <= 2.0);
  MRGI_TEST_CHECK(CountDifferent(plain, off, 1.0) <= W * H / 1000);
  // Indirect light is there, on the lit surfaces.
  int litPixels = 0;
  const double onSurfaces = MaxDifferenceWhere(full, off, position, true, 0, 0, W, H, &litPixels);
  std::printf("indirect light: max %.0f / 255 over %d surface pixels\n", onSurfaces, litPixels);
  MRGI_TEST_CHECK(onSurfaces > 20);

  // Where there is no opaque surface (background, volumes over it) nothing is added.
  int empty = 0;
  const double offSurfaces = MaxDifferenceWhere(full, off, position, false, 0, 0, W, H, &empty);
  std::printf("no surface: %d pixels, max difference on / off %.0f\n", empty, offSurfaces);
  MRGI_TEST_CHECK(empty > 1000 && offSurfaces <= 1.0);

  // The volumes are drawn, in front of the background and behind the cube.
  gpuVolume->VisibilityOff();
  smartVolume->VisibilityOff();
  window->Render();
  vtkSmartPointer<vtkImageData> noVolumes = mrgitest::GrabRGB(window);
  gpuVolume->VisibilityOn();
  smartVolume->VisibilityOn();
  const int volumePixels = CountDifferent(full, noVolumes, 10);
  std::printf("volumes change %d pixels\n", volumePixels);
  MRGI_TEST_CHECK(volumePixels > 400);

  // The overlays: drawn, and the same with indirect light on and off,
  // although the lit room behind them changes.
  const int tx0 = static_cast<int>(textBox[0]) + 2, tx1 = static_cast<int>(textBox[1]) - 2;
  const int ty0 = static_cast<int>(textBox[2]) + 2, ty1 = static_cast<int>(textBox[3]) - 2;
  MRGI_TEST_CHECK(tx1 - tx0 > 20 && ty1 - ty0 > 5);
  int barRect[4]; // x, y, width, height of the colour bar itself
  bar->GetScalarBarRect(barRect, renderer);
  std::printf(
    "scalar bar rectangle %d %d %d x %d\n", barRect[0], barRect[1], barRect[2], barRect[3]);
  const int bx0 = barRect[0] + 2, bx1 = barRect[0] + barRect[2] - 2;
  const int by0 = barRect[1] + 2, by1 = barRect[1] + barRect[3] - 2;
  MRGI_TEST_CHECK(bx1 - bx0 > 5 && by1 - by0 > 20);
  text->VisibilityOff();
  bar->VisibilityOff();
  window->Render();
  vtkSmartPointer<vtkImageData> noOverlays = mrgitest::GrabRGB(window);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  window->Render();
  vtkSmartPointer<vtkImageData> offNoOverlays = mrgitest::GrabRGB(window);
  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  text->VisibilityOn();
  bar->VisibilityOn();
  struct Overlay
  {
    const char* Name;
    int X0, Y0, X1, Y1;
  } overlays[] = { { "text", tx0, ty0, tx1, ty1 }, { "scalar bar", bx0, by0, bx1, by1 } };
  for (const Overlay& o : overlays)
  {
    int under = 0;
    MaxDifferenceWhere(full, off, position, true, o.X0, o.Y0, o.X1, o.Y1, &under);
    const double drawn = MaxDifference(full, noOverlays, o.X0, o.Y0, o.X1, o.Y1);
    const double behind = MaxDifference(noOverlays, offNoOverlays, o.X0, o.Y0, o.X1, o.Y1);
    const double onOff = MaxDifference(full, off, o.X0, o.Y0, o.X1, o.Y1);
    std::printf("%s: %d pixels over surfaces; indirect light behind it %.0f / 255; drawn: %.0f; "
                "indirect on vs off %.0f\n",
      o.Name, under, behind, drawn, onOff);
    MRGI_TEST_CHECK(under > 100);  // over the lit room,
    MRGI_TEST_CHECK(behind >= 5);  // which indirect light brightens,
    MRGI_TEST_CHECK(drawn > 40);   // the overlay is drawn
    MRGI_TEST_CHECK(onOff <= 1.0); // and nothing is added on top of it.
  }

  // Dual depth peeling of a translucent sphere and the volumes together.
  vtkNew<vtkSphereSource> sphereSource;
  sphereSource->SetThetaResolution(24);
  sphereSource->SetPhiResolution(24);
  vtkSmartPointer<vtkActor> glass = MakeActor(sphereSource, 0.2, 0.9, 0.4);
  glass->SetPosition(0.9, -0.2, 0.3);
  glass->SetScale(1.1);
  glass->GetProperty()->SetOpacity(0.4);
  renderer->AddActor(glass);
  renderer->SetUseDepthPeeling(1);
  renderer->SetUseDepthPeelingForVolumes(true);
  renderer->SetMaximumNumberOfPeels(8);
  renderer->SetOcclusionRatio(0.0);
  renderer->SetPass(nullptr);
  window->Render();
  vtkSmartPointer<vtkImageData> plainPeeled = mrgitest::GrabRGB(window);
  std::printf("dual depth peeling supported: %d\n",
    vtkOpenGLRenderer::SafeDownCast(renderer)->IsDualDepthPeelingSupported() ? 1 : 0);
  renderer->SetPass(pass);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  window->Render();
  vtkSmartPointer<vtkImageData> offPeeled = mrgitest::GrabRGB(window);
  DebugWrite(plainPeeled, "TestMRGIPipelineOverlays-plain-peeled");
  DebugWrite(offPeeled, "TestMRGIPipelineOverlays-off-peeled");
  std::printf("depth peeling with volumes: IndirectMode Off vs VTK max difference %.0f / 255, %d "
              "pixels differ by more than 1\n",
    MaxDifference(plainPeeled, offPeeled), CountDifferent(plainPeeled, offPeeled, 1.0));
  MRGI_TEST_CHECK(MaxDifference(plainPeeled, offPeeled) <= 2.0);
  MRGI_TEST_CHECK(CountDifferent(plainPeeled, offPeeled, 1.0) <= W * H / 1000);
  MRGI_TEST_CHECK(CountDifferent(plainPeeled, plain, 10) > 200); // the sphere shows
  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  window->Render();
  vtkNew<vtkImageData> colour;
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, colour) && AllFinite(colour));
  renderer->RemoveActor(glass);
  renderer->SetUseDepthPeeling(0);
  renderer->SetUseDepthPeelingForVolumes(false);

  // FXAA.
  renderer->UseFXAAOn();
  renderer->SetPass(nullptr);
  window->Render();
  vtkSmartPointer<vtkImageData> plainFXAA = mrgitest::GrabRGB(window);
  renderer->SetPass(pass);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  window->Render();
  vtkSmartPointer<vtkImageData> offFXAA = mrgitest::GrabRGB(window);
  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  window->Render();
  vtkSmartPointer<vtkImageData> fullFXAA = mrgitest::GrabRGB(window);
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, colour) && AllFinite(colour));
  DebugWrite(fullFXAA, "TestMRGIPipelineOverlays-full-fxaa");
  // MRGI's float buffer rounds once where VTK's 8-bit buffer rounds after
  // every blend: FXAA's edge detection then differs at a few pixels.
  const int fxaaDiffering = CountDifferent(plainFXAA, offFXAA, 2.0);
  std::printf("FXAA: IndirectMode Off vs VTK max difference %.0f / 255, %d pixels differ by more "
              "than 2; VTK's FXAA changes %d pixels\n",
    MaxDifference(plainFXAA, offFXAA), fxaaDiffering, CountDifferent(plainFXAA, plain, 2.0));
  MRGI_TEST_CHECK(CountDifferent(plainFXAA, plain, 2.0) > 50);
  MRGI_TEST_CHECK(fxaaDiffering <= W * H / 500);
  MRGI_TEST_CHECK(MaxDifference(plainFXAA, offFXAA) <= 16.0);
  // Edges smoothed: the image's total variation drops, as much as VTK's FXAA makes it drop.
  const double tvFull = TotalVariation(full), tvFXAA = TotalVariation(fullFXAA);
  const double tvPlain = TotalVariation(plain), tvPlainFXAA = TotalVariation(plainFXAA);
  std::printf("total variation: with indirect light %.0f -> %.0f with FXAA; VTK %.0f -> %.0f\n",
    tvFull, tvFXAA, tvPlain, tvPlainFXAA);
  MRGI_TEST_CHECK(tvPlainFXAA < tvPlain);
  MRGI_TEST_CHECK(tvFull - tvFXAA > 0.5 * (tvPlain - tvPlainFXAA));
  MRGI_TEST_CHECK(CountDifferent(fullFXAA, full, 2.0) > 50);
  // Overlays are drawn after FXAA: not blurred.
  MRGI_TEST_CHECK(MaxDifference(fullFXAA, full, tx0, ty0, tx1, ty1) <= 1.0);
  MRGI_TEST_CHECK(MaxDifference(fullFXAA, full, bx0, by0, bx1, by1) <= 1.0);

  Uninstall(renderer, window, pass);
  return 0;
}
