// vtkMRGIPass with every kind of vtkLight VTK applications use:
// a spot light (one perspective RSM view), a directional light (one
// orthographic view), a point light (cube faces, the faces that see nothing
// skipped), ParaView's light kit (vtkLightKit::AddLightsToRenderer: key, fill,
// head and two back lights, camera lights and a headlight), a headlight alone,
// and all of them together with a switched-off light, a zero-intensity light
// and a spot light pointing away from everything, which get no view ("model
// only what the scene requires"). For each: the RSM views and the light each
// belongs to (GetNumberOfViews, GetViewLight), every view holds geometry,
// indirect light > 0 where the light reaches, no NaN anywhere; with no light
// reaching the scene nothing is gathered and the image is the direct one.
#include "TestMRGIPipelineCommon.h"

#include "vtkCubeSource.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkLightKit.h"
#include "vtkMRGIReflectiveShadowMapPass.h"

#include <set>
#include <vector>

namespace
{
vtkSmartPointer<vtkLight> Spot(const double position[3], const double focal[3], double cone)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetConeAngle(cone);
  light->SetPosition(position[0], position[1], position[2]);
  light->SetFocalPoint(focal[0], focal[1], focal[2]);
  return light;
}

vtkSmartPointer<vtkLight> Directional(const double from[3])
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetPosition(from[0], from[1], from[2]);
  light->SetFocalPoint(0, 0, 0);
  return light;
}

struct Outcome
{
  int Views = 0;
  std::set<int> Lights;
  double Indirect = 0;
};

// Render, then check buffers for NaN and every view for geometry.
Outcome RenderAndCheck(const char* what, vtkRenderWindow* window, vtkMRGIPass* pass)
{
  window->Render();
  mrgipipe::DebugWrite(mrgitest::GrabRGB(window), std::string("TestMRGIPipelineLights-") + what);
  Outcome out;
  vtkMRGIReflectiveShadowMapPass* rsm = pass->GetReflectiveShadowMapPass();
  out.Views = rsm->GetNumberOfViews();
  vtkNew<vtkImageData> position, normal, flux;
  for (int v = 0; v < out.Views; ++v)
  {
    out.Lights.insert(rsm->GetViewLight(v));
    MRGI_TEST_CHECK(rsm->ReadView(window, v, position, normal, flux));
    MRGI_TEST_CHECK(mrgipipe::AllFinite(position) && mrgipipe::AllFinite(flux));
    MRGI_TEST_CHECK(mrgipipe::CountValid(position) > 0);
  }
  vtkNew<vtkImageData> colour;
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, colour));
  MRGI_TEST_CHECK(mrgipipe::AllFinite(colour));
  if (pass->GetIndirectComputed())
  {
    vtkNew<vtkImageData> indirect;
    MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, indirect));
    MRGI_TEST_CHECK(mrgipipe::AllFinite(indirect));
    int dims[3];
    indirect->GetDimensions(dims);
    out.Indirect = mrgipipe::SumRGB(indirect, 0, 0, dims[0], dims[1]);
  }
  std::printf("%-28s %d views, lights {", what, out.Views);
  for (int l : out.Lights)
  {
    std::printf(" %d", l);
  }
  std::printf(
    " }, indirect computed %d, sum %.3f\n", pass->GetIndirectComputed() ? 1 : 0, out.Indirect);
  return out;
}
}

int main()
{
  using namespace mrgipipe;
  const int W = 160, H = 120;
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(W, H);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  const double cf[3] = { 0, -1, 0 }, nf[3] = { 0, 1, 0 };
  const double cb[3] = { 0, 0.5, -1.5 }, nb[3] = { 0, 0, 1 };
  renderer->AddActor(MakeQuad(cf, nf, 3, 0.8, 0.8, 0.8, 4));
  renderer->AddActor(MakeQuad(cb, nb, 3, 0.8, 0.8, 0.8, 4));
  vtkNew<vtkCubeSource> cube;
  vtkSmartPointer<vtkActor> box = MakeActor(cube, 0.9, 0.2, 0.1);
  box->SetPosition(-0.3, -0.5, -0.3);
  renderer->AddActor(box);
  renderer->GetActiveCamera()->SetPosition(0.5, 1.0, 4.5);
  renderer->GetActiveCamera()->SetFocalPoint(0, -0.2, 0);
  renderer->ResetCameraClippingRange();

  vtkSmartPointer<vtkMRGIPass> pass = Install(renderer);
  pass->SetRSMResolution(64);
  const double spotFrom[3] = { 1.0, 2.5, 2.0 }, spotAt[3] = { 0, -0.8, 0 };
  const double sun[3] = { -1.0, 2.0, 1.0 };
  const double above[3] = { 0.5, 1.8, 0.8 };

  // Spot light: one perspective view.
  renderer->AddLight(Spot(spotFrom, spotAt, 30));
  Outcome spot = RenderAndCheck("spot", window, pass);
  MRGI_TEST_CHECK(spot.Views == 1 && spot.Lights == std::set<int>{ 0 } && spot.Indirect > 0);

  // Directional light: one orthographic view.
  renderer->RemoveAllLights();
  renderer->AddLight(Directional(sun));
  Outcome directional = RenderAndCheck("directional", window, pass);
  MRGI_TEST_CHECK(directional.Views == 1 && directional.Lights == std::set<int>{ 0 });
  MRGI_TEST_CHECK(directional.Indirect > 0);

  // Point light above the scene: cube faces, the upward face (nothing there) skipped.
  renderer->RemoveAllLights();
  renderer->AddLight(Spot(above, spotAt, 180));
  Outcome point = RenderAndCheck("point", window, pass);
  MRGI_TEST_CHECK(point.Views >= 2 && point.Views <= 5 && point.Lights == std::set<int>{ 0 });
  MRGI_TEST_CHECK(point.Indirect > 0);

  // ParaView's light kit: five lights (camera lights and a headlight), one view each.
  renderer->RemoveAllLights();
  vtkNew<vtkLightKit> kit;
  kit->AddLightsToRenderer(renderer);
  MRGI_TEST_CHECK(renderer->GetLights()->GetNumberOfItems() == 5);
  Outcome lightKit = RenderAndCheck("light kit", window, pass);
  MRGI_TEST_CHECK(lightKit.Views == 5 && lightKit.Lights == (std::set<int>{ 0, 1, 2, 3, 4 }));
  MRGI_TEST_CHECK(lightKit.Indirect > 0);
  // Camera lights follow the camera: their views change when it moves.
  const vtkMTimeType before = pass->GetReflectiveShadowMapPass()->GetContentTime();
  renderer->GetActiveCamera()->Azimuth(30);
  renderer->ResetCameraClippingRange();
  Outcome moved = RenderAndCheck("light kit, camera moved", window, pass);
  MRGI_TEST_CHECK(moved.Views == 5);
  MRGI_TEST_CHECK(pass->GetReflectiveShadowMapPass()->GetContentTime() > before);
  renderer->GetActiveCamera()->Azimuth(-30);
  renderer->ResetCameraClippingRange();

  // A headlight alone.
  renderer->RemoveAllLights();
  vtkNew<vtkLight> headlight;
  headlight->SetLightTypeToHeadlight();
  renderer->AddLight(headlight);
  Outcome head = RenderAndCheck("headlight", window, pass);
  MRGI_TEST_CHECK(head.Views == 1 && head.Lights == std::set<int>{ 0 } && head.Indirect > 0);

  // Everything at once, with three lights that must get no view.
  renderer->RemoveAllLights();
  renderer->AddLight(Spot(spotFrom, spotAt, 30)); // 0
  vtkSmartPointer<vtkLight> off = Spot(spotFrom, spotAt, 30);
  off->SwitchOff();
  renderer->AddLight(off);              // 1: switched off
  renderer->AddLight(Directional(sun)); // 2
  const double away[3] = { 0.5, 6.0, 12.0 };
  renderer->AddLight(Spot(spotFrom, away, 20)); // 3: points away from everything
  renderer->AddLight(Spot(above, spotAt, 180)); // 4: point light
  vtkSmartPointer<vtkLight> dark = Spot(spotFrom, spotAt, 30);
  dark->SetIntensity(0.0);
  renderer->AddLight(dark); // 5: zero intensity
  vtkNew<vtkLight> head2;
  head2->SetLightTypeToHeadlight();
  renderer->AddLight(head2); // 6: headlight
  Outcome all = RenderAndCheck("all together", window, pass);
  MRGI_TEST_CHECK(all.Lights == (std::set<int>{ 0, 2, 4, 6 }));
  MRGI_TEST_CHECK(all.Views == 1 + 1 + point.Views + 1);
  MRGI_TEST_CHECK(all.Indirect > spot.Indirect);

  // Only lights that reach nothing: no views, nothing gathered, the direct image.
  renderer->RemoveAllLights();
  renderer->AddLight(off);
  renderer->AddLight(Spot(spotFrom, away, 20));
  Outcome none = RenderAndCheck("none reaching", window, pass);
  MRGI_TEST_CHECK(none.Views == 0 && !pass->GetIndirectComputed());
  vtkSmartPointer<vtkImageData> gi = mrgitest::GrabRGB(window);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  window->Render();
  vtkSmartPointer<vtkImageData> direct = mrgitest::GrabRGB(window);
  MRGI_TEST_CHECK(MaxDifference(gi, direct) <= 1.0);
  // And IndirectMode Off is VTK's own image for the light kit scene.
  renderer->RemoveAllLights();
  kit->AddLightsToRenderer(renderer);
  window->Render();
  vtkSmartPointer<vtkImageData> offKit = mrgitest::GrabRGB(window);
  renderer->SetPass(nullptr);
  window->Render();
  vtkSmartPointer<vtkImageData> plainKit = mrgitest::GrabRGB(window);
  std::printf("light kit: IndirectMode Off vs VTK max difference %.0f / 255\n",
    MaxDifference(offKit, plainKit));
  MRGI_TEST_CHECK(MaxDifference(offKit, plainKit) <= 1.0);

  pass->ReleaseGraphicsResources(window);
  return 0;
}
