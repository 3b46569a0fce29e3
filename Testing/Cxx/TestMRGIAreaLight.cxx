// vtkMRGIAreaLight, the VTK layer over the core's mrgi_area_light: its
// samples, uniforms and core light are the core's on the same inputs
// (untextured, 8-bit, sRGB, gray, RGBA, float and pipeline-fed textures);
// the pyramid and samples are rebuilt exactly when their inputs change (a
// modified image is the next video frame); every bad input is an error
// naming it, a false return, untouched outputs and no NaN, and fixing it
// recovers; the emitter actor draws the radiance, black from behind a
// one-sided light, the texture upright, the next frame, and nothing when
// hidden or invalid.
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageShiftScale.h"
#include "vtkLight.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIPass.h"
#include "vtkPointData.h"
#include "vtkPlaneSource.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkTestErrorObserver.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"

#include "mrgi_area_light.h"
#include "mrgi_image.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

namespace
{
// A W x H unsigned-char image with `components` components, value
// (x * 37 + y * 91 + c * 53) % 256 (VTK rows, bottom first).
vtkSmartPointer<vtkImageData> MakeImage8(int w, int h, int components)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, components);
  auto* s = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      for (int c = 0; c < components; ++c)
      {
        s->SetValue((y * w + x) * components + c,
          static_cast<unsigned char>((x * 37 + y * 91 + c * 53) % 256));
      }
    }
  }
  return image;
}

// The core's 3-channel float image of a VTK image (rows flipped: the core's
// row 0 is the top), gray replicated, alpha dropped, 8-bit values / 255 or
// sRGB-decoded: the reference the class must reproduce.
void ReferenceImage(vtkImageData* image, bool srgb, mrgi_image* out)
{
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* s = image->GetPointData()->GetScalars();
  const int n = s->GetNumberOfComponents();
  const bool u8 = s->GetDataType() == VTK_UNSIGNED_CHAR;
  MRGI_TEST_CHECK(mrgi_image_create(out, dims[0], dims[1], 3, nullptr) == MRGI_OK);
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      float* texel = mrgi_image_at(out, x, dims[1] - 1 - y);
      for (int c = 0; c < 3; ++c)
      {
        double v = s->GetComponent(y * dims[0] + x, n < 3 ? 0 : c);
        if (u8)
        {
          const float linear = static_cast<float>(v) / 255.0f;
          v = srgb ? mrgi_srgb_decode(linear) : linear;
        }
        texel[c] = static_cast<float>(v);
      }
    }
  }
}

// The core's samples for the light's properties and a reference texture.
std::vector<float> CoreSamples(vtkMRGIAreaLight* light, const mrgi_image* texture)
{
  mrgi_area_light core{};
  for (int c = 0; c < 3; ++c)
  {
    core.center[c] = light->GetCenter()[c];
    core.edge_u[c] = light->GetEdgeU()[c];
    core.edge_v[c] = light->GetEdgeV()[c];
    core.color[c] = light->GetColor()[c];
  }
  core.intensity = light->GetIntensity();
  core.two_sided = light->GetTwoSided() ? 1 : 0;
  core.texture = texture;
  mrgi_area_light_texture_pyramid pyramid{};
  if (texture)
  {
    MRGI_TEST_CHECK(mrgi_area_light_texture_pyramid_create(&pyramid, texture, nullptr) == MRGI_OK);
  }
  std::vector<mrgi_area_light_sample> samples(MRGI_AREA_LIGHT_MAX_SAMPLES);
  int32_t count = 0;
  MRGI_TEST_CHECK(mrgi_area_light_make_samples(&core, texture ? &pyramid : nullptr,
                    light->GetNumberOfSamples(), light->GetJitter() ? 1 : 0, light->GetSeed(),
                    samples.data(), MRGI_AREA_LIGHT_MAX_SAMPLES, &count, nullptr) == MRGI_OK);
  mrgi_area_light_texture_pyramid_destroy(&pyramid);
  const float* data = mrgi_area_light_sample_texture_data(samples.data());
  return std::vector<float>(
    data, data + static_cast<size_t>(count) * MRGI_AREA_LIGHT_SAMPLE_FLOATS);
}

std::vector<float> Values(vtkFloatArray* a)
{
  return std::vector<float>(a->GetPointer(0), a->GetPointer(0) + a->GetNumberOfValues());
}

// The light's samples, checked for layout and finiteness.
std::vector<float> LightSamples(vtkMRGIAreaLight* light)
{
  vtkNew<vtkFloatArray> samples;
  MRGI_TEST_CHECK(light->GetSamples(samples));
  MRGI_TEST_CHECK(samples->GetNumberOfComponents() == 4);
  MRGI_TEST_CHECK(samples->GetNumberOfTuples() % 3 == 0);
  MRGI_TEST_CHECK(samples->GetNumberOfTuples() / 3 <= light->GetNumberOfSamples());
  for (vtkIdType i = 0; i < samples->GetNumberOfValues(); ++i)
  {
    MRGI_TEST_CHECK(std::isfinite(samples->GetValue(i)));
  }
  return Values(samples);
}

// Max relative difference of two sample sets of the same size.
double MaxRelative(const std::vector<float>& a, const std::vector<float>& b)
{
  MRGI_TEST_CHECK(a.size() == b.size());
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    worst = std::fmax(worst, std::fabs(a[i] - b[i]) / std::fmax(1e-6, std::fabs(b[i])));
  }
  return worst;
}

// A bad input: GetSamples, GetCoreLight and GetCoreSamples fail with an
// error containing `expected`, `samples` keeps its contents, nothing is NaN.
void ExpectFailure(vtkMRGIAreaLight* light, vtkTest::ErrorObserver* errors, const char* expected,
  const char* what)
{
  vtkNew<vtkFloatArray> samples;
  samples->SetNumberOfComponents(4);
  samples->InsertNextTuple4(1, 2, 3, 4);
  errors->Clear();
  const bool ok = light->GetSamples(samples);
  if (ok || errors->CheckErrorMessage(expected) != 0)
  {
    MRGI_TEST_FAIL("%s: GetSamples %s; error: '%s'", what, ok ? "succeeded" : "failed",
      errors->GetErrorMessage().c_str());
  }
  MRGI_TEST_CHECK(std::string(light->GetLastErrorMessage()).find(expected) != std::string::npos);
  MRGI_TEST_CHECK(samples->GetNumberOfTuples() == 1 && samples->GetValue(0) == 1 &&
    samples->GetValue(3) == 4);
  // A second request on the same bad state says it again (from the cache).
  errors->Clear();
  MRGI_TEST_CHECK(!light->GetSamples(samples) && errors->CheckErrorMessage(expected) == 0);
  mrgi_area_light core;
  std::memset(&core, 0x7f, sizeof(core));
  errors->Clear();
  const bool coreOk = light->GetCoreLight(&core);
  // An overflow of radiance (texture * scale) is only found by sampling.
  MRGI_TEST_CHECK(coreOk == (std::string(expected) == "float range"));
  if (!coreOk)
  {
    MRGI_TEST_CHECK(errors->GetError());
    unsigned char pattern[sizeof(core)];
    std::memset(pattern, 0x7f, sizeof(pattern));
    MRGI_TEST_CHECK(std::memcmp(&core, pattern, sizeof(core)) == 0);
  }
  int count = -1;
  errors->Clear();
  MRGI_TEST_CHECK(light->GetCoreSamples(&count) == nullptr && count == 0 && errors->GetError());
  std::printf("bad input rejected (%s): %s\n", what, light->GetLastErrorMessage());
}

// Mean RGB (0..255) of the window pixels [x0, x1) x [y0, y1).
void Mean(vtkRenderWindow* window, int x0, int y0, int x1, int y1, double rgb[3])
{
  vtkSmartPointer<vtkImageData> image = mrgitest::GrabRGB(window);
  mrgitest::MeanColor(image, x0, y0, x1, y1, rgb);
}

bool Near(const double rgb[3], double r, double g, double b, double tolerance)
{
  const bool ok = std::fabs(rgb[0] - r) <= tolerance && std::fabs(rgb[1] - g) <= tolerance &&
    std::fabs(rgb[2] - b) <= tolerance;
  if (!ok)
  {
    std::fprintf(stderr, "got (%.1f, %.1f, %.1f), expected (%.1f, %.1f, %.1f) +- %.1f\n", rgb[0],
      rgb[1], rgb[2], r, g, b, tolerance);
  }
  return ok;
}

// Overwrite the 2 x 2 RGB unsigned-char image's scalars (VTK rows, bottom first).
void SetTexels(vtkImageData* image, std::initializer_list<int> values)
{
  auto* texels = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  vtkIdType i = 0;
  for (int v : values)
  {
    texels->SetValue(i++, static_cast<unsigned char>(v));
  }
}

// The four quadrants of the 64 x 64 window (8 x 8 pixels near each corner,
// between the texel centres and the quad's edges, where bilinear filtering
// clamped at the edges gives a texel's own colour) against `expected`:
// bottom-left, bottom-right, top-left, top-right, RGB each (0..255).
bool Quadrants(vtkRenderWindow* window, std::initializer_list<double> expected)
{
  const int corners[4][2] = { { 8, 8 }, { 48, 8 }, { 8, 48 }, { 48, 48 } };
  std::vector<double> e(expected);
  bool ok = true;
  for (int q = 0; q < 4; ++q)
  {
    double rgb[3];
    Mean(window, corners[q][0], corners[q][1], corners[q][0] + 8, corners[q][1] + 8, rgb);
    if (!Near(rgb, e[3 * q], e[3 * q + 1], e[3 * q + 2], 2.0))
    {
      std::fprintf(
        stderr, "  in quadrant %d (bottom-left, bottom-right, top-left, top-right)\n", q);
      ok = false;
    }
  }
  return ok;
}

void TestSamplesAndCache()
{
  vtkNew<vtkMRGIAreaLight> light;
  MRGI_TEST_CHECK(light->GetNumberOfSamples() == MRGI_AREA_LIGHT_DEFAULT_SAMPLES);
  MRGI_TEST_CHECK(light->GetVisible() && !light->GetTwoSided() && light->GetIntensity() == 1.0);
  light->SetNumberOfSamples(100000);
  MRGI_TEST_CHECK(light->GetNumberOfSamples() == MRGI_AREA_LIGHT_MAX_SAMPLES);
  light->SetNumberOfSamples(0);
  MRGI_TEST_CHECK(light->GetNumberOfSamples() == MRGI_AREA_LIGHT_MIN_SAMPLES);

  // Untextured, a 2:1 light facing +y, 100 samples requested (a 14 x 7 grid).
  light->SetCenter(1, 2, 3);
  light->SetEdgeU(2, 0, 0);
  light->SetEdgeV(0, 0, -1);
  light->SetColor(1, 0.5, 0.25);
  light->SetIntensity(3);
  light->SetNumberOfSamples(100);
  std::vector<float> plain = LightSamples(light);
  MRGI_TEST_CHECK(plain == CoreSamples(light, nullptr));
  MRGI_TEST_CHECK(plain.size() == 98 * 12);
  // Texel layout: position + area, normal + 0, radiance + 0.
  MRGI_TEST_CHECK(plain[4] == 0 && plain[5] == 1 && plain[6] == 0 && plain[7] == 0);
  MRGI_TEST_CHECK(std::fabs(plain[8] - 3.0f) < 1e-6 && std::fabs(plain[9] - 1.5f) < 1e-6);
  MRGI_TEST_CHECK(std::fabs(plain[3] * 98 - 2.0f) < 1e-5); // areas sum to |u x v|
  MRGI_TEST_CHECK(light->GetNumberOfSampleBuilds() == 1);
  MRGI_TEST_CHECK(light->GetNumberOfTextureBuilds() == 0);

  // The core structs.
  mrgi_area_light core;
  MRGI_TEST_CHECK(light->GetCoreLight(&core));
  MRGI_TEST_CHECK(core.center[1] == 2 && core.edge_u[0] == 2 && core.edge_v[2] == -1 &&
    core.color[2] == 0.25 && core.intensity == 3 && core.two_sided == 0 && !core.texture);
  mrgi_area_light_uniforms uniforms, expected;
  MRGI_TEST_CHECK(light->GetCoreUniforms(&uniforms));
  MRGI_TEST_CHECK(mrgi_area_light_uniforms_init(&core, nullptr, &expected, nullptr) == MRGI_OK);
  MRGI_TEST_CHECK(std::memcmp(&uniforms, &expected, sizeof(expected)) == 0);
  // Any non-null start value: an untextured light must answer nullptr.
  const auto* pyramid = reinterpret_cast<const mrgi_area_light_texture_pyramid*>(&core);
  MRGI_TEST_CHECK(light->GetCorePyramid(&pyramid) && pyramid == nullptr);
  int count = 0;
  const mrgi_area_light_sample* records = light->GetCoreSamples(&count);
  MRGI_TEST_CHECK(records && count == 98);
  MRGI_TEST_CHECK(std::memcmp(mrgi_area_light_sample_texture_data(records), plain.data(),
                    plain.size() * sizeof(float)) == 0);

  // Nothing changed, or only what samples ignore: the cache answers.
  LightSamples(light);
  light->SetCenter(1, 2, 3);
  light->SetVisible(false);
  light->GetCoreSamples(&count);
  MRGI_TEST_CHECK(light->GetNumberOfSampleBuilds() == 1);
  light->SetIntensity(4);
  std::vector<float> brighter = LightSamples(light);
  MRGI_TEST_CHECK(light->GetNumberOfSampleBuilds() == 2);
  MRGI_TEST_CHECK(std::fabs(brighter[8] - 4.0f) < 1e-6);
  light->JitterOn();
  light->SetSeed(7);
  MRGI_TEST_CHECK(LightSamples(light) == CoreSamples(light, nullptr));
  light->JitterOff();
  light->SetTwoSided(true);
  MRGI_TEST_CHECK(LightSamples(light) == CoreSamples(light, nullptr));
  light->SetTwoSided(false);

  // An 8-bit RGB texture (non-square, non power of two).
  vtkSmartPointer<vtkImageData> image = MakeImage8(24, 10, 3);
  light->SetNumberOfSamples(256);
  light->SetTextureData(image);
  mrgi_image reference{};
  ReferenceImage(image, false, &reference);
  std::vector<float> textured = LightSamples(light);
  MRGI_TEST_CHECK(textured == CoreSamples(light, &reference));
  MRGI_TEST_CHECK(light->GetNumberOfTextureBuilds() == 1);
  const int builds = light->GetNumberOfSampleBuilds();
  MRGI_TEST_CHECK(light->GetCoreLight(&core) && core.texture && core.texture->width == 24 &&
    core.texture->height == 10 && core.texture->channels == 3);
  MRGI_TEST_CHECK(std::memcmp(core.texture->pixels, reference.pixels,
                    mrgi_image_value_count(&reference) * sizeof(float)) == 0);
  MRGI_TEST_CHECK(light->GetCoreUniforms(&uniforms) && uniforms.texture_width == 24 &&
    uniforms.texture_height == 10 && uniforms.texture_levels == 5);
  MRGI_TEST_CHECK(light->GetCorePyramid(&pyramid) && pyramid && pyramid->level_count == 5);
  mrgi_image_destroy(&reference);

  // Same image, not modified: reused.
  LightSamples(light);
  MRGI_TEST_CHECK(light->GetNumberOfTextureBuilds() == 1);
  MRGI_TEST_CHECK(light->GetNumberOfSampleBuilds() == builds);

  // The next video frame: new values, Modified(); picked up on the next call.
  auto* scalars = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  for (vtkIdType i = 0; i < scalars->GetNumberOfValues(); ++i)
  {
    scalars->SetValue(i, static_cast<unsigned char>(255 - scalars->GetValue(i)));
  }
  image->Modified();
  std::vector<float> nextFrame = LightSamples(light);
  MRGI_TEST_CHECK(nextFrame != textured);
  ReferenceImage(image, false, &reference);
  MRGI_TEST_CHECK(nextFrame == CoreSamples(light, &reference));
  MRGI_TEST_CHECK(light->GetNumberOfTextureBuilds() == 2);
  MRGI_TEST_CHECK(light->GetNumberOfSampleBuilds() == builds + 1);
  // Modifying only the scalars array counts too (it is part of the image's MTime).
  scalars->SetValue(0, static_cast<unsigned char>(scalars->GetValue(0) ^ 0xff));
  scalars->Modified();
  LightSamples(light);
  MRGI_TEST_CHECK(light->GetNumberOfTextureBuilds() == 3);

  // Moving the light rebuilds the samples, not the pyramid.
  light->SetCenter(0, 0, 0);
  LightSamples(light);
  MRGI_TEST_CHECK(light->GetNumberOfTextureBuilds() == 3);
  MRGI_TEST_CHECK(light->GetNumberOfSampleBuilds() == builds + 3);
  mrgi_image_destroy(&reference);

  // Through a vtkTexture: the same samples; with UseSRGBColorSpace decoded.
  ReferenceImage(image, false, &reference);
  const std::vector<float> linear = CoreSamples(light, &reference);
  mrgi_image_destroy(&reference);
  vtkNew<vtkTexture> texture;
  texture->SetInputData(image);
  light->SetTexture(texture);
  MRGI_TEST_CHECK(light->GetTextureData() == nullptr);
  MRGI_TEST_CHECK(LightSamples(light) == linear);
  texture->UseSRGBColorSpaceOn();
  ReferenceImage(image, true, &reference);
  std::vector<float> decoded = LightSamples(light);
  MRGI_TEST_CHECK(MaxRelative(decoded, CoreSamples(light, &reference)) < 1e-6);
  MRGI_TEST_CHECK(decoded != linear);
  mrgi_image_destroy(&reference);
  texture->UseSRGBColorSpaceOff();

  // A texture fed by a pipeline: the light updates it when it needs it.
  vtkNew<vtkImageShiftScale> halve;
  halve->SetInputData(MakeImage8(16, 16, 3));
  halve->SetScale(0.5);
  halve->SetOutputScalarTypeToUnsignedChar();
  texture->SetInputConnection(halve->GetOutputPort());
  std::vector<float> half = LightSamples(light);
  halve->SetScale(0.25);
  std::vector<float> quarter = LightSamples(light);
  MRGI_TEST_CHECK(half != quarter);
  halve->Update();
  ReferenceImage(halve->GetOutput(), false, &reference);
  MRGI_TEST_CHECK(quarter == CoreSamples(light, &reference));
  mrgi_image_destroy(&reference);

  // Gray, gray + alpha and RGBA 8-bit images: the colour as RGB, alpha ignored.
  for (int components : { 1, 2, 4 })
  {
    vtkSmartPointer<vtkImageData> other = MakeImage8(9, 7, components);
    light->SetTextureData(other);
    ReferenceImage(other, false, &reference);
    MRGI_TEST_CHECK(LightSamples(light) == CoreSamples(light, &reference));
    mrgi_image_destroy(&reference);
  }
  MRGI_TEST_CHECK(light->GetTexture() == nullptr);

  // A float (HDR) texture is radiance as is.
  vtkNew<vtkImageData> hdr;
  hdr->SetDimensions(5, 3, 1);
  hdr->AllocateScalars(VTK_FLOAT, 3);
  auto* values = vtkFloatArray::SafeDownCast(hdr->GetPointData()->GetScalars());
  for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
  {
    values->SetValue(i, 0.25f * static_cast<float>(i % 41));
  }
  light->SetTextureData(hdr);
  ReferenceImage(hdr, false, &reference);
  MRGI_TEST_CHECK(LightSamples(light) == CoreSamples(light, &reference));
  mrgi_image_destroy(&reference);

  // Back to untextured.
  light->SetTextureData(nullptr);
  MRGI_TEST_CHECK(LightSamples(light) == CoreSamples(light, nullptr));
  std::printf("samples: equal to the core's; %d pyramid and %d sample builds\n",
    light->GetNumberOfTextureBuilds(), light->GetNumberOfSampleBuilds());
}

void TestBadInput()
{
  vtkNew<vtkMRGIAreaLight> light;
  vtkNew<vtkTest::ErrorObserver> errors;
  light->AddObserver(vtkCommand::ErrorEvent, errors);
  const std::vector<float> good = LightSamples(light);
  const double nan = std::nan("");

  light->SetCenter(0, nan, 0);
  ExpectFailure(light, errors, "Center[1]", "NaN center");
  light->SetCenter(0, 0, 0);
  light->SetEdgeU(nan, 0, 0);
  ExpectFailure(light, errors, "EdgeU", "NaN edge");
  light->SetEdgeU(1, 0, 0);
  light->SetEdgeV(0, 0, 0);
  ExpectFailure(light, errors, "EdgeV is a zero-length edge", "zero edge");
  light->SetEdgeV(2, 0, 0);
  ExpectFailure(light, errors, "parallel", "parallel edges");
  light->SetEdgeV(1, 1, 0);
  ExpectFailure(light, errors, "not perpendicular", "skewed edges");
  light->SetEdgeV(0, 1, 0);
  light->SetIntensity(-1);
  MRGI_TEST_CHECK(light->GetIntensity() == -1); // kept as given, reported on use
  ExpectFailure(light, errors, "Intensity", "negative intensity");
  light->SetIntensity(nan);
  ExpectFailure(light, errors, "Intensity", "NaN intensity");
  light->SetIntensity(1);
  light->SetColor(1, -0.5, 1);
  ExpectFailure(light, errors, "Color[1]", "negative color");
  light->SetColor(1, 1, 1);
  MRGI_TEST_CHECK(LightSamples(light) == good);

  // The emitter geometry of an invalid light: refused too.
  light->SetEdgeV(0, 0, 0);
  vtkNew<vtkPolyData> quad;
  errors->Clear();
  MRGI_TEST_CHECK(
    !light->MakeGeometry(quad) && errors->GetError() && quad->GetNumberOfPoints() == 0);
  light->SetEdgeV(0, 1, 0);

  // Textures.
  vtkNew<vtkImageData> doubles;
  doubles->SetDimensions(4, 4, 1);
  doubles->AllocateScalars(VTK_DOUBLE, 3);
  doubles->GetPointData()->GetScalars()->Fill(0.5);
  light->SetTextureData(doubles);
  ExpectFailure(light, errors, "type double", "double texture");
  light->SetTextureData(MakeImage8(4, 4, 5));
  ExpectFailure(light, errors, "5 components", "5 components");
  vtkNew<vtkImageData> empty;
  light->SetTextureData(empty);
  ExpectFailure(light, errors, "empty", "empty image");
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(4, 4, 2);
  volume->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  light->SetTextureData(volume);
  ExpectFailure(light, errors, "3D", "3D image");
  vtkNew<vtkImageData> bare;
  bare->SetDimensions(4, 4, 1);
  light->SetTextureData(bare);
  ExpectFailure(light, errors, "no point scalars", "no scalars");
  vtkNew<vtkImageData> hdr;
  hdr->SetDimensions(4, 4, 1);
  hdr->AllocateScalars(VTK_FLOAT, 4);
  auto* values = vtkFloatArray::SafeDownCast(hdr->GetPointData()->GetScalars());
  values->Fill(1.0);
  values->SetValue(4 * 5 + 1, static_cast<float>(nan));
  light->SetTextureData(hdr);
  ExpectFailure(light, errors, "(1, 1) component 1", "NaN texel");
  values->SetValue(4 * 5 + 1, -2.0f);
  values->Modified();
  ExpectFailure(light, errors, "not finite and >= 0", "negative texel");
  values->SetValue(4 * 5 + 3, static_cast<float>(nan)); // alpha: ignored
  values->SetValue(4 * 5 + 1, 3.0e38f);
  values->Modified();
  light->SetIntensity(1e10);
  ExpectFailure(light, errors, "float range", "radiance overflow");
  light->SetIntensity(1);
  vtkSmartPointer<vtkImageData> texels = MakeImage8(4, 4, 3);
  light->SetTextureData(texels);
  const std::vector<float> textured = LightSamples(light);
  vtkNew<vtkTexture> inputless;
  light->SetTexture(inputless);
  ExpectFailure(light, errors, "no input image", "texture without input");
  // Fixed: the next request succeeds, with the samples of the good texture.
  light->SetTextureData(texels);
  MRGI_TEST_CHECK(LightSamples(light) == textured);
  errors->Clear();
  MRGI_TEST_CHECK(!light->GetSamples(nullptr) && errors->GetError());
  MRGI_TEST_CHECK(
    std::string(light->GetLastErrorMessage()).find("no output array") != std::string::npos);
}

void TestGeometryAndRendering()
{
  vtkNew<vtkMRGIAreaLight> light;
  vtkNew<vtkTest::ErrorObserver> errors;
  light->AddObserver(vtkCommand::ErrorEvent, errors);
  light->SetCenter(1, 2, 3);
  light->SetEdgeU(0, 2, 0);
  light->SetEdgeV(0, 0, 4);
  vtkNew<vtkPolyData> quad;
  MRGI_TEST_CHECK(light->MakeGeometry(quad));
  MRGI_TEST_CHECK(quad->GetNumberOfPoints() == 4 && quad->GetNumberOfPolys() == 1);
  const double corners[4][3] = { { 1, 1, 1 }, { 1, 3, 1 }, { 1, 3, 5 }, { 1, 1, 5 } };
  const double st[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  for (int i = 0; i < 4; ++i)
  {
    double p[3], n[3], t[2];
    quad->GetPoint(i, p);
    quad->GetPointData()->GetNormals()->GetTuple(i, n);
    quad->GetPointData()->GetTCoords()->GetTuple(i, t);
    for (int c = 0; c < 3; ++c)
    {
      MRGI_TEST_CHECK(p[c] == corners[i][c]);
      MRGI_TEST_CHECK(n[c] == (c == 0 ? 1.0 : 0.0)); // u x v = +x
    }
    MRGI_TEST_CHECK(t[0] == st[i][0] && t[1] == st[i][1]);
  }

  // Render the emitter: a 2 x 2 light at the origin facing +z, filling a
  // 64 x 64 window through a parallel camera; blue background.
  const int size = 64;
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(size, size);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 1);
  window->AddRenderer(renderer);
  light->SetCenter(0, 0, 0);
  light->SetEdgeU(2, 0, 0);
  light->SetEdgeV(0, 2, 0);
  light->SetColor(1, 0.5, 0.25);
  light->SetIntensity(0.5);
  renderer->AddActor(light->GetGeometryActor());
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetParallelScale(1.0);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, 0, 5);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCameraClippingRange(-3, 3, -3, 3, -3, 3);
  window->Render();
  double rgb[3];
  Mean(window, 16, 16, 48, 48, rgb);
  MRGI_TEST_CHECK(Near(rgb, 127.5, 63.75, 31.9, 2.0)); // Intensity * Color

  // From behind: black for a one-sided light, the radiance for a two-sided one.
  camera->SetPosition(0, 0, -5);
  window->Render();
  Mean(window, 16, 16, 48, 48, rgb);
  MRGI_TEST_CHECK(Near(rgb, 0, 0, 0, 1.0));
  light->TwoSidedOn();
  window->Render();
  Mean(window, 16, 16, 48, 48, rgb);
  MRGI_TEST_CHECK(Near(rgb, 127.5, 63.75, 31.9, 2.0));
  light->TwoSidedOff();
  camera->SetPosition(0, 0, 5);

  // A 2 x 2 texture, upright from the front: VTK row 0 (bottom) red, green;
  // row 1 blue, white. Intensity 1 and white: the picture itself. Every
  // quadrant has its own colour, so texture coordinates flipped in s, in t
  // or transposed swap two of them and fail.
  vtkNew<vtkImageData> picture;
  picture->SetDimensions(2, 2, 1);
  picture->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* texels = vtkUnsignedCharArray::SafeDownCast(picture->GetPointData()->GetScalars());
  SetTexels(picture, { 255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255 });
  light->SetTextureData(picture);
  light->SetColor(1, 1, 1);
  light->SetIntensity(1);
  window->Render();
  MRGI_TEST_CHECK(light->GetGeometryActor()->GetTexture() != nullptr);
  MRGI_TEST_CHECK(Quadrants(window, { 255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255 }));
  // The samples agree: the sample nearest the bottom-left corner is red.
  std::vector<float> samples = LightSamples(light);
  MRGI_TEST_CHECK(samples[8] > 0.99f && samples[9] < 0.01f && samples[10] < 0.01f);

  // From behind: black for a one-sided light; a two-sided one shows the
  // same picture, mirrored (the camera's right is -x there).
  camera->SetPosition(0, 0, -5);
  window->Render();
  Mean(window, 8, 8, 56, 56, rgb);
  MRGI_TEST_CHECK(Near(rgb, 0, 0, 0, 1.0));
  light->TwoSidedOn();
  window->Render();
  MRGI_TEST_CHECK(Quadrants(window, { 0, 255, 0, 255, 0, 0, 255, 255, 255, 0, 0, 255 }));
  light->TwoSidedOff();
  camera->SetPosition(0, 0, 5);

  // The next video frame: new scalars in the same image and Modified(); the
  // next render shows it, nothing else called.
  SetTexels(picture, { 0, 255, 255, 255, 0, 255, 255, 255, 0, 0, 0, 0 });
  picture->Modified();
  window->Render();
  MRGI_TEST_CHECK(Quadrants(window, { 0, 255, 255, 255, 0, 255, 255, 255, 0, 0, 0, 0 }));
  // One texel of it changed (the red texel of the first frame turns half
  // grey: 128 of 255 in linear 8-bit).
  SetTexels(picture, { 255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255 });
  picture->Modified();
  window->Render();
  MRGI_TEST_CHECK(Quadrants(window, { 255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255 }));
  texels->SetValue(0, 128);
  texels->SetValue(1, 128);
  texels->SetValue(2, 128);
  picture->Modified();
  window->Render();
  Mean(window, 8, 8, 16, 16, rgb);
  MRGI_TEST_CHECK(Near(rgb, 128, 128, 128, 2.0));

  // A radiance scale above 1 is normalised for display (P = Intensity *
  // max(Color) = 40): the picture keeps its range, tinted by Color / 1.
  light->SetIntensity(40);
  light->SetColor(1, 0.5, 0.25);
  window->Render();
  MRGI_TEST_CHECK(Quadrants(window,
    { 128, 64, 32, 0, 127.5, 0, 0, 0, 63.75, 255, 127.5, 63.75 }));
  // Below 1 it is the radiance: 0.5 halves the picture.
  light->SetColor(1, 1, 1);
  light->SetIntensity(0.5);
  window->Render();
  Mean(window, 48, 48, 56, 56, rgb);
  MRGI_TEST_CHECK(Near(rgb, 127.5, 127.5, 127.5, 2.0));

  // An HDR float texture through a vtkTexture: P = max texel = 4 (Intensity
  // 1) maps 4 to 1; its next frame is shown as well.
  vtkNew<vtkImageData> hdr;
  hdr->SetDimensions(2, 2, 1);
  hdr->AllocateScalars(VTK_FLOAT, 3);
  auto* hdrTexels = vtkFloatArray::SafeDownCast(hdr->GetPointData()->GetScalars());
  const float hdrValues[12] = { 4, 0, 0, 0, 2, 0, 0, 0, 1, 1, 1, 1 };
  for (int i = 0; i < 12; ++i)
  {
    hdrTexels->SetValue(i, hdrValues[i]);
  }
  vtkNew<vtkTexture> hdrTexture;
  hdrTexture->SetInputData(hdr);
  light->SetTexture(hdrTexture);
  light->SetIntensity(1);
  window->Render();
  MRGI_TEST_CHECK(Quadrants(window,
    { 255, 0, 0, 0, 127.5, 0, 0, 0, 63.75, 63.75, 63.75, 63.75 }));
  // (A float picture's peak above 1 is its frame's: without the 4, the
  // brightest texel, 2, maps to 1.)
  hdrTexels->SetValue(0, 0); // bottom-left red 4 -> green 0.5
  hdrTexels->SetValue(1, 0.5f);
  hdr->Modified();
  window->Render();
  MRGI_TEST_CHECK(Quadrants(window,
    { 0, 63.75, 0, 0, 255, 0, 0, 0, 127.5, 127.5, 127.5, 127.5 }));

  // A second actor sharing the emitter (ShareGeometryActor) draws the same
  // picture with its own visibility, and follows the texture switch.
  vtkNew<vtkActor> view;
  light->ShareGeometryActor(view);
  light->ShareGeometryActor(view); // once is enough
  renderer->RemoveActor(light->GetGeometryActor());
  renderer->AddActor(view);
  light->VisibleOff();
  light->SetTextureData(picture); // the first frame again, red texel grey
  window->Render();
  MRGI_TEST_CHECK(view->GetVisibility() && view->GetTexture() != nullptr);
  MRGI_TEST_CHECK(Quadrants(window, { 128, 128, 128, 0, 255, 0, 0, 0, 255, 255, 255, 255 }));
  light->SetTextureData(nullptr);
  light->SetColor(0.2, 0.4, 0.6);
  window->Render();
  MRGI_TEST_CHECK(view->GetTexture() == nullptr);
  Mean(window, 16, 16, 48, 48, rgb);
  MRGI_TEST_CHECK(Near(rgb, 51, 102, 153, 2.0));
  light->SetTextureData(picture);
  light->SetColor(1, 1, 1);
  light->SetIntensity(0.5);
  window->Render();
  Mean(window, 48, 48, 56, 56, rgb);
  MRGI_TEST_CHECK(Near(rgb, 127.5, 127.5, 127.5, 2.0));
  renderer->RemoveActor(view);
  // A view keeps its light alive: made from a light nobody else holds (a
  // scene builder's, once the builder is gone), it still draws the picture.
  vtkNew<vtkActor> orphan;
  {
    auto temporary = vtkSmartPointer<vtkMRGIAreaLight>::New();
    temporary->SetEdgeU(2, 0, 0);
    temporary->SetEdgeV(0, 2, 0);
    temporary->SetTextureData(picture);
    temporary->VisibleOff();
    temporary->ShareGeometryActor(orphan);
  }
  renderer->AddActor(orphan);
  window->Render();
  MRGI_TEST_CHECK(Quadrants(window, { 128, 128, 128, 0, 255, 0, 0, 0, 255, 255, 255, 255 }));
  renderer->RemoveActor(orphan);
  renderer->AddActor(light->GetGeometryActor());
  light->VisibleOn();
  window->Render();
  Mean(window, 48, 48, 56, 56, rgb);
  MRGI_TEST_CHECK(Near(rgb, 127.5, 127.5, 127.5, 2.0));

  // Hidden, and invalid: the background shows; the error is reported once.
  light->VisibleOff();
  window->Render();
  Mean(window, 16, 16, 48, 48, rgb);
  MRGI_TEST_CHECK(Near(rgb, 0, 0, 255, 1.0));
  light->VisibleOn();
  light->SetEdgeV(0, 0, 0);
  errors->Clear();
  window->Render();
  MRGI_TEST_CHECK(errors->GetError());
  Mean(window, 16, 16, 48, 48, rgb);
  MRGI_TEST_CHECK(Near(rgb, 0, 0, 255, 1.0));
  light->SetEdgeV(0, 2, 0);
  window->Render();
  Mean(window, 48, 48, 56, 56, rgb);
  MRGI_TEST_CHECK(Near(rgb, 127.5, 127.5, 127.5, 2.0));

  // The texture removed: the plain radiance again.
  light->SetTextureData(nullptr);
  light->SetColor(0.2, 0.4, 0.6);
  light->SetIntensity(1);
  window->Render();
  Mean(window, 16, 16, 48, 48, rgb);
  MRGI_TEST_CHECK(Near(rgb, 51, 102, 153, 2.0));

  // An actor may outlive its light (a renderer holds it): it draws nothing.
  auto shortLived = vtkSmartPointer<vtkMRGIAreaLight>::New();
  vtkSmartPointer<vtkActor> actor = shortLived->GetGeometryActor();
  shortLived = nullptr;
  renderer->RemoveAllViewProps();
  renderer->AddActor(actor);
  window->Render();
  Mean(window, 16, 16, 48, 48, rgb);
  MRGI_TEST_CHECK(Near(rgb, 0, 0, 255, 1.0));
  std::printf("rendering: emitter colour, back face, texture orientation, next frame, "
              "visibility checked\n");
}

// The textured emitter drawn through vtkMRGIPass, with its own light and a
// second, bright area light facing it: the pass lights the diffuse wall
// behind the emitter but adds nothing onto the emitter (unlit geometry is
// no receiver; the gather also skips receivers in a light's plane), which
// shows the same picture as without the pass.
void TestEmitterUnderPass()
{
  const int size = 64;
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(size, size);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetParallelScale(1.0);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, 0, 5);
  camera->SetViewUp(0, 1, 0);

  // The emitter: 2 x 2 at z = 0 facing +z, the 2 x 2 picture of
  // TestGeometryAndRendering (it fills the window).
  vtkNew<vtkImageData> picture;
  picture->SetDimensions(2, 2, 1);
  picture->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  SetTexels(picture, { 255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255 });
  vtkNew<vtkMRGIAreaLight> emitter;
  emitter->SetEdgeU(2, 0, 0);
  emitter->SetEdgeV(0, 2, 0);
  emitter->SetTextureData(picture);
  emitter->SetIntensity(0.5); // P <= 1: the picture at half its values
  emitter->SetNumberOfSamples(16);
  renderer->AddActor(emitter->GetGeometryActor());
  // A grey wall behind it, larger than the view, and a second light in
  // front facing the scene (-z), its geometry not drawn.
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-3, -3, -0.5);
  plane->SetPoint1(3, -3, -0.5);
  plane->SetPoint2(-3, 3, -0.5);
  vtkNew<vtkPolyDataMapper> wallMapper;
  wallMapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> wall;
  wall->SetMapper(wallMapper);
  wall->GetProperty()->SetColor(0.5, 0.5, 0.5);
  wall->GetProperty()->SetAmbient(0.0);
  wall->GetProperty()->SetDiffuse(1.0);
  renderer->AddActor(wall);
  vtkNew<vtkMRGIAreaLight> flood;
  flood->SetCenter(0, 0, 1);
  flood->SetEdgeU(6, 0, 0);
  flood->SetEdgeV(0, -6, 0); // u x v = -z
  flood->SetIntensity(1.0);
  flood->SetNumberOfSamples(16);
  vtkNew<vtkLight> dark; // keeps VTK's lighting on, adds nothing
  dark->SetLightTypeToSceneLight();
  dark->SetIntensity(0.0);
  renderer->AddLight(dark);
  renderer->AutomaticLightCreationOff();
  renderer->ResetCameraClippingRange(-3, 3, -3, 3, -3, 3);

  // Half the picture's values (Intensity 0.5).
  const std::initializer_list<double> half = { 127.5, 0, 0, 0, 127.5, 0, 0, 0, 127.5, 127.5, 127.5,
    127.5 };
  window->Render();
  MRGI_TEST_CHECK(Quadrants(window, half));

  // Shrink the emitter to the middle half of the view: the wall shows
  // around it.
  emitter->SetEdgeU(1, 0, 0);
  emitter->SetEdgeV(0, 1, 0);
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> pass;
  pass->SetDelegatePass(steps);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  pass->SetAreaLightVisibility(vtkMRGIPass::VisibilityOff);
  pass->AddAreaLight(emitter);
  pass->AddAreaLight(flood);
  renderer->SetPass(pass);
  window->Render();
  MRGI_TEST_CHECK(pass->GetAreaLightsComputed());
  double rgb[3];
  // The wall (outside the emitter) is lit by the flood light.
  Mean(window, 2, 2, 10, 10, rgb);
  std::printf("under vtkMRGIPass: wall (%.1f, %.1f, %.1f)\n", rgb[0], rgb[1], rgb[2]);
  MRGI_TEST_CHECK(rgb[0] > 40 && rgb[1] > 40 && rgb[2] > 40);
  // The emitter (pixels 16..48) keeps its picture, quadrant by quadrant.
  // (Between the texel centres and the quad's edges, as in Quadrants().)
  const int corners[4][2] = { { 17, 17 }, { 41, 17 }, { 17, 41 }, { 41, 41 } };
  std::vector<double> e(half);
  for (int q = 0; q < 4; ++q)
  {
    Mean(window, corners[q][0], corners[q][1], corners[q][0] + 6, corners[q][1] + 6, rgb);
    MRGI_TEST_CHECK(Near(rgb, e[3 * q], e[3 * q + 1], e[3 * q + 2], 2.0));
  }
  // The next frame under the pass too.
  SetTexels(picture, { 0, 255, 255, 255, 0, 255, 255, 255, 0, 0, 0, 0 });
  picture->Modified();
  window->Render();
  const double next[12] = { 0, 127.5, 127.5, 127.5, 0, 127.5, 127.5, 127.5, 0, 0, 0, 0 };
  for (int q = 0; q < 4; ++q)
  {
    Mean(window, corners[q][0], corners[q][1], corners[q][0] + 6, corners[q][1] + 6, rgb);
    MRGI_TEST_CHECK(Near(rgb, next[3 * q], next[3 * q + 1], next[3 * q + 2], 2.0));
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  std::printf("under vtkMRGIPass: the emitter keeps its picture, the next frame too\n");
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestSamplesAndCache), MRGI_TEST_CASE(TestBadInput),
      MRGI_TEST_CASE(TestGeometryAndRendering), MRGI_TEST_CASE(TestEmitterUnderPass) });
}
