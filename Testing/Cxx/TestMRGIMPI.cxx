// The same VPLs on every MPI rank (run by ctest as
// `mpirun -np 2 TestMRGIMPI`, label mpi). The Cornell box is split across
// two ranks, as ParaView partitions data: rank r keeps the actors whose
// index % 2 == r (index % P == r under `mpirun -np P`; ctest runs 2), all
// keep the light and the camera (with the clipping
// range of the whole scene, as ParaView synchronises it). With a
// vtkMRGIControllerRSMCompositor over the MPI controller, vtkMRGIPass
// composites the reflective shadow maps across the ranks; each rank gathers
// on its own G-buffer. Checked, for the
// multiresolution and the full-resolution gather:
//  (a) the VPLs of all ranks are identical bit for bit, and equal to those
//      of a one-process render of the whole scene within VPL_TOLERANCE
//      (relative RMS over the VPL records);
//  (b) the ranks' images composited by depth (as IceT does; gathered to
//      rank 0 here) are within IMAGE_TOLERANCE relative RMS of the
//      one-process image;
//  (c) the composite is collective and cached: an unchanged frame sends
//      only the decision, a change on one rank re-composites on both, and
//      maps rendered without the compositor are not reused with it, and
//      ranks that disagree on the RSM resolution do not exchange maps.
// It prints the composite's bytes, the RSM texels that differ from the
// one-process maps and the image differences (Documentation/ParaView-MPI.md).
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMPIController.h"
#include "vtkMRGIControllerRSMCompositor.h"
#include "vtkMRGIImageIO.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkPointData.h"
#include "vtkPropCollection.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"

#include "mrgi_metrics.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace
{
constexpr int Size = 192;
constexpr double VPL_TOLERANCE = 1e-3;
constexpr double IMAGE_TOLERANCE = 0.01;
// Area lights: the voxels are OR-ed across ranks, but each rank's
// multiresolution buffer and visibility masks see only its own G-buffer
// (measured 0.023 on 2 ranks; 0.156 without the voxels' OR).
constexpr double AREA_LIGHT_TOLERANCE = 0.04;
constexpr int Tag = 4711;

int Failures = 0;

// No exceptions here: a rank that left early would leave the other waiting
// in a collective. Checks count failures; the ranks agree on the verdict.
#define MPI_CHECK(cond)                                                                            \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);                \
      ++Failures;                                                                                  \
    }                                                                                              \
  } while (0)

// What one render leaves: colour (RGB, bottom-up), depth, VPLs, RSM views.
struct Frame
{
  std::vector<float> RGB;
  std::vector<float> Depth;
  std::vector<float> VPLs;
  std::vector<float> RSM; // position, normal, flux of every view, RGBA float
  int Views = 0;
};

// A built-in scene into `renderer`; part -1 keeps every actor, else those
// with index % parts == part. The clipping range is the whole scene's on
// every rank. Returns the builder (its area lights).
vtkSmartPointer<vtkMRGISceneBuilder> BuildScene(
  vtkRenderer* renderer, int part, int parts, const char* scene = "cornell")
{
  auto builder = vtkSmartPointer<vtkMRGISceneBuilder>::New();
  builder->SetScene(scene);
  if (!builder->Build(renderer))
  {
    MRGI_TEST_FAIL("%s: %s", scene, builder->GetLastErrorMessage());
  }
  renderer->ResetCameraClippingRange();
  double range[2];
  renderer->GetActiveCamera()->GetClippingRange(range);
  std::vector<vtkProp*> props;
  vtkPropCollection* all = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  all->InitTraversal(it);
  while (vtkProp* p = all->GetNextProp(it))
  {
    props.push_back(p);
  }
  for (size_t i = 0; part >= 0 && i < props.size(); ++i)
  {
    if (static_cast<int>(i % static_cast<size_t>(parts)) != part)
    {
      renderer->RemoveViewProp(props[i]);
    }
  }
  renderer->GetActiveCamera()->SetClippingRange(range);
  std::printf("rank part %d: %d of %zu actors\n", part,
    renderer->GetViewProps()->GetNumberOfItems(), props.size());
  return builder;
}

Frame Grab(vtkRenderWindow* window, vtkMRGIPass* pass, bool vpls = true)
{
  Frame f;
  vtkSmartPointer<vtkImageData> rgb = mrgitest::GrabRGB(window);
  auto* chars = vtkUnsignedCharArray::SafeDownCast(rgb->GetPointData()->GetScalars());
  f.RGB.assign(chars->GetPointer(0), chars->GetPointer(0) + 3 * Size * Size);
  f.Depth.resize(Size * Size);
  window->GetZbufferData(0, 0, Size - 1, Size - 1, f.Depth.data());
  vtkNew<vtkFloatArray> records;
  if (vpls && pass->GetVPLs(window, records))
  {
    f.VPLs.assign(records->GetPointer(0), records->GetPointer(0) + records->GetNumberOfValues());
  }
  vtkMRGIReflectiveShadowMapPass* rsm = pass->GetReflectiveShadowMapPass();
  f.Views = rsm->GetNumberOfViews();
  for (int v = 0; v < f.Views; ++v)
  {
    vtkNew<vtkImageData> p, n, x;
    MPI_CHECK(rsm->ReadView(window, v, p, n, x));
    for (vtkImageData* im : { p.GetPointer(), n.GetPointer(), x.GetPointer() })
    {
      auto* a = vtkFloatArray::SafeDownCast(im->GetPointData()->GetScalars());
      f.RSM.insert(f.RSM.end(), a->GetPointer(0), a->GetPointer(0) + a->GetNumberOfValues());
    }
  }
  return f;
}

double RelativeRMS(const std::vector<float>& test, const std::vector<float>& ref)
{
  if (test.size() != ref.size() || ref.empty())
  {
    return HUGE_VAL;
  }
  double d = 0, r = 0;
  for (size_t i = 0; i < ref.size(); ++i)
  {
    d += (double(test[i]) - ref[i]) * (double(test[i]) - ref[i]);
    r += double(ref[i]) * ref[i];
  }
  return r > 0 ? std::sqrt(d / r) : (d > 0 ? HUGE_VAL : 0.0);
}

// mrgi_metrics_compare on two RGB images of Size x Size (0..255 values).
mrgi_metrics CompareImages(const std::vector<float>& test, const std::vector<float>& ref)
{
  mrgi_metrics m;
  std::memset(&m, 0, sizeof m);
  m.relative_rms = HUGE_VAL;
  mrgi_image a{ Size, Size, 3, const_cast<float*>(test.data()) };
  mrgi_image b{ Size, Size, 3, const_cast<float*>(ref.data()) };
  mrgi_error err;
  if (mrgi_metrics_compare(&a, &b, nullptr, 255.0, &m, &err) != MRGI_OK)
  {
    std::fprintf(stderr, "image comparison: %s\n", err.message);
    ++Failures;
  }
  return m;
}

void SendFrame(vtkMultiProcessController* c, const Frame& f, int to)
{
  const vtkIdType sizes[4] = { static_cast<vtkIdType>(f.RGB.size()),
    static_cast<vtkIdType>(f.Depth.size()), static_cast<vtkIdType>(f.VPLs.size()),
    static_cast<vtkIdType>(f.RSM.size()) };
  c->Send(sizes, 4, to, Tag);
  c->Send(f.RGB.data(), sizes[0], to, Tag);
  c->Send(f.Depth.data(), sizes[1], to, Tag);
  c->Send(f.VPLs.data(), sizes[2], to, Tag);
  c->Send(f.RSM.data(), sizes[3], to, Tag);
}

Frame ReceiveFrame(vtkMultiProcessController* c, int from)
{
  vtkIdType sizes[4];
  c->Receive(sizes, 4, from, Tag);
  Frame f;
  f.RGB.resize(sizes[0]);
  f.Depth.resize(sizes[1]);
  f.VPLs.resize(sizes[2]);
  f.RSM.resize(sizes[3]);
  c->Receive(f.RGB.data(), sizes[0], from, Tag);
  c->Receive(f.Depth.data(), sizes[1], from, Tag);
  c->Receive(f.VPLs.data(), sizes[2], from, Tag);
  c->Receive(f.RSM.data(), sizes[3], from, Tag);
  return f;
}

// Depth composite of rank 0's frame with the others' (others[r - 1] is rank
// r's), nearest wins as in IceT; owner[p] is the rank whose pixel won.
void DepthComposite(const Frame& mine, const std::vector<Frame>& others,
  std::vector<float>& composite, std::vector<int>& owner)
{
  composite.assign(3 * Size * Size, 0.0f);
  owner.assign(Size * Size, 0);
  const int size = static_cast<int>(others.size()) + 1;
  for (int p = 0; p < Size * Size; ++p)
  {
    const Frame* best = &mine;
    owner[p] = 0;
    for (int r = 1; r < size; ++r)
    {
      if (others[r - 1].Depth[p] < best->Depth[p])
      {
        best = &others[r - 1];
        owner[p] = r;
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      composite[3 * p + k] = best->RGB[3 * p + k];
    }
  }
}

void WritePNG(const std::vector<float>& rgb, const std::string& name)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(Size, Size, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* p = static_cast<unsigned char*>(image->GetScalarPointer());
  for (size_t i = 0; i < rgb.size(); ++i)
  {
    p[i] = static_cast<unsigned char>(std::lround(std::min(255.0f, std::max(0.0f, rgb[i]))));
  }
  vtkNew<vtkMRGIImageIO> io;
  io->Write(image, mrgitest::TempPath(name).c_str());
}

// The one-process image, the composite and their difference x4, as PNGs.
void WriteComparison(
  const std::vector<float>& reference, const std::vector<float>& composite, const std::string& tag)
{
  WritePNG(reference, tag + "-1rank.png");
  WritePNG(composite, tag + "-2rank.png");
  std::vector<float> diff(composite.size());
  for (size_t i = 0; i < diff.size(); ++i)
  {
    diff[i] = 4.0f * std::fabs(composite[i] - reference[i]);
  }
  WritePNG(diff, tag + "-diff4.png");
}

// Where the differences are: pixels off by more than 2/255 in a channel,
// by their distance (Chebyshev, pixels) to the nearest partition border
// (a pixel whose neighbour was won by another rank).
void BorderStatistics(const std::vector<float>& composite, const std::vector<float>& reference,
  const std::vector<int>& owner, const char* name)
{
  const int radii[3] = { 4, 16, 64 };
  int differ = 0, within[3] = { 0, 0, 0 };
  for (int y = 0; y < Size; ++y)
  {
    for (int x = 0; x < Size; ++x)
    {
      const int p = y * Size + x;
      bool off = false;
      for (int k = 0; k < 3; ++k)
      {
        off = off || std::fabs(composite[3 * p + k] - reference[3 * p + k]) > 2.0f;
      }
      if (!off)
      {
        continue;
      }
      ++differ;
      int distance = Size;
      for (int yy = 0; yy < Size; ++yy)
      {
        for (int xx = 0; xx < Size; ++xx)
        {
          if (owner[yy * Size + xx] != owner[p])
          {
            distance = std::min(distance, std::max(std::abs(xx - x), std::abs(yy - y)));
          }
        }
      }
      for (int i = 0; i < 3; ++i)
      {
        within[i] += distance <= radii[i] ? 1 : 0;
      }
    }
  }
  std::printf("%s: %d pixels differ by more than 2/255; within 4, 16, 64 pixels of a partition "
              "border: %d, %d, %d\n",
    name, differ, within[0], within[1], within[2]);
}

void RunMode(vtkMultiProcessController* c, int mode, const char* name)
{
  const int rank = c->GetLocalProcessId();
  const int size = c->GetNumberOfProcesses();
  auto configure = [&](vtkMRGIPass* pass, vtkRenderStepsPass* steps) {
    pass->SetDelegatePass(steps);
    pass->SetIndirectMode(mode);
  };

  // The one-process render of the whole scene (rank 0 only; no controller).
  Frame reference;
  double referenceMs = 0;
  if (rank == 0)
  {
    vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(Size, Size);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    BuildScene(renderer, -1, 1);
    vtkNew<vtkRenderStepsPass> steps;
    vtkNew<vtkMRGIPass> pass;
    configure(pass, steps);
    renderer->SetPass(pass);
    const auto t0 = std::chrono::steady_clock::now();
    window->Render();
    referenceMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    MPI_CHECK(pass->GetIndirectComputed());
    MPI_CHECK(pass->GetRSMCompositeBytes() == 0);
    reference = Grab(window, pass);
  }

  // The distributed render: this rank's half, the controller set.
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(Size, Size);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  BuildScene(renderer, rank, size);
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> pass;
  configure(pass, steps);
  vtkNew<vtkMRGIControllerRSMCompositor> compositor;
  compositor->SetController(c);
  pass->SetRSMCompositor(compositor);
  renderer->SetPass(pass);
  vtkMRGIReflectiveShadowMapPass* rsm = pass->GetReflectiveShadowMapPass();
  c->Barrier();
  const auto t0 = std::chrono::steady_clock::now();
  window->Render();
  const double distributedMs =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  MPI_CHECK(pass->GetIndirectComputed());
  MPI_CHECK(rsm->GetNumberOfComposites() == 1);
  const vtkTypeInt64 bytes = pass->GetRSMCompositeBytes();
  Frame mine = Grab(window, pass);
  const vtkTypeInt64 mapBytes =
    static_cast<vtkTypeInt64>(mine.Views) * rsm->GetResolution() * rsm->GetResolution() * 48;
  std::printf("%s rank %d: %d views, composite sent %lld bytes (maps %lld), frame %.0f ms "
              "(one process: %.0f ms)\n",
    name, rank, mine.Views, static_cast<long long>(bytes), static_cast<long long>(mapBytes),
    distributedMs, referenceMs);
  // Two ranks: rank 1 sends the maps up once, rank 0 sends them down once.
  // More: at most once up and once per child of the binomial tree down.
  int children = 0;
  for (int m = 1; m < size && !(rank & m); m <<= 1)
  {
    children += rank + m < size ? 1 : 0;
  }
  const vtkTypeInt64 messages = (rank != 0 ? 1 : 0) + children;
  MPI_CHECK(bytes > messages * mapBytes && bytes < messages * mapBytes + 1024);

  // (c) An unchanged frame: the decision only, no composite.
  auto t1 = std::chrono::steady_clock::now();
  window->Render();
  const double unchangedMs =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
  MPI_CHECK(rsm->GetNumberOfComposites() == 1);
  MPI_CHECK(pass->GetRSMCompositeBytes() > 0 && pass->GetRSMCompositeBytes() < 1024);
  // A change on rank 1 only re-renders and composites on both ranks.
  if (rank == size - 1)
  {
    vtkActor::SafeDownCast(renderer->GetViewProps()->GetItemAsObject(0))->Modified();
  }
  c->Barrier();
  t1 = std::chrono::steady_clock::now();
  window->Render();
  const double recompositeMs =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
  std::printf("%s rank %d: unchanged frame %.0f ms, frame with RSM re-render + composite %.0f ms\n",
    name, rank, unchangedMs, recompositeMs);
  MPI_CHECK(rsm->GetNumberOfComposites() == 2);
  Frame again = Grab(window, pass);
  MPI_CHECK(again.VPLs == mine.VPLs);
  // Rendering alone for a frame (as ParaView does when it renders on one
  // process) and back: the cached maps are not reused across the switch.
  pass->SetRSMCompositor(nullptr);
  window->Render();
  MPI_CHECK(rsm->GetNumberOfComposites() == 2);
  MPI_CHECK(pass->GetRSMCompositeBytes() == 0);
  MPI_CHECK(Grab(window, pass).VPLs != mine.VPLs); // this rank's half only
  pass->SetRSMCompositor(compositor);
  window->Render();
  MPI_CHECK(rsm->GetNumberOfComposites() == 3);
  MPI_CHECK(Grab(window, pass).VPLs == mine.VPLs);
  // Ranks that disagree (here on the RSM resolution) render their own maps
  // uncomposited, with an error, instead of exchanging maps of different
  // sizes; once they agree again they composite again.
  const int resolution = rsm->GetResolution();
  if (rank == size - 1)
  {
    pass->SetRSMResolution(resolution / 2);
  }
  vtkObject::GlobalWarningDisplayOff(); // the expected error
  window->Render();
  vtkObject::GlobalWarningDisplayOn();
  MPI_CHECK(rsm->GetNumberOfComposites() == 3);
  pass->SetRSMResolution(resolution);
  window->Render();
  MPI_CHECK(rsm->GetNumberOfComposites() == 4);
  MPI_CHECK(Grab(window, pass).VPLs == mine.VPLs);

  if (rank != 0)
  {
    SendFrame(c, mine, 0);
    return;
  }
  std::vector<Frame> others;
  for (int r = 1; r < size; ++r)
  {
    others.push_back(ReceiveFrame(c, r));
  }

  // (a) The same VPLs on both ranks, bit for bit, and the same maps.
  MPI_CHECK(!mine.VPLs.empty());
  for (const Frame& other : others)
  {
    MPI_CHECK(mine.VPLs == other.VPLs);
    MPI_CHECK(mine.RSM == other.RSM);
  }
  // ... and those of one process within the tolerance.
  MPI_CHECK(mine.Views == reference.Views);
  size_t differing = 0, texels = 0;
  if (mine.RSM.size() == reference.RSM.size())
  {
    const size_t plane = static_cast<size_t>(rsm->GetResolution()) * rsm->GetResolution() * 4;
    for (size_t base = 0; base < mine.RSM.size(); base += 3 * plane)
    {
      for (size_t t = 0; t < plane; t += 4)
      {
        ++texels;
        bool same = true;
        for (size_t k = 0; k < 3; ++k)
        {
          same = same &&
            std::memcmp(&mine.RSM[base + k * plane + t], &reference.RSM[base + k * plane + t],
              4 * sizeof(float)) == 0;
        }
        differing += same ? 0 : 1;
      }
    }
  }
  const double vplError = RelativeRMS(mine.VPLs, reference.VPLs);
  std::printf("%s: RSM texels differing from one process: %zu of %zu; VPL relative RMS %.3g\n",
    name, differing, texels, vplError);
  MPI_CHECK(mine.RSM.size() == reference.RSM.size());
  MPI_CHECK(vplError <= VPL_TOLERANCE);

  // (b) Depth composite of the ranks' images, nearest wins (IceT's rule).
  std::vector<float> composite;
  std::vector<int> owner; // the rank whose pixel won
  DepthComposite(mine, others, composite, owner);
  BorderStatistics(composite, reference.RGB, owner, name);
  const mrgi_metrics m = CompareImages(composite, reference.RGB);
  std::printf("%s: %d-rank depth composite vs one process: relative RMS %.4f, max %.0f/255, "
              "PSNR %.1f dB\n",
    name, size, m.relative_rms, m.max_abs_error, m.psnr_db);
  MPI_CHECK(m.relative_rms <= IMAGE_TOLERANCE);
  const std::string tag =
    std::string("TestMRGIMPI-") + name + (size == 2 ? "" : "-np" + std::to_string(size));
  WriteComparison(reference.RGB, composite, tag);
}
}

// `TestMRGIMPI --area-lights` (ctest: mpi.TestMRGIMPIAreaLights): the
// area-light scene split the same way; with the compositor the ranks OR
// their voxelizations, so every rank's geometry shadows the area light on
// every rank. The depth composite must be within AREA_LIGHT_TOLERANCE of
// one process.
void MeasureAreaLights(vtkMultiProcessController* c)
{
  const int rank = c->GetLocalProcessId();
  const int size = c->GetNumberOfProcesses();
  auto render = [&](int part, int parts, bool distributed, Frame& out) {
    vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(Size, Size);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    vtkSmartPointer<vtkMRGISceneBuilder> builder =
      BuildScene(renderer, part, parts, "cornell-area");
    vtkNew<vtkRenderStepsPass> steps;
    vtkNew<vtkMRGIPass> pass;
    pass->SetDelegatePass(steps);
    for (int i = 0; i < builder->GetNumberOfAreaLights(); ++i)
    {
      pass->AddAreaLight(builder->GetAreaLight(i));
    }
    vtkNew<vtkMRGIControllerRSMCompositor> compositor;
    compositor->SetController(c);
    if (distributed)
    {
      pass->SetRSMCompositor(compositor);
    }
    renderer->SetPass(pass);
    window->Render();
    out = Grab(window, pass, false); // lit by the area light only: no VPLs
  };
  Frame reference, mine;
  if (rank == 0)
  {
    render(-1, 1, false, reference);
  }
  render(rank, size, true, mine);
  if (rank != 0)
  {
    SendFrame(c, mine, 0);
    return;
  }
  std::vector<float> composite;
  std::vector<Frame> others;
  for (int r = 1; r < size; ++r)
  {
    others.push_back(ReceiveFrame(c, r));
  }
  std::vector<int> owner;
  DepthComposite(mine, others, composite, owner);
  BorderStatistics(composite, reference.RGB, owner, "area lights");
  const mrgi_metrics m = CompareImages(composite, reference.RGB);
  std::printf("area lights: %d-rank depth composite vs one process: relative RMS %.4f, max "
              "%.0f/255, PSNR %.1f dB\n",
    size, m.relative_rms, m.max_abs_error, m.psnr_db);
  MPI_CHECK(m.relative_rms <= AREA_LIGHT_TOLERANCE);
  const std::string tag = "TestMRGIMPI-area" + (size == 2 ? "" : "-np" + std::to_string(size));
  WriteComparison(reference.RGB, composite, tag);
}

int main(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  vtkMultiProcessController::SetGlobalController(controller);
  const int rank = controller->GetLocalProcessId();
  if (controller->GetNumberOfProcesses() < 2)
  {
    std::fprintf(stderr, "TestMRGIMPI: run it with mpirun -np 2 or more (got %d process)\n",
      controller->GetNumberOfProcesses());
    controller->Finalize();
    return 1;
  }
  if (argc > 1 && std::string(argv[1]) == "--area-lights")
  {
    MeasureAreaLights(controller);
    int local = Failures, total = 0;
    controller->AllReduce(&local, &total, 1, vtkCommunicator::SUM_OP);
    controller->Finalize();
    return total == 0 ? 0 : 1;
  }
  RunMode(controller, vtkMRGIPass::IndirectMultires, "multires");
  RunMode(controller, vtkMRGIPass::IndirectFull, "full");
  int local = Failures, total = 0;
  controller->AllReduce(&local, &total, 1, vtkCommunicator::SUM_OP);
  if (rank == 0)
  {
    std::printf("TestMRGIMPI: %s\n", total == 0 ? "passed" : "FAILED");
  }
  controller->Finalize();
  return total == 0 ? 0 : 1;
}
