// Shared by TestMRGIBMRMask and TestMRGIBMRBlend: a frame (a Cornell
// render through vtkMRGIPass, or a random G-buffer uploaded as textures)
// with its G-buffer read back for the C twins; the BMR masks read back from
// the GPU as a mrgi_bmr_masks; a test effect rendered per level under the
// stencils; texture read-back through VTK.
#ifndef mrgiBMRTestUtilities_h
#define mrgiBMRTestUtilities_h

#include "vtk_glew.h"

#include "mrgiTestUtilities.h"

#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIBMRLevels.h"
#include "vtkMRGIBMRMask.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPixelBufferObject.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"

#include "mrgi_bmr_blend.h"
#include "mrgi_bmr_mask.h"
#include "mrgi_multires.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <random>
#include <string>
#include <vector>

namespace bmrtest
{
/** A window-sized RGBA32F texture holding `rgba` (w x h x 4 floats; null: allocated only). */
inline vtkSmartPointer<vtkTextureObject> Upload(
  vtkOpenGLRenderWindow* window, int w, int h, const float* rgba)
{
  auto t = vtkSmartPointer<vtkTextureObject>::New();
  t->SetContext(window);
  t->SetInternalFormat(GL_RGBA32F);
  t->SetFormat(GL_RGBA);
  t->SetDataType(GL_FLOAT);
  t->SetMinificationFilter(vtkTextureObject::Nearest);
  t->SetMagnificationFilter(vtkTextureObject::Nearest);
  if (rgba)
  {
    MRGI_TEST_CHECK(t->Create2DFromRaw(static_cast<unsigned int>(w), static_cast<unsigned int>(h),
      4, VTK_FLOAT, const_cast<float*>(rgba)));
  }
  else
  {
    MRGI_TEST_CHECK(
      t->Allocate2D(static_cast<unsigned int>(w), static_cast<unsigned int>(h), 4, VTK_FLOAT));
  }
  return t;
}

/** The (x, y, w, h) region of a float texture, RGBA, rows bottom-up (through a pixel buffer). */
inline std::vector<float> Read(
  vtkOpenGLRenderWindow* window, vtkTextureObject* texture, int x, int y, int w, int h)
{
  window->MakeCurrent();
  vtkNew<vtkOpenGLFramebufferObject> fbo;
  fbo->SetContext(window);
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->AddColorAttachment(0, texture);
  fbo->ActivateReadBuffer(0);
  int extent[4] = { x, x + w - 1, y, y + h - 1 };
  vtkPixelBufferObject* pbo = fbo->DownloadColor4(extent, VTK_FLOAT);
  MRGI_TEST_CHECK(pbo);
  const float* mapped = static_cast<const float*>(pbo->MapPackedBuffer());
  MRGI_TEST_CHECK(mapped);
  std::vector<float> out(mapped, mapped + 4 * static_cast<size_t>(w) * static_cast<size_t>(h));
  pbo->UnmapPackedBuffer();
  pbo->Delete();
  fbo->RemoveColorAttachments(1);
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
  fbo->ReleaseGraphicsResources(window);
  return out;
}

/** A frame: the GPU's view (frame context, textures) and the C twins' (arrays). */
struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkSmartPointer<vtkRenderer> Renderer;
  vtkSmartPointer<vtkMRGIPass> Pass;
  vtkOpenGLRenderWindow* GL = nullptr;
  vtkMRGIFrameContext Frame;
  int W = 0, H = 0;
  std::vector<float> Position, Normal, Albedo; // W x H x 4, rows bottom-up
  float PixelSize[2] = { 0.0f, 0.0f };
  std::vector<vtkSmartPointer<vtkTextureObject>> Owned;

  mrgi_gather_receivers View() const
  {
    return mrgi_gather_receivers{ W, H, Position.data(), Normal.data() };
  }

  /** A window-sized texture the scene releases; `rgba` W x H x 4 over the viewport (or null). */
  vtkTextureObject* Texture(const float* rgba)
  {
    const int tw = this->Frame.Viewport[0] + W, th = this->Frame.Viewport[1] + H;
    std::vector<float> full(static_cast<size_t>(tw) * static_cast<size_t>(th) * 4, 0.0f);
    if (rgba)
    {
      for (int y = 0; y < H; ++y)
      {
        std::memcpy(
          &full[(static_cast<size_t>(y + this->Frame.Viewport[1]) * static_cast<size_t>(tw) +
                  static_cast<size_t>(this->Frame.Viewport[0])) *
            4],
          rgba + static_cast<size_t>(y) * static_cast<size_t>(W) * 4,
          sizeof(float) * 4 * static_cast<size_t>(W));
      }
    }
    this->Owned.push_back(Upload(this->GL, tw, th, full.data()));
    return this->Owned.back();
  }

  ~Scene()
  {
    if (this->GL)
    {
      this->GL->MakeCurrent();
      for (auto& t : this->Owned)
      {
        t->ReleaseGraphicsResources(this->GL);
      }
    }
  }
};

/** A built-in scene rendered through vtkMRGIPass; the G-buffer read back. */
inline void RenderScene(Scene& s, const char* name, int width, int height, bool parallel)
{
  s.Window = mrgitest::HeadlessWindow(width, height);
  s.Renderer = vtkSmartPointer<vtkRenderer>::New();
  s.Window->AddRenderer(s.Renderer);
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene(name);
  MRGI_TEST_CHECK(builder->Build(s.Renderer));
  vtkCamera* camera = s.Renderer->GetActiveCamera();
  if (parallel)
  {
    camera->ParallelProjectionOn();
    s.Renderer->ResetCamera();
  }
  vtkNew<vtkRenderStepsPass> steps;
  s.Pass = vtkSmartPointer<vtkMRGIPass>::New();
  s.Pass->SetDelegatePass(steps);
  s.Pass->SetNumberOfVPLs(16);
  s.Renderer->SetPass(s.Pass);
  s.Window->Render();
  s.GL = vtkOpenGLRenderWindow::SafeDownCast(s.Window);
  vtkNew<vtkImageData> position, normal, albedo;
  MRGI_TEST_CHECK(s.Pass->GetGBuffer(s.Window, position, normal, albedo));
  const int* vp = s.Pass->GetViewport();
  s.W = vp[2];
  s.H = vp[3];
  const size_t n = static_cast<size_t>(s.W) * static_cast<size_t>(s.H) * 4;
  const float* P = static_cast<const float*>(position->GetScalarPointer());
  const float* N = static_cast<const float*>(normal->GetScalarPointer());
  const float* A = static_cast<const float*>(albedo->GetScalarPointer());
  s.Position.assign(P, P + n);
  s.Normal.assign(N, N + n);
  s.Albedo.assign(A, A + n);
  mrgi_multires_projection projection = { parallel ? 1 : 0, camera->GetViewAngle(),
    camera->GetParallelScale() };
  mrgi_error err;
  MRGI_TEST_CHECK(
    mrgi_multires_pixel_size_coefficients(&projection, s.H, s.PixelSize, &err) == MRGI_OK);
  s.Frame.Window = s.GL;
  s.Frame.Renderer = s.Renderer;
  s.Frame.Position = s.Pass->GetPositionTexture();
  s.Frame.Normal = s.Pass->GetNormalTexture();
  s.Frame.Albedo = s.Pass->GetAlbedoTexture();
  for (int i = 0; i < 4; ++i)
  {
    s.Frame.Viewport[i] = vp[i];
  }
  s.Frame.Parallel = parallel;
  s.Frame.PixelSize[0] = s.PixelSize[0];
  s.Frame.PixelSize[1] = s.PixelSize[1];
}

/**
 * A random G-buffer (smooth depth with steps, bent and non-unit normals,
 * holes, NaN and infinite texels) uploaded as textures, on a window that
 * only provides the context. The frame's viewport starts at (3, 2) to test
 * the offsets.
 */
inline void RandomScene(Scene& s, int width, int height, uint32_t seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  s.Window = mrgitest::HeadlessWindow(32, 32);
  s.Window->Render();
  s.GL = vtkOpenGLRenderWindow::SafeDownCast(s.Window);
  s.W = width;
  s.H = height;
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  s.Position.assign(4 * n, 0.0f);
  s.Normal.assign(4 * n, 0.0f);
  s.Albedo.assign(4 * n, 0.0f);
  const float hole = 0.1f * unit(rng);
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const size_t p = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
      const float d = 5.0f + 0.02f * static_cast<float>(x) + 0.01f * static_cast<float>(y) +
        (unit(rng) < 0.03f ? 2.0f * unit(rng) : 0.0f);
      s.Position[4 * p + 0] = 0.01f * static_cast<float>(x);
      s.Position[4 * p + 1] = 0.01f * static_cast<float>(y);
      s.Position[4 * p + 2] = -d;
      s.Position[4 * p + 3] = unit(rng) < hole ? 0.0f : 1.0f;
      const bool bent = unit(rng) < 0.04f;
      s.Normal[4 * p + 0] = bent ? unit(rng) - 0.5f : 0.0f;
      s.Normal[4 * p + 1] = bent ? unit(rng) - 0.5f : 0.0f;
      s.Normal[4 * p + 2] = 0.5f + 2.0f * unit(rng);
      for (int c = 0; c < 3; ++c)
      {
        s.Albedo[4 * p + static_cast<size_t>(c)] = unit(rng);
      }
      const float r = unit(rng);
      if (r < 0.005f)
      {
        s.Position[4 * p + 2] = std::nanf("");
      }
      else if (r < 0.01f)
      {
        s.Normal[4 * p + 1] = INFINITY;
      }
    }
  }
  s.Frame.Window = s.GL;
  s.Frame.Viewport[0] = 3;
  s.Frame.Viewport[1] = 2;
  s.Frame.Viewport[2] = width;
  s.Frame.Viewport[3] = height;
  s.Frame.Position = s.Texture(s.Position.data());
  s.Frame.Normal = s.Texture(s.Normal.data());
  s.Frame.Albedo = s.Texture(s.Albedo.data());
  s.PixelSize[0] = 0.001f + 0.01f * unit(rng);
  s.PixelSize[1] = 0.0f;
  s.Frame.PixelSize[0] = s.PixelSize[0];
  s.Frame.PixelSize[1] = s.PixelSize[1];
}

/** The GPU's masks read back as the C twin's struct (edge, nonempty, mask, required, stencil). */
struct GPUMasks
{
  mrgi_bmr_masks Masks{};
  std::vector<std::vector<uint8_t>> StencilBytes; // read from the depth-stencil textures
  ~GPUMasks() { mrgi_bmr_masks_destroy(&this->Masks); }
};

inline void ReadMasks(vtkRenderWindow* window, vtkMRGIBMRLevels* levels, GPUMasks& out)
{
  mrgi_bmr_masks& m = out.Masks;
  mrgi_bmr_masks_destroy(&m);
  m.width = levels->GetWidth();
  m.height = levels->GetHeight();
  out.StencilBytes.assign(MRGI_BMR_LEVELS, {});
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    int size[2];
    MRGI_TEST_CHECK(levels->GetLevelSize(k, size));
    m.level_width[k] = size[0];
    m.level_height[k] = size[1];
    const size_t n = static_cast<size_t>(size[0]) * static_cast<size_t>(size[1]);
    m.edge[k] = static_cast<uint8_t*>(std::calloc(n, 1));
    m.nonempty[k] = static_cast<uint8_t*>(std::calloc(n, 1));
    m.required[k] = static_cast<uint8_t*>(std::calloc(n, 1));
    m.stencil[k] = static_cast<uint8_t*>(std::calloc(n, 1));
    m.mask[k] = static_cast<float*>(std::calloc(n, sizeof(float)));
    MRGI_TEST_CHECK(m.edge[k] && m.nonempty[k] && m.required[k] && m.stencil[k] && m.mask[k]);
    vtkNew<vtkFloatArray> rgba;
    vtkNew<vtkUnsignedCharArray> stencil;
    MRGI_TEST_CHECK(levels->ReadMask(window, k, rgba));
    MRGI_TEST_CHECK(levels->ReadStencil(window, k, stencil));
    MRGI_TEST_CHECK(static_cast<size_t>(rgba->GetNumberOfTuples()) == n);
    out.StencilBytes[static_cast<size_t>(k)].assign(
      stencil->GetPointer(0), stencil->GetPointer(0) + n);
    for (size_t t = 0; t < n; ++t)
    {
      const float* v = rgba->GetPointer(0) + 4 * t;
      m.mask[k][t] = v[0];
      m.edge[k][t] = v[1] > 0.5f ? 1 : 0;
      const int bits = static_cast<int>(v[2]);
      m.required[k][t] = (bits & 1) ? 1 : 0;
      m.stencil[k][t] = (bits & 2) ? 1 : 0;
      m.nonempty[k][t] = v[3] > 0.5f ? 1 : 0;
    }
  }
}

/**
 * The test effect: at level k texel t, a smooth function of the G-buffer at
 * the footprint's centre pixel min(t 2^k + 2^(k-1), size - 1) (level 0: t):
 * (albedo r, 0.5 + 0.5 sin(8 x / |z|) (smooth across the image), 0.5 + 0.5
 * clamp(normal z, -1, 1), 1) with the eye-space position (x, y, z); 0 at an invalid
 * centre. Rendered per level under the stencil with vtkMRGIBMRLevels::LevelStep;
 * alpha 1 marks the texels it rendered (the rest stay 0).
 */
class TestEffect
{
public:
  /** `samples` > 0 adds a loop of that many G-buffer fetches (a stand-in for an expensive effect).
   */
  explicit TestEffect(vtkOpenGLRenderWindow* window, int samples = 0)
    : Window(window)
  {
    const std::string fs = "//VTK::System::Dec\n"
                           "#define SAMPLES " +
      std::to_string(samples) +
      "\n"
      "in vec2 texCoord;\n"
      "uniform sampler2D gPosition;\n"
      "uniform sampler2D gAlbedo;\n"
      "uniform sampler2D gNormal;\n"
      "uniform ivec2 offset;\n"
      "uniform ivec2 frameSize;\n"
      "uniform int level;\n"
      "//VTK::Output::Dec\n"
      "void main()\n"
      "{\n"
      "  if (texCoord.x < -1.0) { discard; }\n"
      "  ivec2 t = ivec2(gl_FragCoord.xy);\n"
      "  int s = 1 << level;\n"
      "  ivec2 c = level == 0 ? t : min(t * s + s / 2, frameSize - 1);\n"
      "  vec4 P = texelFetch(gPosition, c + offset, 0);\n"
      "  vec3 A = texelFetch(gAlbedo, c + offset, 0).rgb;\n"
      "  vec3 N = texelFetch(gNormal, c + offset, 0).xyz;\n"
      "  bool valid = P.w > 0.5 && !isnan(P.z) && !isinf(P.z) && !any(isnan(N)) && "
      "!any(isinf(N));\n"
      "  float cost = 0.0;\n"
      "  for (int i = 0; i < SAMPLES; ++i)\n"
      "  {\n"
      "    ivec2 o = ivec2((i * 7) % 15 - 7, (i * 11) % 15 - 7);\n"
      "    cost += texelFetch(gPosition, clamp(c + o, ivec2(0), frameSize - 1) + offset, 0).w;\n"
      "  }\n"
      "  gl_FragData[0] = vec4(0.0, 1e-30 * cost, 0.0, 0.0) + (valid ? vec4(A.r, 0.5 + 0.5 * "
      "sin(8.0 * P.x / max(abs(P.z), 1e-30)), 0.5 + 0.5 * clamp(N.z, -1.0, 1.0), 1.0) : vec4(0.0, "
      "0.0, 0.0, 1.0));\n"
      "}\n";
    this->Quad = new vtkOpenGLQuadHelper(
      window, vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), fs.c_str(), "");
    MRGI_TEST_CHECK(this->Quad->Program && this->Quad->Program->GetCompiled());
  }
  ~TestEffect()
  {
    this->Window->MakeCurrent();
    delete this->Quad;
  }
  /** Every level, or only level `only` (>= 0). */
  void Render(const vtkMRGIFrameContext& frame, vtkMRGIBMRLevels* levels, int only = -1)
  {
    for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
    {
      if (only >= 0 && k != only)
      {
        continue;
      }
      vtkMRGIBMRLevels::LevelStep step(this->Window, levels, k);
      MRGI_TEST_CHECK(step.IsValid());
      vtkShaderProgram* p = this->Quad->Program;
      this->Window->GetShaderCache()->ReadyShaderProgram(p);
      frame.Position->Activate();
      frame.Albedo->Activate();
      frame.Normal->Activate();
      p->SetUniformi("gPosition", frame.Position->GetTextureUnit());
      p->SetUniformi("gAlbedo", frame.Albedo->GetTextureUnit());
      p->SetUniformi("gNormal", frame.Normal->GetTextureUnit());
      const int offset[2] = { frame.Viewport[0], frame.Viewport[1] };
      const int size[2] = { frame.Viewport[2], frame.Viewport[3] };
      p->SetUniform2i("offset", offset);
      p->SetUniform2i("frameSize", size);
      p->SetUniformi("level", k);
      this->Quad->Render();
      frame.Position->Deactivate();
      frame.Albedo->Deactivate();
      frame.Normal->Deactivate();
    }
  }

private:
  vtkOpenGLRenderWindow* Window;
  vtkOpenGLQuadHelper* Quad = nullptr;
};

/** RGB difference of two same-sized RGBA images: `a` the reference, `b` the one tested. */
struct ImageDifference
{
  double RMS = 0.0;      ///< over the RGB channels
  double MaxError = 0.0; ///< largest |b - a|
  double MaxValue = 0.0; ///< largest channel of `a`
  size_t Bad = 0;        ///< non-finite channels of `b`
};

inline ImageDifference CompareRGB(const std::vector<float>& a, const std::vector<float>& b)
{
  ImageDifference d;
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
  {
    if (i % 4 == 3)
    {
      continue;
    }
    d.Bad += !std::isfinite(b[i]);
    d.MaxValue = std::max(d.MaxValue, static_cast<double>(a[i]));
    const double e = static_cast<double>(b[i]) - a[i];
    d.MaxError = std::max(d.MaxError, std::fabs(e));
    sum += e * e;
    ++n;
  }
  d.RMS = n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
  return d;
}

/**
 * The pass's colour buffer after one render at each of `resolutions`
 * (`setResolution` switches the effect's resolution before each render).
 */
template <typename SetResolution>
std::vector<std::vector<float>> RenderResolutions(
  Scene& s, std::initializer_list<int> resolutions, SetResolution setResolution)
{
  std::vector<std::vector<float>> images;
  for (int r : resolutions)
  {
    setResolution(r);
    s.Window->Render();
    vtkNew<vtkImageData> colour;
    if (!s.Pass->GetColorBuffer(s.Window, colour))
    {
      return {};
    }
    const float* c = static_cast<const float*>(colour->GetScalarPointer());
    images.emplace_back(c, c + 4 * static_cast<size_t>(s.W) * static_cast<size_t>(s.H));
  }
  return images;
}

/**
 * The Benchmark cases' switch: true with MRGI_BMR_BENCHMARK=1, else false
 * after printing how to run it (the case then passes without timing).
 */
inline bool BenchmarkEnabled()
{
  const char* enabled = std::getenv("MRGI_BMR_BENCHMARK");
  if (!enabled || std::string(enabled) != "1")
  {
    std::printf("Benchmark: set MRGI_BMR_BENCHMARK=1 to run it\n");
    return false;
  }
  return true;
}

/** Timed A B pairs per row: MRGI_BMR_REPEATS, at least 1 (default 3). */
inline int BenchmarkRepeats()
{
  const char* repeats = std::getenv("MRGI_BMR_REPEATS");
  return std::max(1, std::atoi(repeats ? repeats : "3"));
}

/** A comma-separated list of integers from environment variable `name`, or `fallback`. */
inline std::vector<int> EnvInts(const char* name, const char* fallback)
{
  const char* text = std::getenv(name);
  std::vector<int> values;
  for (std::string k = text ? text : fallback; !k.empty();)
  {
    const size_t comma = k.find(',');
    values.push_back(std::atoi(k.substr(0, comma).c_str()));
    k = comma == std::string::npos ? "" : k.substr(comma + 1);
  }
  return values;
}

/** The median (upper for an even count) of `v`; 0 when empty. */
inline double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

/** |a - b| <= 1e-4 |b| (+ a floor for values near 0). */
inline bool Near(double a, double b, double floor = 1e-6)
{
  return std::fabs(a - b) <= 1e-4 * std::fabs(b) + floor;
}
}

#endif
