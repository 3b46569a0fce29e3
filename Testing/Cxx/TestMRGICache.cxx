// "Model only what a scene requires": reflective shadow maps and the VPL
// cache are not re-rendered while lights and geometry are unchanged (a
// camera move does not touch them), and are when a light or a prop changes;
// lights that are off or cannot reach anything visible get no map at all.
// The area lights' light is not recomputed while nothing it depends on
// changed, and is when the camera, a light, its picture, a prop or a setting
// changes.
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkDataArray.h"
#include "vtkActorCollection.h"
#include "vtkCallbackCommand.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIPass.h"
#include "vtkProperty.h"
#include "vtkUnsignedCharArray.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
std::vector<double> Values(vtkImageData* image)
{
  vtkDataArray* a = image->GetPointData()->GetScalars();
  std::vector<double> v(static_cast<size_t>(a->GetNumberOfValues()));
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    v[static_cast<size_t>(i)] = a->GetVariantValue(i).ToDouble();
  }
  return v;
}

void TestAreaLightReuse()
{
  mrgitest::PassScene scene(64, 64, "cornell-area");
  vtkRenderWindow* window = scene.Window;
  vtkRenderer* renderer = scene.Renderer;
  vtkMRGIPass* pass = scene.Pass;
  MRGI_TEST_CHECK(scene.Builder->GetNumberOfAreaLights() == 1);
  vtkMRGIAreaLight* light = scene.Builder->GetAreaLight(0);
  light->SetNumberOfSamples(32);
  pass->AddAreaLight(light);
  MRGI_TEST_CHECK(pass->GetAreaLightReuse()); // the default
  auto frame = [&]() {
    window->Render();
    MRGI_TEST_CHECK(pass->GetAreaLightsComputed());
    vtkNew<vtkImageData> color, area;
    MRGI_TEST_CHECK(pass->GetColorBuffer(window, color) && pass->GetAreaLightBuffer(window, area));
    return std::make_pair(Values(color), Values(area));
  };
  auto first = frame();
  MRGI_TEST_CHECK(pass->GetNumberOfAreaLightUpdates() == 1);
  // Unchanged: reused, and the image is the same.
  auto again = frame();
  MRGI_TEST_CHECK(pass->GetNumberOfAreaLightUpdates() == 1);
  MRGI_TEST_CHECK(again == first);
  // Each input changes it once.
  vtkIdType expected = 1;
  auto changes = [&](const char* what) {
    auto changed = frame();
    ++expected;
    std::printf("area-light reuse: %s -> %lld updates\n", what,
      static_cast<long long>(pass->GetNumberOfAreaLightUpdates()));
    MRGI_TEST_CHECK(pass->GetNumberOfAreaLightUpdates() == expected);
    frame();
    MRGI_TEST_CHECK(pass->GetNumberOfAreaLightUpdates() == expected);
    return changed;
  };
  renderer->GetActiveCamera()->Azimuth(4.0);
  auto turned = changes("camera turned");
  MRGI_TEST_CHECK(turned.second != first.second);
  light->SetIntensity(2.0 * light->GetIntensity());
  changes("light intensity");
  vtkNew<vtkImageData> picture;
  picture->SetDimensions(2, 2, 1);
  picture->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* texels = static_cast<unsigned char*>(picture->GetScalarPointer());
  for (int i = 0; i < 12; ++i)
  {
    texels[i] = 200;
  }
  light->SetTextureData(picture);
  auto pictured = changes("picture set");
  texels[0] = 10; // the next video frame
  picture->Modified();
  auto next = changes("picture modified");
  MRGI_TEST_CHECK(next.second != pictured.second);
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  actors->GetNextActor()->GetProperty()->SetColor(0.2, 0.9, 0.3);
  changes("prop colour");
  pass->SetAreaLightVisibility(vtkMRGIPass::VisibilityNaive);
  changes("visibility mode");
  pass->GetMultiresolution()->SetDepthThreshold(2.0);
  changes("multiresolution setting");
  window->SetSize(48, 64);
  changes("window size");
  // Released resources, statistics and reuse off: computed every frame.
  pass->ReleaseGraphicsResources(window);
  changes("resources released");
  pass->AreaLightReuseOff();
  window->Render();
  window->Render();
  MRGI_TEST_CHECK(pass->GetNumberOfAreaLightUpdates() == expected + 2);
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
}
}

// The reflective shadow maps and the VPL cache follow lights, props and
// settings, not the camera; NaN input warns once per change of the data.
static void TestMapsAndVPLCache()
{
  mrgitest::PassScene scene(96, 96, "cornell-spot");
  vtkRenderWindow* window = scene.Window;
  vtkRenderer* renderer = scene.Renderer;
  vtkMRGIPass* pass = scene.Pass;
  vtkMRGIReflectiveShadowMapPass* rsm = pass->GetReflectiveShadowMapPass();
  vtkMRGIVPLSelection* vpls = pass->GetVPLSelection();

  window->Render();
  MRGI_TEST_CHECK(rsm->GetNumberOfViews() == 1); // one spot light, one view
  const vtkIdType renders = rsm->GetNumberOfRenders();
  const vtkIdType selections = vpls->GetNumberOfSelections();
  MRGI_TEST_CHECK(renders == 1 && selections == 1);

  // Unchanged scene: nothing re-rendered.
  window->Render();
  window->Render();
  MRGI_TEST_CHECK(rsm->GetNumberOfRenders() == renders);
  MRGI_TEST_CHECK(vpls->GetNumberOfSelections() == selections);

  // The camera moves: the maps are the light's, not the camera's.
  renderer->GetActiveCamera()->Azimuth(10);
  window->Render();
  MRGI_TEST_CHECK(rsm->GetNumberOfRenders() == renders);
  MRGI_TEST_CHECK(pass->GetIndirectComputed());

  // A light changes: re-rendered once, then stable again.
  vtkLight* light = vtkLight::SafeDownCast(renderer->GetLights()->GetItemAsObject(0));
  light->SetIntensity(0.5);
  window->Render();
  MRGI_TEST_CHECK(rsm->GetNumberOfRenders() == renders + 1);
  MRGI_TEST_CHECK(vpls->GetNumberOfSelections() == selections + 1);
  window->Render();
  MRGI_TEST_CHECK(rsm->GetNumberOfRenders() == renders + 1);

  // A prop moves: re-rendered.
  vtkActor* actor = renderer->GetActors()->GetLastActor();
  actor->SetPosition(5, 0, 0);
  window->Render();
  MRGI_TEST_CHECK(rsm->GetNumberOfRenders() == renders + 2);

  // A VPL setting changes: the maps stay, the VPL cache is rebuilt.
  pass->SetNumberOfVPLs(64);
  window->Render();
  MRGI_TEST_CHECK(rsm->GetNumberOfRenders() == renders + 2);
  MRGI_TEST_CHECK(vpls->GetNumberOfSelections() == selections + 3);
  MRGI_TEST_CHECK(vpls->GetVPLCount() == 64);

  // The light switched off: no views, no indirect light, same image as off.
  light->SwitchOff();
  window->Render();
  MRGI_TEST_CHECK(rsm->GetNumberOfViews() == 0);
  MRGI_TEST_CHECK(!pass->GetIndirectComputed());
  light->SwitchOn();

  // A spot aimed away from everything visible: no views either.
  {
    vtkSmartPointer<vtkRenderWindow> w2 = mrgitest::HeadlessWindow(64, 64);
    vtkNew<vtkRenderer> r2;
    w2->AddRenderer(r2);
    vtkNew<vtkPlaneSource> plane;
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(plane->GetOutputPort());
    vtkNew<vtkActor> floor;
    floor->SetMapper(mapper);
    r2->AddActor(floor);
    vtkNew<vtkLight> away;
    away->SetLightTypeToSceneLight();
    away->SetPositional(true);
    away->SetConeAngle(20);
    away->SetPosition(0, 0, 5);
    away->SetFocalPoint(0, 0, 10); // pointing away from the plane at z = 0
    r2->AddLight(away);
    r2->ResetCamera();
    vtkNew<vtkRenderStepsPass> steps2;
    vtkNew<vtkMRGIPass> pass2;
    pass2->SetDelegatePass(steps2);
    r2->SetPass(pass2);
    w2->Render();
    MRGI_TEST_CHECK(pass2->GetReflectiveShadowMapPass()->GetNumberOfViews() == 0);
    MRGI_TEST_CHECK(!pass2->GetIndirectComputed());
    // Turned towards the plane, the same light gets its view.
    away->SetFocalPoint(0, 0, 0);
    w2->Render();
    MRGI_TEST_CHECK(pass2->GetReflectiveShadowMapPass()->GetNumberOfViews() == 1);
    MRGI_TEST_CHECK(pass2->GetIndirectComputed());
    r2->SetPass(nullptr);
    pass2->ReleaseGraphicsResources(w2);
  }

  // NaN coordinates in an actor's data: one warning per change of the data,
  // not one per frame, and no NaN in the image.
  {
    vtkNew<vtkPlaneSource> plane;
    plane->SetResolution(4, 4);
    plane->SetOrigin(100, 1, 100);
    plane->SetPoint1(400, 1, 100);
    plane->SetPoint2(100, 1, 400);
    plane->Update();
    vtkNew<vtkPolyData> poisoned;
    poisoned->DeepCopy(plane->GetOutput());
    poisoned->GetPoints()->SetPoint(3, std::nan(""), 0, 0);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(poisoned);
    vtkNew<vtkActor> bad;
    bad->SetMapper(mapper);
    renderer->AddActor(bad);
    int warnings = 0;
    vtkNew<vtkCallbackCommand> counter;
    counter->SetClientData(&warnings);
    counter->SetCallback([](vtkObject*, unsigned long, void* data, void*) { ++*static_cast<int*>(data); });
    rsm->AddObserver(vtkCommand::WarningEvent, counter);
    window->Render();
    window->Render();
    MRGI_TEST_CHECK(warnings == 1);
    poisoned->Modified();
    window->Render();
    MRGI_TEST_CHECK(warnings == 2);
    vtkNew<vtkImageData> color;
    MRGI_TEST_CHECK(pass->GetColorBuffer(window, color));
    vtkDataArray* values = color->GetPointData()->GetScalars();
    for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
    {
      MRGI_TEST_CHECK(std::isfinite(values->GetVariantValue(i).ToDouble()));
    }
    rsm->RemoveObserver(counter);
  }

  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(
    argc, argv, { MRGI_TEST_CASE(TestAreaLightReuse), MRGI_TEST_CASE(TestMapsAndVPLCache) });
}
