// vtkMRGIPass with direct light only must not change what VTK draws; its HDR
// buffer must hold the unclamped colour; its stage timings must be real GPU
// times; ReleaseGraphicsResources must free everything; zero-size and 1x1
// windows must neither crash nor produce NaN.
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <cmath>

namespace
{
double MaxDifference(vtkImageData* a, vtkImageData* b)
{
  vtkDataArray* sa = a->GetPointData()->GetScalars();
  vtkDataArray* sb = b->GetPointData()->GetScalars();
  double worst = 0;
  for (vtkIdType i = 0; i < sa->GetNumberOfValues(); ++i)
  {
    worst = std::fmax(worst, std::fabs(sa->GetVariantValue(i).ToDouble() - sb->GetVariantValue(i).ToDouble()));
  }
  return worst;
}
}

int main()
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(160, 120);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene("cornell-spot");
  MRGI_TEST_CHECK(builder->Build(renderer));

  // 1. Reference: VTK's own rendering, no pass.
  window->Render();
  vtkSmartPointer<vtkImageData> plain = mrgitest::GrabRGB(window);

  // 2. Through vtkMRGIPass with indirect light and direct shadows off: the
  // same pixels (non-square window on purpose), and nothing but the scene
  // and the copy run.
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> pass;
  pass->SetDelegatePass(steps);
  pass->SetStageTimingEnabled(true);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  pass->SetDirectShadowsToOff();
  renderer->SetPass(pass);
  window->Render();
  vtkSmartPointer<vtkImageData> withPass = mrgitest::GrabRGB(window);
  const double diff = MaxDifference(plain, withPass);
  std::printf("max difference plain vs pass (indirect off): %.1f / 255\n", diff);
  MRGI_TEST_CHECK(diff <= 1.0);
  MRGI_TEST_CHECK(pass->GetBufferSize()[0] == 160 && pass->GetBufferSize()[1] == 120);
  MRGI_TEST_CHECK(!pass->GetIndirectComputed());
  MRGI_TEST_CHECK(pass->GetReflectiveShadowMapPass()->GetNumberOfRenders() == 0);

  // 3. Stage timings from vtkRenderTimerLog: the first fetch switches the
  // window's timer log on (between frames), the next frame is timed.
  MRGI_TEST_CHECK(pass->FetchStageTimings(window, true) == 0);
  window->Render();
  int stages = pass->FetchStageTimings(window, true);
  std::printf("%d stages (indirect off)\n", stages);
  MRGI_TEST_CHECK(stages == 3);
  MRGI_TEST_CHECK(std::string(pass->GetStageName(0)) == "scene");
  MRGI_TEST_CHECK(std::string(pass->GetStageName(1)) == "forward");
  MRGI_TEST_CHECK(std::string(pass->GetStageName(2)) == "output");

  // With indirect light: every stage runs, and the image gets brighter
  // (indirect light only adds), strictly so somewhere.
  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  window->Render();
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  vtkSmartPointer<vtkImageData> withGI = mrgitest::GrabRGB(window);
  double brighter = 0, darker = 0;
  for (vtkIdType i = 0; i < withGI->GetPointData()->GetScalars()->GetNumberOfValues(); ++i)
  {
    const double d = withGI->GetPointData()->GetScalars()->GetVariantValue(i).ToDouble() -
      plain->GetPointData()->GetScalars()->GetVariantValue(i).ToDouble();
    brighter = std::fmax(brighter, d);
    darker = std::fmax(darker, -d);
  }
  std::printf("indirect light: brightest gain %.0f, largest loss %.0f (of 255)\n", brighter, darker);
  MRGI_TEST_CHECK(brighter > 10 && darker <= 1);
  stages = pass->FetchStageTimings(window, true);
  const char* expected[] = { "scene", "rsm", "vpl", "gather", "add", "forward", "output" };
  MRGI_TEST_CHECK(stages == 7);
  for (int s = 0; s < stages; ++s)
  {
    MRGI_TEST_CHECK(std::string(pass->GetStageName(s)) == expected[s]);
  }
  for (int s = 0; s < stages; ++s)
  {
    const double ms = pass->GetStageTimeMilliseconds(s);
    std::printf("  %s %.3f ms\n", pass->GetStageName(s), ms);
    MRGI_TEST_CHECK(std::isfinite(ms) && ms >= 0.0 && ms < 60000.0);
  }
  MRGI_TEST_CHECK(pass->GetStageName(stages) == nullptr);
  MRGI_TEST_CHECK(pass->GetStageTimeMilliseconds(-1) < 0);

  // 4. HDR: a light of intensity 4 saturates the window but not the buffer.
  vtkLight* light = vtkLight::SafeDownCast(renderer->GetLights()->GetItemAsObject(0));
  MRGI_TEST_CHECK(light != nullptr);
  light->SetIntensity(4.0);
  window->Render();
  vtkNew<vtkImageData> hdr;
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, hdr));
  vtkFloatArray* values = vtkFloatArray::SafeDownCast(hdr->GetPointData()->GetScalars());
  MRGI_TEST_CHECK(values && values->GetNumberOfComponents() == 4);
  float maxValue = 0;
  for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
  {
    MRGI_TEST_CHECK(std::isfinite(values->GetValue(i)));
    maxValue = std::fmax(maxValue, values->GetValue(i));
  }
  std::printf("HDR max %.3f\n", maxValue);
  MRGI_TEST_CHECK(maxValue > 1.5f);

  // 5. Resize to 1x1 and back: still finite, still the right size.
  window->SetSize(1, 1);
  window->Render();
  MRGI_TEST_CHECK(pass->GetBufferSize()[0] == 1 && pass->GetBufferSize()[1] == 1);
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, hdr));
  for (int c = 0; c < 4; ++c)
  {
    MRGI_TEST_CHECK(std::isfinite(hdr->GetScalarComponentAsDouble(0, 0, 0, c)));
  }

  // 6. A zero-size window: an error, not a crash, and the buffers survive.
  window->SetSize(0, 0);
  window->Render();
  window->SetSize(64, 48);
  window->Render();
  MRGI_TEST_CHECK(pass->GetBufferSize()[0] == 64 && pass->GetBufferSize()[1] == 48);

  // 7. No delegate: a warning, nothing drawn, no crash.
  vtkNew<vtkMRGIPass> lonely;
  renderer->SetPass(lonely);
  window->Render();
  MRGI_TEST_CHECK(lonely->GetBufferSize()[0] == 0);
  renderer->SetPass(pass);

  // 8. ReleaseGraphicsResources frees everything.
  pass->ReleaseGraphicsResources(window);
  MRGI_TEST_CHECK(pass->GetBufferSize()[0] == 0);
  vtkNew<vtkImageData> none;
  MRGI_TEST_CHECK(!pass->GetColorBuffer(window, none));
  window->Render(); // resources come back on demand
  MRGI_TEST_CHECK(pass->GetBufferSize()[0] == 64);
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  lonely->ReleaseGraphicsResources(window);
  return 0;
}
