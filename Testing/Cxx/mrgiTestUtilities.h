/**
 * @file mrgiTestUtilities.h
 * @brief Shared helpers of MRGI's C++ tests: checks, named cases, headless
 *        windows, pixel reads and VTK-style image regression against baselines.
 *
 * Checks and cases: MRGI_TEST_CHECK(cond) fails a test. A program that hands
 * its cases to mrgitest::RunCases() runs every case (a failed check ends its
 * case only), names the failed ones and exits non-zero if there was one;
 * `TestX --list` lists the cases, `TestX --case NAME` runs one. Without
 * RunCases() a failed check exits with status 1 at once. Testing/Core/mrgi_test.h is
 * the C core tests' twin (same options and output).
 *
 * Regression: a test renders, then compares its image with
 * Testing/Data/Baseline/<name>.png. It passes when the relative RMS error is
 * within the stated tolerance. On failure the test image and a difference
 * image (|test - baseline| x 4) are kept in the test's temporary directory.
 * Set MRGI_REGENERATE_BASELINES=1 to (re)write the baseline instead of
 * comparing; see Testing/README.md.
 */
#ifndef mrgiTestUtilities_h
#define mrgiTestUtilities_h

#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkMRGIImageIO.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIRenderWindowFactory.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include "mrgi_image.h"
#include "mrgi_metrics.h"
#include "mrgi_vpl.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <functional>
#include <string>
#include <vector>

namespace mrgitest
{
/**
 * Thrown by a failed check inside a case that RunCases() runs: it ends that
 * case only. Not a std::exception, so that a test's own handlers of those
 * do not swallow it.
 */
struct CheckFailed
{
};

/** Whether RunCases() is running a case (then a failed check throws). */
inline bool InCase = false;

/** A failed check: end the running case, or the program outside a case. */
[[noreturn]] inline void Fail()
{
  std::fflush(stdout);
  if (InCase)
  {
    throw CheckFailed{};
  }
  std::exit(1);
}
}

/** Check `cond`; when false, print file, line and expression and fail (mrgitest::Fail()). */
#define MRGI_TEST_CHECK(cond)                                                                      \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);                \
      mrgitest::Fail();                                                                            \
    }                                                                                              \
  } while (0)

/** Fail unconditionally with a printf-style message. */
#define MRGI_TEST_FAIL(...)                                                                        \
  do                                                                                               \
  {                                                                                                \
    std::fprintf(stderr, "%s:%d: failed: ", __FILE__, __LINE__);                                   \
    std::fprintf(stderr, __VA_ARGS__);                                                             \
    std::fputc('\n', stderr);                                                                      \
    mrgitest::Fail();                                                                              \
  } while (0)

/** A case named after its function: MRGI_TEST_CASE(TestBadInput). */
// clang-format off
#define MRGI_TEST_CASE(function) mrgitest::Case{ #function, function }
// clang-format on

namespace mrgitest
{
/** One named case of a test program. */
struct Case
{
  std::string Name;
  std::function<void()> Run;
};

/**
 * Runs the cases the command line asks for, in the listed order: all by
 * default, only those named by `--case NAME` (repeatable); `--list` prints
 * the names. A failed check ends its case, the others still run; a case
 * that throws anything else fails too. At the end the failed cases are
 * named. Returns main's exit code: 0 when every case run passed, 1 when one
 * failed, 2 for a bad command line.
 *
 *     int main(int argc, char* argv[])
 *     {
 *       return mrgitest::RunCases(argc, argv,
 *         { MRGI_TEST_CASE(TestBadInput), { "CornellParallel", [] { Cornell(true); } } });
 *     }
 */
inline int RunCases(int argc, char* argv[], const std::vector<Case>& cases)
{
  std::string program = argc > 0 && argv[0] ? argv[0] : "test";
  program = program.substr(program.find_last_of('/') + 1);
  std::vector<bool> selected(cases.size(), false);
  bool anySelected = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--list")
    {
      for (const Case& c : cases)
      {
        std::printf("%s\n", c.Name.c_str());
      }
      return 0;
    }
    if (arg == "--case" && i + 1 < argc)
    {
      const std::string name = argv[++i];
      size_t c = 0;
      while (c < cases.size() && cases[c].Name != name)
      {
        ++c;
      }
      if (c == cases.size())
      {
        std::fprintf(
          stderr, "%s: no case '%s' (--list lists them)\n", program.c_str(), name.c_str());
        return 2;
      }
      selected[c] = true;
      anySelected = true;
      continue;
    }
    std::fprintf(stderr, "usage: %s [--list] [--case NAME]...\n", program.c_str());
    return 2;
  }
  std::vector<std::string> failed;
  size_t ran = 0;
  for (size_t c = 0; c < cases.size(); ++c)
  {
    if (anySelected && !selected[c])
    {
      continue;
    }
    const std::string& name = cases[c].Name;
    std::printf("[ RUN    ] %s\n", name.c_str());
    std::fflush(stdout);
    ++ran;
    bool ok = false;
    InCase = true;
    try
    {
      cases[c].Run();
      ok = true;
    }
    catch (const CheckFailed&)
    {
    }
    catch (const std::exception& e)
    {
      std::fprintf(stderr, "%s: exception: %s\n", name.c_str(), e.what());
    }
    catch (...)
    {
      std::fprintf(stderr, "%s: unknown exception\n", name.c_str());
    }
    InCase = false;
    std::printf("%s %s\n", ok ? "[     OK ]" : "[ FAILED ]", name.c_str());
    std::fflush(stdout);
    if (!ok)
    {
      failed.push_back(name);
    }
  }
  if (!failed.empty())
  {
    std::fprintf(stderr, "%s: %zu of %zu cases failed:", program.c_str(), failed.size(), ran);
    for (const std::string& name : failed)
    {
      std::fprintf(stderr, " %s", name.c_str());
    }
    std::fprintf(stderr, "\n");
    return 1;
  }
  std::printf("%s: all %zu cases passed\n", program.c_str(), ran);
  return 0;
}

/**
 * Catches vtkErrorMacro output (observe ErrorEvent with it) so that expected
 * errors are checked, not printed: Count and the Last message.
 */
class ErrorCatcher : public vtkCommand
{
public:
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    this->Last = data ? static_cast<const char*>(data) : "";
    this->All += this->Last;
    this->All += '\n';
    ++this->Count;
  }
  /** Whether an error containing `fragment` came since the last call; resets. */
  bool Caught(const char* fragment)
  {
    const bool ok = this->Count > 0 && this->All.find(fragment) != std::string::npos;
    if (!ok)
    {
      std::fprintf(stderr, "expected an error containing '%s', got %d errors, last '%s'\n", fragment,
        this->Count, this->Last.c_str());
    }
    this->Count = 0;
    this->Last.clear();
    this->All.clear();
    return ok;
  }
  std::string Last;
  std::string All; // every message since the last Caught()
  int Count = 0;
};

/** The area lights' buffer of the last frame (vtkMRGIPass::GetAreaLightBuffer()); fails the test when there is none. */
inline vtkSmartPointer<vtkImageData> AreaBuffer(vtkMRGIPass* pass, vtkRenderWindow* window)
{
  vtkNew<vtkImageData> image;
  MRGI_TEST_CHECK(pass->GetAreaLightBuffer(window, image));
  return vtkSmartPointer<vtkImageData>(image.GetPointer());
}

/** The VPLs of the last frame (vtkMRGIPass::GetVPLs()) as records; fails the test when there are none. */
inline std::vector<mrgi_vpl> ReadVPLs(vtkMRGIPass* pass, vtkRenderWindow* window)
{
  vtkNew<vtkFloatArray> array;
  MRGI_TEST_CHECK(pass->GetVPLs(window, array));
  MRGI_TEST_CHECK(array->GetNumberOfComponents() == MRGI_VPL_FLOATS);
  std::vector<mrgi_vpl> vpls(static_cast<size_t>(array->GetNumberOfTuples()));
  std::memcpy(vpls.data(), array->GetPointer(0), sizeof(mrgi_vpl) * vpls.size());
  return vpls;
}

/** A headless window of the given size; without one, Fail() with the reason. */
inline vtkSmartPointer<vtkRenderWindow> HeadlessWindow(int width, int height)
{
  std::string why;
  vtkSmartPointer<vtkRenderWindow> window = vtkSmartPointer<vtkRenderWindow>::Take(
    vtkMRGIRenderWindowFactory::CreateRenderWindow(vtkMRGIRenderWindowFactory::Headless, &why));
  if (!window)
  {
    MRGI_TEST_FAIL("no headless window: %s", why.c_str());
  }
  // The tests registered again with MRGI_BACKEND=osmesa must not run on EGL.
  const char* backend = std::getenv("MRGI_BACKEND");
  if (backend && backend[0] && std::string(backend) != "auto" &&
    std::string(backend) != vtkMRGIRenderWindowFactory::GetBackendName(window))
  {
    MRGI_TEST_FAIL("MRGI_BACKEND=%s, but the factory made a %s window", backend,
      vtkMRGIRenderWindowFactory::GetBackendName(window));
  }
  std::printf(
    "headless window: %s\n", vtkMRGIRenderWindowFactory::DescribeRenderWindow(window).c_str());
  window->SetSize(width, height);
  window->SetMultiSamples(0);
  return window;
}

/**
 * The world -> eye matrix the C gather twin takes (column-major floats, as
 * OpenGL), from vtkMRGIPass::GetLastViewToWorld() (column-major doubles).
 */
inline void WorldToViewColumnMajor(const double viewToWorld[16], float worldToView[16])
{
  vtkNew<vtkMatrix4x4> forward, inverse;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      forward->SetElement(r, c, viewToWorld[c * 4 + r]);
    }
  }
  vtkMatrix4x4::Invert(forward, inverse);
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      worldToView[c * 4 + r] = static_cast<float>(inverse->GetElement(r, c));
    }
  }
}

/** Scratch directory for this test's files ($MRGI_TEST_TMP or /tmp). */
inline std::string TempPath(const std::string& name)
{
  const char* dir = std::getenv("MRGI_TEST_TMP");
  return std::string(dir && dir[0] ? dir : "/tmp") + "/" + name;
}

/** The window's RGB pixels as an unsigned-char vtkImageData (bottom-up). */
inline vtkSmartPointer<vtkImageData> GrabRGB(vtkRenderWindow* window)
{
  const int* size = window->GetSize();
  vtkNew<vtkUnsignedCharArray> rgba;
  window->GetRGBACharPixelData(0, 0, size[0] - 1, size[1] - 1, 0, rgba);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(static_cast<vtkIdType>(size[0]) * size[1]);
  for (vtkIdType p = 0; p < rgb->GetNumberOfTuples(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      rgb->SetValue(3 * p + c, rgba->GetValue(4 * p + c));
    }
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(size[0], size[1], 1);
  image->GetPointData()->SetScalars(rgb);
  return image;
}

/** Mean RGB (0..255) of the window-pixel rectangle [x0,x1) x [y0,y1), y from the bottom. */
inline void MeanColor(vtkImageData* image, int x0, int y0, int x1, int y1, double rgb[3])
{
  rgb[0] = rgb[1] = rgb[2] = 0;
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* s = image->GetPointData()->GetScalars();
  double n = 0;
  for (int y = y0; y < y1; ++y)
  {
    for (int x = x0; x < x1; ++x)
    {
      const vtkIdType id = static_cast<vtkIdType>(y) * dims[0] + x;
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] += s->GetComponent(id, c);
      }
      n += 1;
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] /= (n > 0 ? n : 1);
  }
}

/**
 * Compare `image` with the baseline `name`.png under MRGI_BASELINE_DIR.
 * Returns true when the relative RMS error is at most `tolerance`; prints the
 * metrics either way and keeps test/difference images on failure.
 */
inline bool CompareWithBaseline(vtkImageData* image, const std::string& name, double tolerance)
{
  const char* baselineDir = std::getenv("MRGI_BASELINE_DIR");
  if (!baselineDir)
  {
    std::fprintf(stderr, "MRGI_BASELINE_DIR is not set\n");
    return false;
  }
  const std::string baseline = std::string(baselineDir) + "/" + name + ".png";
  vtkNew<vtkMRGIImageIO> io;
  const char* regenerate = std::getenv("MRGI_REGENERATE_BASELINES");
  if (regenerate && std::string(regenerate) == "1")
  {
    const bool ok = io->WritePNG(image, baseline.c_str());
    std::printf("regenerated baseline %s: %s\n", baseline.c_str(), ok ? "ok" : io->GetLastErrorMessage());
    return ok;
  }
  vtkNew<vtkImageData> reference;
  if (!io->Read(baseline.c_str(), reference))
  {
    std::fprintf(stderr, "cannot read baseline %s: %s\n", baseline.c_str(), io->GetLastErrorMessage());
    return false;
  }
  mrgi_image test{}, ref{}, diff{};
  std::string why;
  bool ok = vtkMRGIImageIO::ToCoreImage(image, &test, why) &&
    vtkMRGIImageIO::ToCoreImage(reference, &ref, why);
  mrgi_metrics metrics{};
  mrgi_error err;
  if (ok && mrgi_metrics_compare(&test, &ref, nullptr, 1.0, &metrics, &err) != MRGI_OK)
  {
    why = err.message;
    ok = false;
  }
  if (!ok)
  {
    std::fprintf(stderr, "regression %s: cannot compare: %s\n", name.c_str(), why.c_str());
  }
  else
  {
    std::printf("regression %s: relative RMS %.5f (tolerance %.5f), max %.4f, PSNR %.2f dB, "
                "SSIM %.4f\n",
      name.c_str(), metrics.relative_rms, tolerance, metrics.max_abs_error, metrics.psnr_db,
      metrics.ssim);
    ok = metrics.relative_rms <= tolerance;
  }
  // Runs on another backend (cxx.X.osmesa) keep their own files.
  const char* backend = std::getenv("MRGI_BACKEND");
  const std::string kept = name + (backend && backend[0] ? std::string(".") + backend : "");
  if (!ok)
  {
    io->WritePNG(image, TempPath(kept + ".test.png").c_str());
    if (test.pixels && ref.pixels &&
      mrgi_metrics_difference_image(&test, &ref, nullptr, &diff, &err) == MRGI_OK)
    {
      for (size_t i = 0; i < mrgi_image_value_count(&diff); ++i)
      {
        diff.pixels[i] = std::fmin(1.0f, 4.0f * diff.pixels[i]);
      }
      vtkNew<vtkImageData> diffImage;
      if (vtkMRGIImageIO::FromCoreImage(&diff, diffImage, why))
      {
        io->WritePNG(diffImage, TempPath(kept + ".diff.png").c_str());
      }
    }
    std::fprintf(stderr, "kept %s and %s\n", TempPath(kept + ".test.png").c_str(),
      TempPath(kept + ".diff.png").c_str());
  }
  mrgi_image_destroy(&test);
  mrgi_image_destroy(&ref);
  mrgi_image_destroy(&diff);
  return ok;
}
}

#endif
