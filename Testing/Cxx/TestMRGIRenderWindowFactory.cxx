// The window factory's backends (MRGI_BACKEND, the backend argument, the
// errors for unknown and unavailable backends) and the OSMesa window itself:
// core context, resizing, released resources, and an EGL and an OSMesa window
// alternating in one process with the same picture.
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkMRGIEGLRenderWindow.h"
#include "vtkMRGIOSMesaRenderWindow.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIRenderWindowFactory.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>

namespace
{
// The environment this program's cases change, restored by the destructor.
struct Environment
{
  Environment()
  {
    unsetenv("MRGI_BACKEND");
    unsetenv("MRGI_WINDOW");
    unsetenv("MRGI_OSMESA_LIBRARY");
  }
  ~Environment()
  {
    unsetenv("MRGI_BACKEND");
    unsetenv("MRGI_WINDOW");
    unsetenv("MRGI_OSMESA_LIBRARY");
  }
};

bool Contains(const std::string& text, const char* fragment)
{
  if (text.find(fragment) == std::string::npos)
  {
    std::fprintf(stderr, "expected '%s' in '%s'\n", fragment, text.c_str());
    return false;
  }
  return true;
}

void AddSphere(vtkRenderer* renderer);
void CheckSphereImage(vtkRenderWindow* window, int width, int height);

vtkSmartPointer<vtkRenderWindow> Make(int kind, const char* backend, std::string& why)
{
  why.clear();
  return vtkSmartPointer<vtkRenderWindow>::Take(
    vtkMRGIRenderWindowFactory::CreateRenderWindow(kind, backend, &why));
}

// Runs first: the EGL backend renders without ever loading libOSMesa (so
// ParaView and EGL programs never see its GL symbols).
void TestEGLDoesNotLoadOSMesa()
{
  Environment env;
  std::string why;
  vtkSmartPointer<vtkRenderWindow> window = Make(vtkMRGIRenderWindowFactory::Headless, "egl", why);
  if (!window)
  {
    MRGI_TEST_FAIL("no EGL window: %s", why.c_str());
  }
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  AddSphere(renderer);
  window->SetSize(32, 32);
  window->SetMultiSamples(0);
  window->Render();
  CheckSphereImage(window, 32, 32);
  for (const char* name : { "libOSMesa.so.8", "libOSMesa.so.6" })
  {
    void* loaded = dlopen(name, RTLD_NOW | RTLD_NOLOAD);
    MRGI_TEST_CHECK(loaded == nullptr);
    if (loaded)
    {
      dlclose(loaded);
    }
  }
}

// Before any OSMesa window: once libOSMesa is loaded it stays loaded.
void TestOSMesaLibraryMissing()
{
  Environment env;
  setenv("MRGI_OSMESA_LIBRARY", "/nonexistent/libOSMesa.so.8", 1);
  setenv("MRGI_BACKEND", "osmesa", 1);
  std::string why;
  vtkSmartPointer<vtkRenderWindow> window =
    Make(vtkMRGIRenderWindowFactory::Headless, nullptr, why);
  // Asked for by name: an error, never a silent EGL window instead.
  MRGI_TEST_CHECK(window == nullptr);
  MRGI_TEST_CHECK(Contains(why, "/nonexistent/libOSMesa.so.8"));
  MRGI_TEST_CHECK(Contains(why, "OSMesa"));
}

void TestUnknownBackend()
{
  Environment env;
  setenv("MRGI_BACKEND", "vulkan", 1);
  std::string why;
  MRGI_TEST_CHECK(Make(vtkMRGIRenderWindowFactory::Headless, nullptr, why) == nullptr);
  MRGI_TEST_CHECK(Contains(why, "MRGI_BACKEND='vulkan'"));
  MRGI_TEST_CHECK(Contains(why, "auto, egl, osmesa, x"));
  MRGI_TEST_CHECK(
    std::strcmp(vtkMRGIRenderWindowFactory::GetWindowKindName(vtkMRGIRenderWindowFactory::Headless),
      "none") == 0);
  unsetenv("MRGI_BACKEND");
  MRGI_TEST_CHECK(Make(vtkMRGIRenderWindowFactory::Headless, "EGL", why) == nullptr);
  MRGI_TEST_CHECK(Contains(why, "backend='EGL'"));
  setenv("MRGI_WINDOW", "gl", 1);
  MRGI_TEST_CHECK(Make(vtkMRGIRenderWindowFactory::Headless, nullptr, why) == nullptr);
  MRGI_TEST_CHECK(Contains(why, "MRGI_WINDOW='gl'"));
}

void TestXWithoutDisplay()
{
  Environment env;
  unsetenv("DISPLAY");
  std::string why;
  setenv("MRGI_BACKEND", "x", 1);
  MRGI_TEST_CHECK(Make(vtkMRGIRenderWindowFactory::Headless, nullptr, why) == nullptr);
  MRGI_TEST_CHECK(Contains(why, "DISPLAY"));
  unsetenv("MRGI_BACKEND");
  MRGI_TEST_CHECK(Make(vtkMRGIRenderWindowFactory::Interactive, nullptr, why) == nullptr);
  MRGI_TEST_CHECK(Contains(why, "DISPLAY"));
}

void TestBackendChoice()
{
  Environment env;
  unsetenv("DISPLAY");
  std::string why;
  struct Row
  {
    const char* Variable;
    const char* Value;
    const char* Argument;
    const char* Expected;
  };
  const Row rows[] = {
    { nullptr, nullptr, nullptr, "egl" },      // automatic, headless: EGL first
    { nullptr, nullptr, "auto", "egl" },       //
    { "MRGI_BACKEND", "egl", nullptr, "egl" }, //
    { "MRGI_BACKEND", "osmesa", nullptr, "osmesa" },
    { "MRGI_BACKEND", "egl", "osmesa", "osmesa" },  // the argument wins
    { "MRGI_BACKEND", "osmesa", "auto", "egl" },    // "auto" asks for no backend
    { "MRGI_WINDOW", "osmesa", nullptr, "osmesa" }, // the older variable
  };
  for (const Row& row : rows)
  {
    unsetenv("MRGI_BACKEND");
    unsetenv("MRGI_WINDOW");
    if (row.Variable)
    {
      setenv(row.Variable, row.Value, 1);
    }
    for (int kind : { vtkMRGIRenderWindowFactory::Headless, vtkMRGIRenderWindowFactory::Automatic })
    {
      vtkSmartPointer<vtkRenderWindow> window = Make(kind, row.Argument, why);
      if (!window)
      {
        MRGI_TEST_FAIL("%s=%s, argument %s: no window: %s", row.Variable ? row.Variable : "-",
          row.Value ? row.Value : "-", row.Argument ? row.Argument : "-", why.c_str());
      }
      const char* got = vtkMRGIRenderWindowFactory::GetBackendName(window);
      if (std::strcmp(got, row.Expected) != 0)
      {
        MRGI_TEST_FAIL("%s=%s, argument %s: backend %s, expected %s",
          row.Variable ? row.Variable : "-", row.Value ? row.Value : "-",
          row.Argument ? row.Argument : "-", got, row.Expected);
      }
      const std::string line = vtkMRGIRenderWindowFactory::DescribeRenderWindow(window);
      MRGI_TEST_CHECK(line.rfind(row.Expected, 0) == 0);
      MRGI_TEST_CHECK(Contains(line, "llvmpipe") || Contains(line, "("));
    }
  }
  setenv("MRGI_BACKEND", "osmesa", 1);
  MRGI_TEST_CHECK(
    std::strcmp(vtkMRGIRenderWindowFactory::GetWindowKindName(vtkMRGIRenderWindowFactory::Headless),
      "osmesa") == 0);
}

// A sphere in the middle of a coloured background.
void AddSphere(vtkRenderer* renderer)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(16);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  renderer->SetBackground(0.2, 0.4, 0.6);
  renderer->ResetCamera();
}

// The window shows the background at a corner and the white sphere in the middle.
void CheckSphereImage(vtkRenderWindow* window, int width, int height)
{
  vtkSmartPointer<vtkImageData> image = mrgitest::GrabRGB(window);
  int dims[3];
  image->GetDimensions(dims);
  MRGI_TEST_CHECK(dims[0] == width && dims[1] == height);
  double corner[3], middle[3];
  mrgitest::MeanColor(image, 0, 0, 2, 2, corner);
  mrgitest::MeanColor(image, width / 2 - 1, height / 2 - 1, width / 2 + 1, height / 2 + 1, middle);
  MRGI_TEST_CHECK(std::fabs(corner[0] - 0.2 * 255) < 1.5);
  MRGI_TEST_CHECK(std::fabs(corner[1] - 0.4 * 255) < 1.5);
  MRGI_TEST_CHECK(std::fabs(corner[2] - 0.6 * 255) < 1.5);
  MRGI_TEST_CHECK(middle[0] > 150 && middle[1] > 150 && middle[2] > 150);
}

void TestOSMesaWindow()
{
  vtkNew<vtkMRGIOSMesaRenderWindow> window;
  if (!window->InitializeHeadlessContext())
  {
    MRGI_TEST_FAIL("no OSMesa context: %s", window->GetLastErrorMessage());
  }
  std::printf("OSMesa window: %s\n", window->GetPlatformDescription());
  MRGI_TEST_CHECK(window->GetContextVersion() >= 32);
  MRGI_TEST_CHECK(Contains(window->GetPlatformDescription(), "OSMesa, OpenGL"));
  MRGI_TEST_CHECK(window->GetOffScreenRendering() || window->GetUseOffScreenBuffers());
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  AddSphere(renderer);
  window->SetMultiSamples(0);

  window->SetSize(64, 48);
  window->Render();
  CheckSphereImage(window, 64, 48);
  window->SetSize(150, 40); // resizing: VTK's framebuffers follow
  window->Render();
  CheckSphereImage(window, 150, 40);
  window->ReleaseGraphicsResources(window); // then it renders again from scratch
  window->Render();
  CheckSphereImage(window, 150, 40);

  std::ostringstream print;
  window->Print(print);
  MRGI_TEST_CHECK(Contains(print.str(), "PlatformDescription: OSMesa"));
  MRGI_TEST_CHECK(Contains(print.str(), "ContextVersion: "));
  MRGI_TEST_CHECK(Contains(print.str(), "Library: libOSMesa"));
  MRGI_TEST_CHECK(vtkMRGIOSMesaRenderWindow::IsHeadlessRenderingAvailable());

  // A zero-sized window is an error, not a crash.
  vtkNew<mrgitest::ErrorCatcher> errors;
  window->AddObserver(vtkCommand::ErrorEvent, errors);
  window->SetSize(0, 10);
  window->Render();
  MRGI_TEST_CHECK(errors->Caught("at least 1"));
}

// A built-in scene through vtkMRGIPass in `window`.
struct SceneView
{
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderStepsPass> Steps;
  vtkNew<vtkMRGIPass> Pass;

  SceneView(vtkRenderWindow* window, const char* scene)
  {
    window->SetSize(128, 128);
    window->SetMultiSamples(0);
    window->AddRenderer(this->Renderer);
    vtkNew<vtkMRGISceneBuilder> builder;
    builder->SetScene(scene);
    MRGI_TEST_CHECK(builder->Build(this->Renderer));
    this->Pass->SetDelegatePass(this->Steps);
    this->Renderer->SetPass(this->Pass);
  }
};

struct Difference
{
  mrgi_metrics Metrics{};
};

Difference Compare(vtkImageData* a, vtkImageData* b)
{
  mrgi_image ia{}, ib{};
  std::string why;
  MRGI_TEST_CHECK(vtkMRGIImageIO::ToCoreImage(a, &ia, why));
  MRGI_TEST_CHECK(vtkMRGIImageIO::ToCoreImage(b, &ib, why));
  Difference d;
  mrgi_error err;
  const bool ok = mrgi_metrics_compare(&ia, &ib, nullptr, 1.0, &d.Metrics, &err) == MRGI_OK;
  mrgi_image_destroy(&ia);
  mrgi_image_destroy(&ib);
  MRGI_TEST_CHECK(ok);
  return d;
}

// Both windows in one process, rendering in turn: libglvnd must switch
// between EGL and the OSMesa dispatch each time, and both must agree.
void TestEGLAndOSMesaAlternate()
{
  Environment env;
  std::string why;
  vtkSmartPointer<vtkRenderWindow> egl = Make(vtkMRGIRenderWindowFactory::Headless, "egl", why);
  if (!egl)
  {
    MRGI_TEST_FAIL("no EGL window: %s", why.c_str());
  }
  vtkSmartPointer<vtkRenderWindow> osmesa =
    Make(vtkMRGIRenderWindowFactory::Headless, "osmesa", why);
  if (!osmesa)
  {
    MRGI_TEST_FAIL("no OSMesa window: %s", why.c_str());
  }
  SceneView eglView(egl, "cornell");
  SceneView osmesaView(osmesa, "cornell");
  egl->Render();
  vtkSmartPointer<vtkImageData> eglFirst = mrgitest::GrabRGB(egl);
  osmesa->Render();
  vtkSmartPointer<vtkImageData> osmesaFirst = mrgitest::GrabRGB(osmesa);
  egl->Render();
  vtkSmartPointer<vtkImageData> eglSecond = mrgitest::GrabRGB(egl);
  osmesa->Render();
  vtkSmartPointer<vtkImageData> osmesaSecond = mrgitest::GrabRGB(osmesa);

  // Each window repeats itself exactly after the other rendered in between.
  MRGI_TEST_CHECK(Compare(eglFirst, eglSecond).Metrics.max_abs_error == 0.0);
  MRGI_TEST_CHECK(Compare(osmesaFirst, osmesaSecond).Metrics.max_abs_error == 0.0);
  // The lit box, not a blank frame.
  double wall[3];
  mrgitest::MeanColor(osmesaFirst, 10, 50, 18, 80, wall);
  MRGI_TEST_CHECK(wall[0] > 2 * wall[1] && wall[0] > 40);

  const Difference d = Compare(osmesaFirst, eglFirst);
  std::printf("OSMesa vs EGL, Cornell box 128x128 through vtkMRGIPass: relative RMS %.5f, "
              "max %.4f (x255 = %.1f), PSNR %.2f dB\n",
    d.Metrics.relative_rms, d.Metrics.max_abs_error, 255.0 * d.Metrics.max_abs_error,
    d.Metrics.psnr_db);
  // The baselines' tolerance: both are Mesa's llvmpipe, so far closer in practice.
  MRGI_TEST_CHECK(d.Metrics.relative_rms <= 0.02);

  // vtkRenderer picks its near plane from the window's depth bits: both
  // windows report those of the framebuffer VTK renders into (at least 24,
  // a desktop window's; framebuffer 0 has none), hence the 24-bit tolerance,
  // or deep scenes lose the geometry near the camera (vtkMRGIHeadlessDepth.h).
  std::printf("depth bits: EGL %d, OSMesa %d; near plane tolerance %g\n",
    egl->GetDepthBufferSize(), osmesa->GetDepthBufferSize(),
    eglView.Renderer->GetNearClippingPlaneTolerance());
  MRGI_TEST_CHECK(egl->GetDepthBufferSize() == osmesa->GetDepthBufferSize());
  MRGI_TEST_CHECK(egl->GetDepthBufferSize() >= 24);
  MRGI_TEST_CHECK(eglView.Renderer->GetNearClippingPlaneTolerance() == 0.001);
  MRGI_TEST_CHECK(eglView.Renderer->GetNearClippingPlaneTolerance() ==
    osmesaView.Renderer->GetNearClippingPlaneTolerance());
  vtkSmartPointer<vtkRenderWindow> eglRoom = Make(vtkMRGIRenderWindowFactory::Headless, "egl", why);
  vtkSmartPointer<vtkRenderWindow> osmesaRoom =
    Make(vtkMRGIRenderWindowFactory::Headless, "osmesa", why);
  MRGI_TEST_CHECK(eglRoom && osmesaRoom);
  SceneView eglRoomView(eglRoom, "living-room");
  SceneView osmesaRoomView(osmesaRoom, "living-room");
  eglRoom->Render();
  osmesaRoom->Render();
  const Difference room = Compare(mrgitest::GrabRGB(osmesaRoom), mrgitest::GrabRGB(eglRoom));
  std::printf("OSMesa vs EGL, living room 128x128 (area light, voxel shadows): relative RMS %.5f, "
              "max %.4f\n",
    room.Metrics.relative_rms, room.Metrics.max_abs_error);
  MRGI_TEST_CHECK(room.Metrics.relative_rms <= 0.02);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestEGLDoesNotLoadOSMesa), MRGI_TEST_CASE(TestOSMesaLibraryMissing),
      MRGI_TEST_CASE(TestUnknownBackend), MRGI_TEST_CASE(TestXWithoutDisplay),
      MRGI_TEST_CASE(TestBackendChoice), MRGI_TEST_CASE(TestOSMesaWindow),
      MRGI_TEST_CASE(TestEGLAndOSMesaAlternate) });
}
