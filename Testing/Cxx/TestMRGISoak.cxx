// Soak and lifecycle: vtkMRGIPass over many frames, as an interactive
// application drives it (issue 18, part 9).
//
// One window shows the Cornell box lit by a moving spot light and by its own
// emitter as an area light; each frame moves the camera and the light, and on
// fixed periods the schedule below
//   - cycles the indirect mode (multiresolution, full, off),
//   - cycles the multiresolution preset (fast, balanced, accurate),
//   - removes and re-adds the area light,
//   - resizes the window through 256x256, 1x1, 257x129, 3x5, 200x300, 640x64,
//   - releases the pass's graphics resources, or the whole window's, and
//     renders again,
//   - renders a second window that shares the first window's actors (each
//     window with its own vtkMRGIPass).
// Every 10th frame reads the HDR colour buffer back and requires every value
// to be finite. At 10 checkpoints it records the process's resident set size
// (and GPU memory where the driver reports it through GL_NVX_gpu_memory_info).
//
// The assertion: after the warm-up (the first 40% of the frames, at least
// one whole cycle of the schedule), the C heap in use (malloc's arenas and
// mmap'd blocks; llvmpipe keeps textures and buffers there) grows by at most
// 8 MiB, and the resident set (after malloc_trim) by at most
// max(64 MiB, 25%). The heap is exact where the resident set moves with page
// reuse; a per-frame leak of one 256x256 RGBA16F texture (512 KiB) exceeds
// the heap bound within 20 frames.
//
// Usage: TestMRGISoak [--frames N] [--csv FILE]   (default 500 frames, at
// least 2 x 120 so that two checkpoints compare)
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <malloc.h>
#include <unistd.h>
#include <vector>

namespace
{
// The schedule's periods, in frames. Indirect mode (3 x 10) and area light
// (2 x 20) meet in every combination within the size cycle (6 x 20 = 120
// frames), and at every multiple of 120 frames all of them are back in the
// same state.
constexpr int ModePeriod = 10;
constexpr int PresetPeriod = 30;
constexpr int AreaLightPeriod = 20;
constexpr int SizePeriod = 20;
constexpr int ReleasePeriod = 100;
constexpr int SecondWindowPeriod = 7;
constexpr int NaNCheckPeriod = 10;
constexpr int Sizes[][2] = { { 256, 256 }, { 1, 1 }, { 257, 129 }, { 3, 5 }, { 200, 300 }, { 640, 64 } };
constexpr int CycleFrames = SizePeriod * static_cast<int>(sizeof(Sizes) / sizeof(Sizes[0]));
// Light samples per area light: the soak exercises the area lights'
// lifecycle, not their noise, and 16 samples cost a tenth of the default.
constexpr int AreaLightSamples = 16;
constexpr double HeapGrowthAllowedMiB = 8.0;

double ResidentMiB()
{
  malloc_trim(0); // hand freed pages back first: what stays is in use
  long pages = 0, resident = 0;
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f)
  {
    return -1.0;
  }
  const int read = std::fscanf(f, "%ld %ld", &pages, &resident);
  std::fclose(f);
  return read == 2 ? static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1048576.0
                   : -1.0;
}

// Bytes the C heap has handed out (malloc arenas and mmap'd blocks), in MiB:
// unlike the resident set, it does not move with page reuse.
double HeapMiB()
{
  const struct mallinfo2 info = mallinfo2();
  return static_cast<double>(info.uordblks + info.hblkhd) / 1048576.0;
}

// GPU memory in use (MiB) where the driver reports it, else -1.
double GPUUsedMiB(vtkRenderWindow* window)
{
#ifndef GL_GPU_MEMORY_INFO_TOTAL_AVAILABLE_MEMORY_NVX
#define GL_GPU_MEMORY_INFO_TOTAL_AVAILABLE_MEMORY_NVX 0x9048
#define GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX 0x9049
#endif
  window->MakeCurrent();
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  bool nvx = false;
  for (GLint i = 0; i < count && !nvx; ++i)
  {
    const char* name = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
    nvx = name && std::strcmp(name, "GL_NVX_gpu_memory_info") == 0;
  }
  if (!nvx)
  {
    return -1.0;
  }
  GLint total = 0, available = 0;
  glGetIntegerv(GL_GPU_MEMORY_INFO_TOTAL_AVAILABLE_MEMORY_NVX, &total);
  glGetIntegerv(GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, &available);
  return (total - available) / 1024.0;
}

// Number of non-finite values in the pass's last HDR colour buffer; -1 when
// the pass made none (e.g. a 1x1 window still makes one; indirect off too).
long NonFiniteColors(vtkMRGIPass* pass, vtkRenderWindow* window)
{
  vtkNew<vtkImageData> image;
  if (!pass->GetColorBuffer(window, image))
  {
    return -1;
  }
  vtkDataArray* values = image->GetPointData()->GetScalars();
  long bad = 0;
  const vtkIdType n = values ? values->GetNumberOfValues() : 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (!std::isfinite(values->GetVariantValue(i).ToDouble()))
    {
      ++bad;
    }
  }
  return bad;
}

vtkSmartPointer<vtkMRGIPass> Install(vtkRenderer* renderer)
{
  vtkNew<vtkRenderStepsPass> steps;
  auto pass = vtkSmartPointer<vtkMRGIPass>::New();
  pass->SetDelegatePass(steps);
  renderer->SetPass(pass);
  return pass;
}

struct Checkpoint
{
  int Frame;
  double ResidentMiB;
  double HeapMiB;
  double GPUMiB;
};

int Soak(int frames, const std::string& csvPath)
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(256, 256);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene("cornell-area");
  MRGI_TEST_CHECK(builder->Build(renderer));
  MRGI_TEST_CHECK(builder->GetNumberOfAreaLights() == 1);
  vtkSmartPointer<vtkMRGIAreaLight> areaLight = builder->GetAreaLight(0);
  areaLight->SetNumberOfSamples(AreaLightSamples);

  // A spot light under the ceiling gives the RSM its VPLs.
  double bounds[6];
  renderer->ComputeVisiblePropBounds(bounds);
  const double centre[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };
  const double extent = std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
  vtkNew<vtkLight> spot;
  spot->SetLightTypeToSceneLight();
  spot->SetPositional(true);
  spot->SetConeAngle(60);
  spot->SetFocalPoint(centre[0], bounds[2], centre[2]);
  renderer->AddLight(spot);

  vtkSmartPointer<vtkMRGIPass> pass = Install(renderer);
  pass->AddAreaLight(areaLight);
  bool areaLightOn = true;

  // The second window shows the same actors, with its own pass.
  vtkSmartPointer<vtkRenderWindow> window2 = mrgitest::HeadlessWindow(128, 96);
  vtkNew<vtkRenderer> renderer2;
  window2->AddRenderer(renderer2);
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor())
  {
    renderer2->AddActor(actor);
  }
  renderer2->AddLight(spot);
  renderer2->SetActiveCamera(renderer->GetActiveCamera());
  vtkSmartPointer<vtkMRGIPass> pass2 = std::getenv("MRGI_SOAK_NOPASS2") ? vtkSmartPointer<vtkMRGIPass>::New() : Install(renderer2);

  const int modes[3] = { vtkMRGIPass::IndirectMultires, vtkMRGIPass::IndirectFull, vtkMRGIPass::IndirectOff };
  const int presets[3] = { vtkMRGIMultiresolution::PresetFast, vtkMRGIMultiresolution::PresetBalanced,
    vtkMRGIMultiresolution::PresetAccurate };
  const int sizeCount = static_cast<int>(sizeof(Sizes) / sizeof(Sizes[0]));
  // Checkpoints fall on multiples of the 120-frame size cycle, where every
  // schedule is in the same state (256x256, multiresolution, area light on),
  // so that they compare like with like: about 10 per run.
  const int checkpointEvery = CycleFrames * std::max(1, (frames / 10 + CycleFrames / 2) / CycleFrames);
  std::vector<Checkpoint> checkpoints;
  long nanChecks = 0, releases = 0, resizes = 0, secondFrames = 0;
  vtkCamera* camera = renderer->GetActiveCamera();
  const bool verbose = std::getenv("MRGI_SOAK_VERBOSE") != nullptr;
  // Time per (indirect mode, area light) state, to say where a soak's time goes.
  double stateMilliseconds[6] = { 0, 0, 0, 0, 0, 0 };
  long stateFrames[6] = { 0, 0, 0, 0, 0, 0 };

  for (int frame = 1; frame <= frames; ++frame)
  {
    camera->Azimuth(0.7);
    camera->Elevation(0.3 * std::sin(0.05 * frame));
    camera->OrthogonalizeViewUp();
    renderer->ResetCameraClippingRange();
    const double angle = 0.031 * frame;
    spot->SetPosition(centre[0] + 0.3 * extent * std::cos(angle), bounds[3] - 0.05 * extent,
      centre[2] + 0.3 * extent * std::sin(angle));

    if (frame % ModePeriod == 0)
    {
      pass->SetIndirectMode(modes[(frame / ModePeriod) % 3]);
    }
    if (frame % PresetPeriod == 0)
    {
      MRGI_TEST_CHECK(pass->GetMultiresolution()->SetPreset(presets[(frame / PresetPeriod) % 3]));
    }
    if (frame % AreaLightPeriod == 0)
    {
      if (areaLightOn)
      {
        pass->RemoveAreaLight(areaLight);
      }
      else
      {
        pass->AddAreaLight(areaLight);
      }
      areaLightOn = !areaLightOn;
    }
    if (frame % SizePeriod == 0)
    {
      const int* size = Sizes[(frame / SizePeriod) % sizeCount];
      window->SetSize(size[0], size[1]);
      ++resizes;
    }
    if (frame % ReleasePeriod == 0)
    {
      // Alternate: the pass alone, then the whole window (as a window that is
      // closed and reopened).
      if ((frame / ReleasePeriod) % 2)
      {
        pass->ReleaseGraphicsResources(window);
      }
      else
      {
        window->ReleaseGraphicsResources(window);
      }
      ++releases;
    }

    if (verbose)
    {
      std::printf("frame %d: mode %d, area light %d, size %dx%d\n", frame, pass->GetIndirectMode(),
        areaLightOn ? 1 : 0, window->GetSize()[0], window->GetSize()[1]);
      std::fflush(stdout);
    }
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const int state = (pass->GetIndirectMode() * 2 + (areaLightOn ? 1 : 0));
    stateMilliseconds[state] += ms;
    stateFrames[state] += 1;
    if (frame % SecondWindowPeriod == 0)
    {
      if (verbose)
      {
        std::printf("frame %d: second window\n", frame);
        std::fflush(stdout);
      }
      window2->Render();
      ++secondFrames;
    }
    if (frame % NaNCheckPeriod == 0)
    {
      const long bad = NonFiniteColors(pass, window);
      if (bad > 0)
      {
        MRGI_TEST_FAIL("frame %d: %ld non-finite values in the HDR colour buffer", frame, bad);
      }
      nanChecks += bad == 0 ? 1 : 0;
    }
    if (frame % checkpointEvery == 0)
    {
      checkpoints.push_back({ frame, ResidentMiB(), HeapMiB(), GPUUsedMiB(window) });
      std::printf("TestMRGISoak: frame %6d  RSS %8.1f MiB  heap %8.1f MiB  GPU %s\n", frame,
        checkpoints.back().ResidentMiB, checkpoints.back().HeapMiB,
        checkpoints.back().GPUMiB < 0 ? "not reported" : std::to_string(checkpoints.back().GPUMiB).c_str());
      std::fflush(stdout);
    }
  }

  std::printf("TestMRGISoak: %d frames, %ld resizes, %ld releases, %ld second-window frames, "
              "%ld NaN-free read-backs\n",
    frames, resizes, releases, secondFrames, nanChecks);
  MRGI_TEST_CHECK(nanChecks > 0);
  const char* modeNames[3] = { "off", "full", "multires" };
  for (int state = 0; state < 6; ++state)
  {
    if (stateFrames[state] > 0)
    {
      std::printf("TestMRGISoak: indirect %-8s area light %-3s %5ld frames, mean %.1f ms\n", modeNames[state / 2],
        state % 2 ? "on" : "off", stateFrames[state], stateMilliseconds[state] / stateFrames[state]);
    }
  }

  if (!csvPath.empty())
  {
    FILE* csv = std::fopen(csvPath.c_str(), "w");
    MRGI_TEST_CHECK(csv != nullptr);
    std::fprintf(csv, "frame,rss_mib,heap_mib,gpu_mib\n");
    for (const Checkpoint& c : checkpoints)
    {
      std::fprintf(csv, "%d,%.2f,%.2f,%.2f\n", c.Frame, c.ResidentMiB, c.HeapMiB, c.GPUMiB);
    }
    std::fclose(csv);
  }

  // Growth after the warm-up.
  const int warmFrame = static_cast<int>(0.4 * frames);
  const Checkpoint* warm = nullptr;
  for (const Checkpoint& c : checkpoints)
  {
    if (c.Frame >= warmFrame)
    {
      warm = &c;
      break;
    }
  }
  MRGI_TEST_CHECK(warm != nullptr && warm->ResidentMiB > 0);
  const Checkpoint& last = checkpoints.back();
  const double heapGrowth = last.HeapMiB - warm->HeapMiB;
  const double residentGrowth = last.ResidentMiB - warm->ResidentMiB;
  const double residentAllowed = std::max(64.0, 0.25 * warm->ResidentMiB);
  std::printf("TestMRGISoak: frames %d -> %d: heap %.1f -> %.1f MiB (growth %.1f, allowed %.1f), "
              "RSS %.1f -> %.1f MiB (growth %.1f, allowed %.1f)\n",
    warm->Frame, last.Frame, warm->HeapMiB, last.HeapMiB, heapGrowth, HeapGrowthAllowedMiB, warm->ResidentMiB,
    last.ResidentMiB, residentGrowth, residentAllowed);
  if (heapGrowth > HeapGrowthAllowedMiB)
  {
    MRGI_TEST_FAIL("the heap grew by %.1f MiB after the warm-up (allowed %.1f)", heapGrowth, HeapGrowthAllowedMiB);
  }
  if (residentGrowth > residentAllowed)
  {
    MRGI_TEST_FAIL("resident memory grew by %.1f MiB after the warm-up (allowed %.1f)", residentGrowth,
      residentAllowed);
  }
  pass->ReleaseGraphicsResources(window);
  pass2->ReleaseGraphicsResources(window2);
  return 0;
}
} // namespace

int TestMRGISoak(int argc, char* argv[])
{
  int frames = 500;
  std::string csv;
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--frames") == 0 && i + 1 < argc)
    {
      frames = std::atoi(argv[++i]);
    }
    else if (std::strcmp(argv[i], "--csv") == 0 && i + 1 < argc)
    {
      csv = argv[++i];
    }
    else
    {
      std::fprintf(stderr, "usage: TestMRGISoak [--frames N (>= 240)] [--csv FILE]\n");
      return 2;
    }
  }
  if (frames < 2 * CycleFrames)
  {
    std::fprintf(stderr, "TestMRGISoak: --frames must be at least %d\n", 2 * CycleFrames);
    return 2;
  }
  return Soak(frames, csv);
}

int main(int argc, char* argv[])
{
  return TestMRGISoak(argc, argv);
}
