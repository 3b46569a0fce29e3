// Translucent actors with vtkMRGIPass:
// - not lit indirectly and not in the G-buffer: behind two overlapping
//   translucent spheres the G-buffer still holds the opaque wall (position,
//   albedo), and the indirect light is the same as without the spheres (they
//   are not in the reflective shadow map either);
// - still drawn over the result: where they are the image differs from the
//   image without them, elsewhere it does not;
// - drawn as VTK draws them without passes: order-independent translucency by
//   default, (dual) depth peeling with renderer->SetUseDepthPeeling(1): with
//   IndirectMode Off the image is VTK's own (max difference 1/255) in each
//   mode, which a plain vtkRenderStepsPass does not achieve;
// - the vtkRenderStepsPass given to MRGI still draws translucency when it is
//   installed on its own again (a GI on/off switch).
#include "TestMRGIPipelineCommon.h"

#include "vtkCubeSource.h"
#include "vtkLight.h"

namespace
{
// The pixel rectangle covering the world-space box [lo, hi].
void ScreenBox(vtkRenderer* renderer, const double lo[3], const double hi[3], int box[4])
{
  box[0] = box[1] = 1 << 20;
  box[2] = box[3] = -1;
  for (int i = 0; i < 8; ++i)
  {
    renderer->SetWorldPoint(i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2], 1);
    renderer->WorldToDisplay();
    const double* d = renderer->GetDisplayPoint();
    box[0] = std::min(box[0], static_cast<int>(std::floor(d[0])));
    box[1] = std::min(box[1], static_cast<int>(std::floor(d[1])));
    box[2] = std::max(box[2], static_cast<int>(std::ceil(d[0])));
    box[3] = std::max(box[3], static_cast<int>(std::ceil(d[1])));
  }
}

// Max difference between a and b outside the rectangle `box` (x0, y0, x1, y1).
double MaxDifferenceOutside(vtkImageData* a, vtkImageData* b, const int box[4])
{
  int dims[3];
  a->GetDimensions(dims);
  double worst = 0;
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      if (x >= box[0] && x <= box[2] && y >= box[1] && y <= box[3])
      {
        continue;
      }
      for (int c = 0; c < 3; ++c)
      {
        worst = std::max(worst,
          std::fabs(
            a->GetScalarComponentAsDouble(x, y, 0, c) - b->GetScalarComponentAsDouble(x, y, 0, c)));
      }
    }
  }
  return worst;
}
}

int main()
{
  using namespace mrgipipe;
  const int W = 160, H = 120;
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(W, H);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  renderer->SetBackground(0.1, 0.1, 0.15);

  const double cw[3] = { 0, 0, -1 }, nw[3] = { 0, 0, 1 };
  const double cf[3] = { 0, -1, 0.5 }, nf[3] = { 0, 1, 0 };
  renderer->AddActor(MakeQuad(cw, nw, 4, 0.8, 0.8, 0.8, 4));
  renderer->AddActor(MakeQuad(cf, nf, 4, 0.8, 0.8, 0.8, 4));
  vtkNew<vtkCubeSource> cube;
  vtkSmartPointer<vtkActor> box = MakeActor(cube, 0.9, 0.15, 0.1);
  box->SetPosition(-1.1, -0.5, -0.2);
  renderer->AddActor(box);
  // Two overlapping translucent spheres in front of the wall (the blue one
  // nearer): the result depends on how translucency is resolved.
  vtkNew<vtkSphereSource> sphereSource;
  sphereSource->SetRadius(0.55);
  sphereSource->SetThetaResolution(32);
  sphereSource->SetPhiResolution(32);
  vtkSmartPointer<vtkActor> blue = MakeActor(sphereSource, 0.2, 0.4, 1.0);
  blue->SetPosition(0.45, -0.1, 0.6);
  blue->GetProperty()->SetOpacity(0.45);
  vtkSmartPointer<vtkActor> green = MakeActor(sphereSource, 0.2, 0.9, 0.3);
  green->SetPosition(0.85, 0.1, -0.1);
  green->GetProperty()->SetOpacity(0.55);
  renderer->AddActor(blue);
  renderer->AddActor(green);
  // An opaque cube in front of part of the spheres: they are depth tested
  // against MRGI's depth (order-independent translucency copies it).
  vtkSmartPointer<vtkActor> occluder = MakeActor(cube, 0.95, 0.85, 0.3);
  occluder->SetPosition(1.05, -0.3, 1.0);
  occluder->SetScale(0.35);
  renderer->AddActor(occluder);
  const double lo[3] = { -0.1, -0.65, -0.65 }, hi[3] = { 1.4, 0.65, 1.15 };

  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetConeAngle(60);
  light->SetPosition(0.5, 2.5, 2.5);
  light->SetFocalPoint(0, -0.5, 0);
  renderer->AddLight(light);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 0.4, 5);
  camera->SetFocalPoint(0, 0, 0);
  renderer->ResetCameraClippingRange();
  int sphereBox[4];
  ScreenBox(renderer, lo, hi, sphereBox);

  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> pass;
  pass->SetDelegatePass(steps);
  pass->SetRSMResolution(128);
  // Compared with VTK's own image below: without direct shadows (the
  // occluder's shadow would differ on purpose; cxx.TestMRGIShadowComposition
  // covers shadows with depth peeling).
  pass->SetDirectShadowsToOff();

  // VTK's own translucency vs MRGI's, each way VTK resolves it.
  struct Mode
  {
    const char* Name;
    bool Peeling;
  } modes[] = { { "order-independent (default)", false }, { "depth peeling", true } };
  for (const Mode& mode : modes)
  {
    renderer->SetUseDepthPeeling(mode.Peeling ? 1 : 0);
    renderer->SetMaximumNumberOfPeels(8);
    renderer->SetOcclusionRatio(0.0);
    renderer->SetPass(nullptr);
    window->Render();
    vtkSmartPointer<vtkImageData> plain = mrgitest::GrabRGB(window);
    renderer->SetPass(steps);
    window->Render();
    vtkSmartPointer<vtkImageData> stepsOnly = mrgitest::GrabRGB(window);
    renderer->SetPass(pass);
    pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
    window->Render();
    vtkSmartPointer<vtkImageData> off = mrgitest::GrabRGB(window);
    DebugWrite(
      plain, std::string("TestMRGIPipelineTranslucent-plain-") + (mode.Peeling ? "peel" : "oit"));
    DebugWrite(
      off, std::string("TestMRGIPipelineTranslucent-off-") + (mode.Peeling ? "peel" : "oit"));
    std::printf("%s: IndirectMode Off vs VTK max difference %.0f / 255 (%d pixels differ); "
                "vtkRenderStepsPass alone vs VTK %.0f / 255 (%d pixels)\n",
      mode.Name, MaxDifference(plain, off), CountDifferent(plain, off, 1.0),
      MaxDifference(plain, stepsOnly), CountDifferent(plain, stepsOnly, 1.0));
    MRGI_TEST_CHECK(MaxDifference(plain, off) <= 1.0);
    // The scene is one where the resolution of translucency shows.
    MRGI_TEST_CHECK(CountDifferent(plain, stepsOnly, 3.0) > 50);

    // Full: the spheres change the image where they are, and only there.
    pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
    blue->VisibilityOff();
    green->VisibilityOff();
    window->Render();
    MRGI_TEST_CHECK(pass->GetIndirectComputed());
    vtkSmartPointer<vtkImageData> without = mrgitest::GrabRGB(window);
    vtkNew<vtkImageData> indirectWithout;
    MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, indirectWithout));
    blue->VisibilityOn();
    green->VisibilityOn();
    window->Render();
    MRGI_TEST_CHECK(pass->GetIndirectComputed());
    vtkSmartPointer<vtkImageData> with = mrgitest::GrabRGB(window);
    DebugWrite(
      with, std::string("TestMRGIPipelineTranslucent-full-") + (mode.Peeling ? "peel" : "oit"));
    vtkNew<vtkImageData> position, normal, albedo, indirect, colour;
    MRGI_TEST_CHECK(pass->GetGBuffer(window, position, normal, albedo));
    MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, indirect));
    MRGI_TEST_CHECK(pass->GetColorBuffer(window, colour));
    MRGI_TEST_CHECK(AllFinite(colour) && AllFinite(indirect));
    double sphereMean[3], withoutMean[3];
    mrgitest::MeanColor(
      with, sphereBox[0] + 5, sphereBox[1] + 5, sphereBox[2] - 5, sphereBox[3] - 5, sphereMean);
    mrgitest::MeanColor(
      without, sphereBox[0] + 5, sphereBox[1] + 5, sphereBox[2] - 5, sphereBox[3] - 5, withoutMean);
    std::printf("  full: sphere region %.0f %.0f %.0f, without spheres %.0f %.0f %.0f; outside "
                "the spheres max difference %.0f\n",
      sphereMean[0], sphereMean[1], sphereMean[2], withoutMean[0], withoutMean[1], withoutMean[2],
      MaxDifferenceOutside(with, without, sphereBox));
    MRGI_TEST_CHECK(std::fabs(sphereMean[0] - withoutMean[0]) +
        std::fabs(sphereMean[1] - withoutMean[1]) + std::fabs(sphereMean[2] - withoutMean[2]) >
      40);
    MRGI_TEST_CHECK(MaxDifferenceOutside(with, without, sphereBox) <= 1.0);
    // The translucent spheres are neither in the G-buffer nor in the RSM:
    // the indirect light is the same with and without them, and behind the
    // nearer sphere's centre the G-buffer holds the wall.
    MRGI_TEST_CHECK(MaxDifference(indirect, indirectWithout) < 1e-6);
    renderer->SetWorldPoint(0.45, -0.1, 0.6, 1);
    renderer->WorldToDisplay();
    const int x = static_cast<int>(renderer->GetDisplayPoint()[0]);
    const int y = static_cast<int>(renderer->GetDisplayPoint()[1]);
    double eye[3] = { At(position, x, y, 0), At(position, x, y, 1), At(position, x, y, 2) };
    double world[3];
    EyeToWorld(renderer, eye, world);
    std::printf(
      "  G-buffer behind the blue sphere (pixel %d %d): world z %.3f, albedo %.3f %.3f %.3f\n", x,
      y, world[2], At(albedo, x, y, 0), At(albedo, x, y, 1), At(albedo, x, y, 2));
    MRGI_TEST_CHECK(Valid(position, x, y) && std::fabs(world[2] + 1.0) < 1e-3);
    for (int c = 0; c < 3; ++c)
    {
      MRGI_TEST_CHECK(std::fabs(At(albedo, x, y, c) - 0.8) < 0.003);
    }
  }

  // The vtkRenderStepsPass MRGI used draws everything again on its own.
  renderer->SetUseDepthPeeling(0);
  renderer->SetPass(pass);
  window->Render();
  renderer->SetPass(steps);
  window->Render();
  vtkSmartPointer<vtkImageData> reused = mrgitest::GrabRGB(window);
  vtkNew<vtkRenderStepsPass> fresh;
  renderer->SetPass(fresh);
  window->Render();
  vtkSmartPointer<vtkImageData> freshImage = mrgitest::GrabRGB(window);
  std::printf("vtkRenderStepsPass after MRGI vs a fresh one: max difference %.0f\n",
    MaxDifference(reused, freshImage));
  MRGI_TEST_CHECK(MaxDifference(reused, freshImage) <= 1.0);

  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  steps->ReleaseGraphicsResources(window);
  fresh->ReleaseGraphicsResources(window);
  return 0;
}
