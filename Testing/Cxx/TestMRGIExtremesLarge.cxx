// The largest window of TestMRGIExtremes' checks: 4096 x 4096 with indirect
// light on (the Cornell box). The colour, indirect and irradiance buffers
// have the window's size and hold no NaN or Inf, indirect light was added,
// and on a subsample of rows the GPU gather equals the C twin
// (mrgi_gather_full) within 1e-4 relative RMS. Label "extremes": long.
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkFloatArray.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMatrix4x4.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"

#include "mrgi_gather.h"
#include "mrgi_vpl.h"

#include <cmath>
#include <cstring>
#include <vector>

namespace
{
float* Floats(vtkImageData* image)
{
  return vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars())->GetPointer(0);
}

// Every value finite, the image size x size; returns the largest of the first
// `components` of each pixel.
double CheckImage(vtkImageData* image, int size, int components, const char* what)
{
  int dims[3];
  image->GetDimensions(dims);
  MRGI_TEST_CHECK(dims[0] == size && dims[1] == size);
  const int n = image->GetNumberOfScalarComponents();
  const float* v = Floats(image);
  const size_t count = static_cast<size_t>(size) * size * n;
  size_t bad = 0;
  double maxValue = 0;
  for (size_t i = 0; i < count; ++i)
  {
    bad += !std::isfinite(v[i]);
    if (static_cast<int>(i % n) < components)
    {
      maxValue = std::fmax(maxValue, v[i]);
    }
  }
  std::printf("%s: %d x %d x %d, %zu non-finite, max %.4g\n", what, dims[0], dims[1], n, bad, maxValue);
  MRGI_TEST_CHECK(bad == 0);
  return maxValue;
}
}

int main()
{
  const int size = 4096;
  mrgitest::PassScene scene(size, size, "cornell");
  vtkRenderWindow* window = scene.Window;
  vtkRenderer* renderer = scene.Renderer;
  vtkMRGIPass* pass = scene.Pass;
  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  window->Render();
  MRGI_TEST_CHECK(pass->GetBufferSize()[0] == size && pass->GetBufferSize()[1] == size);
  MRGI_TEST_CHECK(pass->GetIndirectComputed());

  {
    vtkNew<vtkImageData> color;
    MRGI_TEST_CHECK(pass->GetColorBuffer(window, color));
    CheckImage(color, size, 3, "colour");
  }
  vtkNew<vtkImageData> indirect, irradiance;
  MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, indirect));
  MRGI_TEST_CHECK(CheckImage(indirect, size, 3, "indirect") > 0);
  MRGI_TEST_CHECK(pass->GetIrradianceBuffer(window, irradiance));
  CheckImage(irradiance, size, 3, "irradiance");
  indirect->Initialize();

  // The C twin on every 128th row (32 rows of 4096 pixels).
  vtkNew<vtkImageData> position, normal, albedo;
  MRGI_TEST_CHECK(pass->GetGBuffer(window, position, normal, albedo));
  albedo->Initialize();
  vtkNew<vtkFloatArray> vplArray;
  MRGI_TEST_CHECK(pass->GetVPLs(window, vplArray));
  std::vector<mrgi_vpl> vpls(static_cast<size_t>(vplArray->GetNumberOfTuples()));
  std::memcpy(vpls.data(), vplArray->GetPointer(0), sizeof(mrgi_vpl) * vpls.size());
  const int step = 128, rows = size / step;
  std::vector<float> P(static_cast<size_t>(rows) * size * 4), N(P.size());
  std::vector<float> E(static_cast<size_t>(rows) * size * 3);
  for (int r = 0; r < rows; ++r)
  {
    const size_t src = static_cast<size_t>(r) * step * size;
    const size_t dst = static_cast<size_t>(r) * size;
    std::memcpy(P.data() + 4 * dst, Floats(position) + 4 * src, sizeof(float) * 4 * size);
    std::memcpy(N.data() + 4 * dst, Floats(normal) + 4 * src, sizeof(float) * 4 * size);
    std::memcpy(E.data() + 3 * dst, Floats(irradiance) + 3 * src, sizeof(float) * 3 * size);
  }
  const double* m = pass->GetLastViewToWorld();
  float w2r[16];
  mrgitest::WorldToViewColumnMajor(m, w2r);
  mrgi_gather_receivers receivers = { size, rows, P.data(), N.data() };
  mrgi_image c{};
  mrgi_gather_info info;
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_gather_full(&receivers, vpls.data(), static_cast<int32_t>(vpls.size()), w2r,
                    &c, &info, &err) == MRGI_OK);
  double num = 0, den = 0;
  for (size_t i = 0; i < E.size(); ++i)
  {
    num += (E[i] - static_cast<double>(c.pixels[i])) * (E[i] - static_cast<double>(c.pixels[i]));
    den += static_cast<double>(c.pixels[i]) * c.pixels[i];
  }
  mrgi_image_destroy(&c);
  const double rms = den > 0 ? std::sqrt(num / den) : 1.0;
  std::printf("gather vs C twin on %d rows (%lld receivers, %d VPLs used): relative RMS %.3g\n", rows,
    static_cast<long long>(info.receivers_gathered), info.vpls_used, rms);
  MRGI_TEST_CHECK(info.receivers_gathered > 0 && rms < 1e-4);

  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  return 0;
}
