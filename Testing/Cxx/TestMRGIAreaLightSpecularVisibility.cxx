// Shadowed area-light highlights (nichols-penmatsa-wyman-2010 3.3.1-3.3.3)
// on the GPU against their C twins, on random inputs:
//
// 1. The shadowed specular sum (vtkMRGIAreaLightSpecular.glsl with
//    MRGI_AREA_SPECULAR_VISIBILITY) against mrgi_area_light_specular_visible():
//    random receivers around random lights (as TestMRGIAreaLightSpecular,
//    whose harness this follows: one fragment per receiver), each with a
//    random sample mask (all, none, or random bits) and 24 random query
//    visibilities, read by the shader's visibility functions from textures.
//    S agrees to relative 1e-4 (absolute floor 1e-7 of the case's peak) and
//    the path exactly, for all but 0.5% of the receivers (the unshadowed
//    test's rounding boundaries: a lobe value at the cutoff, the peak at the
//    discard threshold). A twin without visibility and one reading the
//    queries transposed (cell (a, b) <- query (b, a)) must fail.
// 2. The variance shadow query's resolve (vtkMRGIVarianceShadowResolve.glsl,
//    mrgiVsmResolve()) against mrgi_voxel_vsm_resolve() on random moments in
//    the interleaved texture layout, pixels that computed nothing included,
//    radius 0..3: every visibility within 2e-6 (float sums in the same
//    order); a twin with the radius one larger must fail.
// 3. Through vtkMRGIPass on random box scenes (glossy floor and boxes, a
//    light above), with naive and incremental visibility:
//    - the moments pass (vtkMRGIVarianceShadowQuery::ReadMoments()) against
//      mrgi_voxel_vsm_specular_moments() on the read-back voxels and
//      G-buffer: which pixels compute, and every query's (z, z^2) within
//      1e-4, for all but 0.5% of the queries (a march's step or slice
//      boundary within float rounding: mrgi_voxel_march.h "Precision"); a
//      twin computing the wrong interleaving phase must fail;
//    - the highlight the pass adds (area buffer with AreaLightSpecular on
//      minus off) against k_s c_s mrgi_area_light_specular_visible() with
//      the sample bits of the C march (naive) or of the pyramid's level-0
//      masks read back (incremental; refine fraction 1, the most reuse, so
//      that on some pixels these light otherwise than the naive bits and
//      the comparison tells masks from marches), and the query visibilities of
//      mrgi_voxel_vsm_resolve() on the GPU's moments: under 0.5% of the
//      highlighted pixels differ beyond relative 1e-4; the twin without
//      visibility must differ on the shadowed ones.
#include "mrgiTestUtilities.h"
#include "mrgiVoxelTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIVarianceShadowQuery.h"
#include "vtkMRGIVisibilityPyramid.h"
#include "vtkMRGIVoxelization.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPixelBufferObject.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkTypeUInt32Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtk_glew.h"

#include "mrgi_area_light.h"
#include "mrgi_glsl_defines.h"
#include "mrgi_variance_shadow.h"
#include "mrgi_visibility_pyramid.h"
#include "mrgi_voxel_march.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace
{
const double Relative = 1e-4;
const double MaxRate = 0.005;

std::string CoreDefines()
{
  std::vector<char> buffer(mrgi_glsl_defines_size());
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_glsl_defines(buffer.data(), buffer.size(), nullptr, &err) == MRGI_OK);
  return std::string(buffer.data());
}

vtkSmartPointer<vtkTextureObject> MakeTexture(vtkOpenGLRenderWindow* window, bool uint)
{
  auto t = vtkSmartPointer<vtkTextureObject>::New();
  t->SetContext(window);
  t->SetInternalFormat(uint ? GL_RGBA32UI : GL_RGBA32F);
  t->SetFormat(uint ? GL_RGBA_INTEGER : GL_RGBA);
  t->SetDataType(uint ? GL_UNSIGNED_INT : GL_FLOAT);
  t->SetMinificationFilter(vtkTextureObject::Nearest);
  t->SetMagnificationFilter(vtkTextureObject::Nearest);
  return t;
}

// One full-screen draw of `fs` over w x h into `targets` RGBA32F targets,
// read back (4 floats per pixel each); `setup` binds inputs and uniforms.
void RunQuad(vtkOpenGLRenderWindow* window, vtkOpenGLQuadHelper* quad, int w, int h, int targets,
  const std::function<void(vtkShaderProgram*)>& setup, std::vector<std::vector<float>>& out)
{
  window->MakeCurrent();
  window->GetShaderCache()->ReadyShaderProgram(quad->Program);
  vtkShaderProgram* program = quad->Program;
  setup(program);
  std::vector<vtkSmartPointer<vtkTextureObject>> outputs;
  vtkNew<vtkOpenGLFramebufferObject> fbo;
  fbo->SetContext(window);
  vtkOpenGLState* ostate = window->GetState();
  out.assign(static_cast<size_t>(targets), std::vector<float>());
  {
    vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
    vtkOpenGLState::ScopedglEnableDisable depth(ostate, GL_DEPTH_TEST);
    vtkOpenGLState::ScopedglViewport viewport(ostate);
    ostate->vtkglDisable(GL_BLEND);
    ostate->vtkglDisable(GL_DEPTH_TEST);
    fbo->SaveCurrentBindingsAndBuffers();
    fbo->Bind();
    for (int k = 0; k < targets; ++k)
    {
      outputs.push_back(MakeTexture(window, false));
      MRGI_TEST_CHECK(outputs.back()->Allocate2D(w, h, 4, VTK_FLOAT));
      fbo->AddColorAttachment(static_cast<unsigned int>(k), outputs.back());
    }
    fbo->ActivateDrawBuffers(static_cast<unsigned int>(targets));
    const char* status = nullptr;
    MRGI_TEST_CHECK(vtkOpenGLFramebufferObject::GetFrameBufferStatus(GL_FRAMEBUFFER, status));
    ostate->vtkglViewport(0, 0, w, h);
    quad->Render();
    for (int k = 0; k < targets; ++k)
    {
      // Read back through VTK (a pixel buffer object): no GL entry points.
      fbo->ActivateReadBuffer(static_cast<unsigned int>(k));
      int extent[4] = { 0, w - 1, 0, h - 1 };
      vtkPixelBufferObject* pbo = fbo->DownloadColor4(extent, VTK_FLOAT);
      MRGI_TEST_CHECK(pbo);
      const float* mapped = static_cast<const float*>(pbo->MapPackedBuffer());
      MRGI_TEST_CHECK(mapped);
      out[static_cast<size_t>(k)].assign(mapped, mapped + 4 * static_cast<size_t>(w) * h);
      pbo->UnmapPackedBuffer();
      pbo->Delete();
    }
    fbo->RemoveColorAttachments(static_cast<unsigned int>(targets));
    fbo->UnBind();
    fbo->RestorePreviousBindingsAndBuffers();
  }
  for (auto& t : outputs)
  {
    t->ReleaseGraphicsResources(window);
  }
  fbo->ReleaseGraphicsResources(window);
}

vtkOpenGLQuadHelper* MakeQuad(vtkOpenGLRenderWindow* window, const std::string& body)
{
  window->MakeCurrent();
  const std::string fs = "//VTK::System::Dec\n" + CoreDefines() + body;
  auto* quad = new vtkOpenGLQuadHelper(
    window, vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), fs.c_str(), "");
  MRGI_TEST_CHECK(quad->Program && quad->Program->GetCompiled());
  return quad;
}

double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void Normalize(double v[3])
{
  const double l = std::sqrt(Dot(v, v));
  for (int k = 0; k < 3; ++k)
  {
    v[k] /= l;
  }
}

struct Random
{
  explicit Random(unsigned seed)
    : Rng(seed)
  {
  }
  double Uniform(double lo, double hi)
  {
    return lo + (hi - lo) * (static_cast<double>(this->Rng() >> 5) / 134217728.0);
  }
  void Direction(double v[3])
  {
    do
    {
      for (int k = 0; k < 3; ++k)
      {
        v[k] = this->Uniform(-1, 1);
      }
    } while (Dot(v, v) > 1 || Dot(v, v) < 1e-4);
    Normalize(v);
  }
  std::mt19937 Rng;
};

// ===========================================================================
// 1. The shadowed specular sum on random receivers.
const int GridW = 128, GridH = 96, Count = GridW * GridH;
const int MaskWords = 8; // up to 256 samples
const int QueryTexels = MRGI_VOXEL_VSM_QUERIES / 4;

const char* const SumBody = R"(
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; receivers are addressed by gl_FragCoord
uniform sampler2D mrgiReceivers; // 3 texels per receiver: (P, N.x) (N.yz, V.xy) (V.z, power, 0, 0)
uniform usampler2D mrgiMasks;    // 2 texels per receiver: 8 mask words
uniform sampler2D mrgiQueryVisibility; // 6 texels per receiver: 24 query visibilities
uvec4 testMasks[2];
float testQueries[MRGI_VOXEL_VSM_QUERIES];
bool mrgiAreaSpecularSampleVisible(int j, vec3 samplePosition, vec3 sampleNormal)
{
  return ((testMasks[j >> 7][(j >> 5) & 3] >> uint(j & 31)) & 1u) != 0u;
}
float mrgiAreaSpecularQueryVisibility(int query)
{
  return testQueries[query];
}
//VTK::Output::Dec
void main()
{
  if (texCoord.x < -1.0) { discard; } // never true: keeps texCoord alive
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 t0 = texelFetch(mrgiReceivers, ivec2(3 * p.x, p.y), 0);
  vec4 t1 = texelFetch(mrgiReceivers, ivec2(3 * p.x + 1, p.y), 0);
  vec4 t2 = texelFetch(mrgiReceivers, ivec2(3 * p.x + 2, p.y), 0);
  testMasks[0] = texelFetch(mrgiMasks, ivec2(2 * p.x, p.y), 0);
  testMasks[1] = texelFetch(mrgiMasks, ivec2(2 * p.x + 1, p.y), 0);
  for (int k = 0; k < MRGI_VOXEL_VSM_QUERIES / 4; ++k)
  {
    vec4 q = texelFetch(mrgiQueryVisibility, ivec2(MRGI_VOXEL_VSM_QUERIES / 4 * p.x + k, p.y), 0);
    testQueries[4 * k] = q.x;
    testQueries[4 * k + 1] = q.y;
    testQueries[4 * k + 2] = q.z;
    testQueries[4 * k + 3] = q.w;
  }
  int path;
  int inLobe;
  int cells;
  mrgiAreaLightLobe lobe;
  vec3 S = mrgiAreaLightSpecularInfo(t0.xyz, vec3(t0.w, t1.xy), vec3(t1.zw, t2.x), t2.y, path,
    inLobe, cells, lobe);
  gl_FragData[0] = vec4(S, float(path));
  gl_FragData[1] = vec4(float(inLobe), float(cells), 0.0, 0.0);
}
)";

struct LightCase
{
  const char* Name;
  int TextureW, TextureH; // 0: untextured
  bool TwoSided;
  int Samples;
  bool Jitter;
  unsigned Seed;
};

struct Receiver
{
  float P[3], N[3], V[3], Power, Pad[2];
};
static_assert(sizeof(Receiver) == 12 * sizeof(float), "3 RGBA texels per receiver");

struct SumTotals
{
  size_t Receivers = 0, Differ = 0, PathFlips = 0, Lit = 0, WrongNone = 0, GridLit = 0,
         WrongTransposed = 0, Paths[5] = { 0, 0, 0, 0, 0 };
  double MaxError = 0;
} sumTotals;

void SumCase(const LightCase& c, vtkOpenGLRenderWindow* window, vtkOpenGLQuadHelper* quad)
{
  Random g(c.Seed);
  vtkNew<vtkMRGIAreaLight> light;
  double u[3], d[3], v[3];
  g.Direction(u);
  g.Direction(d);
  v[0] = u[1] * d[2] - u[2] * d[1];
  v[1] = u[2] * d[0] - u[0] * d[2];
  v[2] = u[0] * d[1] - u[1] * d[0];
  Normalize(v);
  const double lu = g.Uniform(0.5, 2.0), lv = g.Uniform(0.5, 2.0);
  double C[3], U[3], V[3], n[3];
  for (int k = 0; k < 3; ++k)
  {
    C[k] = g.Uniform(-2, 2);
    U[k] = lu * u[k];
    V[k] = lv * v[k];
  }
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
  light->SetCenter(C);
  light->SetEdgeU(U);
  light->SetEdgeV(V);
  light->SetColor(g.Uniform(0.3, 1.5), g.Uniform(0.3, 1.5), g.Uniform(0.3, 1.5));
  light->SetIntensity(g.Uniform(0.5, 4));
  light->SetTwoSided(c.TwoSided);
  light->SetNumberOfSamples(c.Samples);
  light->SetJitter(c.Jitter);
  light->SetSeed(c.Seed);
  if (c.TextureW > 0)
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(c.TextureW, c.TextureH, 1);
    image->AllocateScalars(VTK_FLOAT, 3);
    auto* s = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
    for (vtkIdType i = 0; i < s->GetNumberOfValues(); ++i)
    {
      s->SetValue(i, static_cast<float>(g.Uniform(0, 2)));
    }
    light->SetTextureData(image);
  }
  mrgi_area_light_uniforms uniforms;
  MRGI_TEST_CHECK(light->GetCoreUniforms(&uniforms));
  const mrgi_area_light_texture_pyramid* pyramid = nullptr;
  MRGI_TEST_CHECK(light->GetCorePyramid(&pyramid));
  int count = 0;
  const mrgi_area_light_sample* samples = light->GetCoreSamples(&count);
  MRGI_TEST_CHECK(samples && count > 0 && count <= 32 * MaskWords);

  // Receivers: lobes aimed at the light (most), anywhere, surfaces below it.
  std::vector<Receiver> receivers(Count);
  std::vector<uint32_t> masks(static_cast<size_t>(Count) * MaskWords);
  std::vector<float> queries(static_cast<size_t>(Count) * MRGI_VOXEL_VSM_QUERIES);
  for (int i = 0; i < Count; ++i)
  {
    Receiver& r = receivers[static_cast<size_t>(i)];
    std::memset(&r, 0, sizeof(r));
    double P[3], N[3], Vd[3];
    const double side = (c.TwoSided && g.Uniform(0, 1) < 0.4) ? -1.0 : 1.0;
    const double kind = g.Uniform(0, 1);
    const double h = std::max(lu, lv) * std::pow(10.0, g.Uniform(-1.2, 0.8)) * side;
    for (int k = 0; k < 3; ++k)
    {
      P[k] = C[k] + g.Uniform(-1.5, 1.5) * U[k] + g.Uniform(-1.5, 1.5) * V[k] + h * n[k];
    }
    if (kind < 0.7)
    {
      // The mirror direction: N around w (the direction to a point of the
      // light), V = reflect(-w, N) so that R = w.
      double target[3], w[3];
      for (int k = 0; k < 3; ++k)
      {
        target[k] = C[k] + g.Uniform(-0.6, 0.6) * U[k] + g.Uniform(-0.6, 0.6) * V[k];
        w[k] = target[k] - P[k];
      }
      Normalize(w);
      do
      {
        g.Direction(N);
      } while (Dot(N, w) < 0.05);
      const double nw = Dot(N, w);
      for (int k = 0; k < 3; ++k)
      {
        Vd[k] = 2 * nw * N[k] - w[k];
      }
    }
    else if (kind < 0.85)
    {
      g.Direction(N);
      g.Direction(Vd);
    }
    else
    {
      double toLight[3] = { C[0] - P[0], C[1] - P[1], C[2] - P[2] };
      Normalize(toLight);
      do
      {
        g.Direction(N);
      } while (Dot(N, toLight) < 0.1);
      do
      {
        g.Direction(Vd);
      } while (Dot(Vd, N) < 0.0);
    }
    for (int k = 0; k < 3; ++k)
    {
      r.P[k] = static_cast<float>(P[k]);
      r.N[k] = static_cast<float>(N[k]);
      r.V[k] = static_cast<float>(Vd[k]);
    }
    const double pick = g.Uniform(0, 1);
    r.Power = pick < 0.3 ? (pick < 0.1 ? 10.0f : (pick < 0.2 ? 50.0f : 128.0f))
                         : static_cast<float>(g.Uniform(1, 128));
    // Visibility: all, none, or random bits at a random density; queries
    // in [0, 1] with exact 0s and 1s.
    const double maskKind = g.Uniform(0, 1);
    const double density = g.Uniform(0.1, 0.9);
    for (int w = 0; w < MaskWords; ++w)
    {
      uint32_t word = 0;
      for (int b = 0; b < 32; ++b)
      {
        const bool bit = maskKind < 0.1 ? true : (maskKind < 0.2 ? false : g.Uniform(0, 1) < density);
        word |= (bit && 32 * w + b < count) ? (1u << b) : 0u;
      }
      masks[static_cast<size_t>(i) * MaskWords + static_cast<size_t>(w)] = word;
    }
    for (int j = 0; j < MRGI_VOXEL_VSM_QUERIES; ++j)
    {
      const double q = g.Uniform(-0.3, 1.3);
      queries[static_cast<size_t>(i) * MRGI_VOXEL_VSM_QUERIES + static_cast<size_t>(j)] =
        static_cast<float>(std::min(std::max(q, 0.0), 1.0));
    }
  }

  vtkSmartPointer<vtkTextureObject> tReceivers = MakeTexture(window, false);
  vtkSmartPointer<vtkTextureObject> tMasks = MakeTexture(window, true);
  vtkSmartPointer<vtkTextureObject> tQueries = MakeTexture(window, false);
  MRGI_TEST_CHECK(tReceivers->Create2DFromRaw(3 * GridW, GridH, 4, VTK_FLOAT, receivers.data()));
  MRGI_TEST_CHECK(tMasks->Create2DFromRaw(2 * GridW, GridH, 4, VTK_UNSIGNED_INT, masks.data()));
  MRGI_TEST_CHECK(tQueries->Create2DFromRaw(QueryTexels * GridW, GridH, 4, VTK_FLOAT, queries.data()));
  std::vector<std::vector<float>> out;
  RunQuad(window, quad, GridW, GridH, 2,
    [&](vtkShaderProgram* program) {
      MRGI_TEST_CHECK(light->SetShaderUniforms(program, window));
      tReceivers->Activate();
      tMasks->Activate();
      tQueries->Activate();
      program->SetUniformi("mrgiReceivers", tReceivers->GetTextureUnit());
      program->SetUniformi("mrgiMasks", tMasks->GetTextureUnit());
      program->SetUniformi("mrgiQueryVisibility", tQueries->GetTextureUnit());
    },
    out);
  tReceivers->Deactivate();
  tMasks->Deactivate();
  tQueries->Deactivate();
  light->DeactivateTextures();

  // The twins.
  auto twin = [&](int i, const uint32_t* mask, const float* q, float S[3], mrgi_area_light_specular_info* info) {
    const Receiver& r = receivers[static_cast<size_t>(i)];
    mrgi_area_light_specular_visible(&uniforms, samples, count, pyramid, r.P, r.N, r.V, r.Power,
      mask, q, S, info);
  };
  std::vector<float> twinS(static_cast<size_t>(Count) * 3);
  std::vector<int> twinPath(static_cast<size_t>(Count));
  double peak = 0;
  for (int i = 0; i < Count; ++i)
  {
    mrgi_area_light_specular_info info;
    twin(i, &masks[static_cast<size_t>(i) * MaskWords], &queries[static_cast<size_t>(i) * MRGI_VOXEL_VSM_QUERIES],
      &twinS[3 * static_cast<size_t>(i)], &info);
    twinPath[static_cast<size_t>(i)] = info.path;
    for (int k = 0; k < 3; ++k)
    {
      peak = std::max(peak, static_cast<double>(twinS[3 * static_cast<size_t>(i) + static_cast<size_t>(k)]));
    }
  }
  const double floor = 1e-7 * peak;
  auto close = [&](const float* gpu, const float* S) {
    for (int k = 0; k < 3; ++k)
    {
      if (!(std::fabs(static_cast<double>(gpu[k]) - S[k]) <= Relative * std::fabs(S[k]) + floor))
      {
        return false;
      }
    }
    return true;
  };
  size_t differ = 0, flips = 0, lit = 0, wrongNone = 0, gridLit = 0, wrongTransposed = 0;
  size_t paths[5] = { 0, 0, 0, 0, 0 };
  double maxError = 0;
  for (int i = 0; i < Count; ++i)
  {
    const float* gpu = &out[0][4 * static_cast<size_t>(i)];
    const float* S = &twinS[3 * static_cast<size_t>(i)];
    const int path = twinPath[static_cast<size_t>(i)];
    const int gpuPath = static_cast<int>(std::lround(gpu[3]));
    ++paths[path];
    flips += gpuPath != path;
    const bool agrees = gpuPath == path && close(gpu, S);
    differ += !agrees;
    if (agrees)
    {
      for (int k = 0; k < 3; ++k)
      {
        if (S[k] > 1e-3 * peak)
        {
          maxError = std::max(maxError, std::fabs(static_cast<double>(gpu[k]) - S[k]) / S[k]);
        }
      }
    }
    else if (differ <= 3)
    {
      std::printf("    differs #%d: n %.6g twin path %d S (%.7g %.7g %.7g) GPU path %d S (%.7g %.7g %.7g)\n",
        i, static_cast<double>(receivers[static_cast<size_t>(i)].Power), path, S[0], S[1], S[2],
        gpuPath, gpu[0], gpu[1], gpu[2]);
    }
    // Wrong twins, on lit receivers.
    if (!(S[0] + S[1] + S[2] > 1e-3 * peak))
    {
      continue;
    }
    ++lit;
    float wrong[3];
    twin(i, nullptr, nullptr, wrong, nullptr);
    wrongNone += !close(gpu, wrong);
    if (path == MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID)
    {
      ++gridLit;
      float transposed[MRGI_VOXEL_VSM_QUERIES];
      for (int j = 0; j < MRGI_VOXEL_VSM_QUERIES; ++j)
      {
        const int a = j % MRGI_AREA_LIGHT_LOBE_GRID, b = j / MRGI_AREA_LIGHT_LOBE_GRID;
        transposed[j] = queries[static_cast<size_t>(i) * MRGI_VOXEL_VSM_QUERIES +
          static_cast<size_t>(a * MRGI_AREA_LIGHT_LOBE_GRID + b)];
      }
      twin(i, &masks[static_cast<size_t>(i) * MaskWords], transposed, wrong, nullptr);
      wrongTransposed += !close(gpu, wrong);
    }
  }
  std::printf("%-36s %3d samples | paths: samples %.1f%% grid %.1f%% early-outs %.1f%% | differ %zu "
              "(%zu path flips) = %.3f%%; max rel. error %.2g | lit %zu: no-visibility twin differs "
              "on %zu, transposed queries on %zu of %zu lobe-grid\n",
    c.Name, count, 100.0 * paths[0] / Count, 100.0 * paths[1] / Count,
    100.0 * (Count - paths[0] - paths[1]) / Count, differ, flips, 100.0 * differ / Count, maxError,
    lit, wrongNone, wrongTransposed, gridLit);
  std::fflush(stdout);
  MRGI_TEST_CHECK(paths[MRGI_AREA_LIGHT_SPECULAR_SAMPLES] > Count / 50 || c.Samples < 9);
  MRGI_TEST_CHECK(paths[MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID] > Count / 50);
  MRGI_TEST_CHECK(differ < MaxRate * Count);
  sumTotals.Receivers += Count;
  sumTotals.Differ += differ;
  sumTotals.PathFlips += flips;
  sumTotals.Lit += lit;
  sumTotals.WrongNone += wrongNone;
  sumTotals.GridLit += gridLit;
  sumTotals.WrongTransposed += wrongTransposed;
  sumTotals.MaxError = std::max(sumTotals.MaxError, maxError);
  for (int p = 0; p < 5; ++p)
  {
    sumTotals.Paths[p] += paths[p];
  }
  tReceivers->ReleaseGraphicsResources(window);
  tMasks->ReleaseGraphicsResources(window);
  tQueries->ReleaseGraphicsResources(window);
  light->ReleaseGraphicsResources(window);
}

// ===========================================================================
// 2. The resolve on random moments.
const char* const ResolveBody = R"(
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; pixels are addressed by gl_FragCoord
//VTK::Output::Dec
void main()
{
  if (texCoord.x < -1.0) { discard; } // never true: keeps texCoord alive
  float visibility[MRGI_VOXEL_VSM_QUERIES];
  mrgiVsmResolve(ivec2(gl_FragCoord.xy), visibility);
  gl_FragData[0] = vec4(visibility[0], visibility[1], visibility[2], visibility[3]);
  gl_FragData[1] = vec4(visibility[4], visibility[5], visibility[6], visibility[7]);
  gl_FragData[2] = vec4(visibility[8], visibility[9], visibility[10], visibility[11]);
  gl_FragData[3] = vec4(visibility[12], visibility[13], visibility[14], visibility[15]);
  gl_FragData[4] = vec4(visibility[16], visibility[17], visibility[18], visibility[19]);
  gl_FragData[5] = vec4(visibility[20], visibility[21], visibility[22], visibility[23]);
}
)";

void ResolveCase(vtkOpenGLRenderWindow* window, vtkOpenGLQuadHelper* quad, int w, int h,
  int radius, float minVariance, unsigned seed)
{
  Random g(seed);
  const size_t pixels = static_cast<size_t>(w) * static_cast<size_t>(h);
  const int Q = MRGI_VOXEL_VSM_QUERIES;
  std::vector<float> moments(pixels * 2 * Q, 0.0f);
  std::vector<uint8_t> phases(pixels, 0);
  std::vector<std::vector<float>> textures(MRGI_VOXEL_VSM_TARGETS, std::vector<float>(pixels * 4, -1.0f));
  // Shadow-like moments: blobs of occluders at a random depth per blob.
  for (size_t p = 0; p < pixels; ++p)
  {
    const int x = static_cast<int>(p % static_cast<size_t>(w)), y = static_cast<int>(p / static_cast<size_t>(w));
    if (g.Uniform(0, 1) < 0.2)
    {
      continue; // computed nothing
    }
    const int q = mrgi_voxel_interleave_phase(x, y);
    phases[p] = static_cast<uint8_t>(1u << q);
    const double shade = 0.5 + 0.5 * std::sin(0.3 * x + 0.2 * y + seed);
    for (int k = 0; k < Q / 4; ++k)
    {
      const int j = 4 * k + q;
      const float z = g.Uniform(0, 1) < shade ? 1.0f : static_cast<float>(g.Uniform(0, 1));
      moments[(p * Q + static_cast<size_t>(j)) * 2] = z;
      moments[(p * Q + static_cast<size_t>(j)) * 2 + 1] = z * z;
      textures[static_cast<size_t>(k >> 1)][4 * p + 2 * static_cast<size_t>(k & 1)] = z;
      textures[static_cast<size_t>(k >> 1)][4 * p + 2 * static_cast<size_t>(k & 1) + 1] = z * z;
    }
  }
  std::vector<vtkSmartPointer<vtkTextureObject>> inputs;
  for (int k = 0; k < MRGI_VOXEL_VSM_TARGETS; ++k)
  {
    inputs.push_back(MakeTexture(window, false));
    MRGI_TEST_CHECK(inputs.back()->Create2DFromRaw(w, h, 4, VTK_FLOAT, textures[static_cast<size_t>(k)].data()));
  }
  std::vector<std::vector<float>> out;
  RunQuad(window, quad, w, h, Q / 4,
    [&](vtkShaderProgram* program) {
      for (int k = 0; k < MRGI_VOXEL_VSM_TARGETS; ++k)
      {
        inputs[static_cast<size_t>(k)]->Activate();
        program->SetUniformi(("mrgiVsmMoments" + std::to_string(k)).c_str(),
          inputs[static_cast<size_t>(k)]->GetTextureUnit());
      }
      const int size[2] = { w, h };
      program->SetUniform2i("mrgiVsmSize", size);
      program->SetUniformi("mrgiVsmRadius", radius);
      program->SetUniformf("mrgiVsmMinVariance", minVariance);
    },
    out);
  for (auto& t : inputs)
  {
    t->Deactivate();
  }
  std::vector<float> twin(pixels * Q), wrong(pixels * Q);
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_voxel_vsm_resolve(w, h, Q, moments.data(), phases.data(), radius, minVariance,
                    twin.data(), &err) == MRGI_OK);
  MRGI_TEST_CHECK(mrgi_voxel_vsm_resolve(w, h, Q, moments.data(), phases.data(), radius + 1,
                    minVariance, wrong.data(), &err) == MRGI_OK);
  size_t compared = 0, differ = 0, wrongDiffer = 0, partial = 0;
  double maxError = 0;
  for (size_t p = 0; p < pixels; ++p)
  {
    if (!phases[p])
    {
      continue; // the GPU resolves at computing pixels only
    }
    for (int j = 0; j < Q; ++j)
    {
      const float gpu = out[static_cast<size_t>(j / 4)][4 * p + static_cast<size_t>(j % 4)];
      const float c = twin[p * Q + static_cast<size_t>(j)];
      ++compared;
      const double e = std::fabs(static_cast<double>(gpu) - c);
      maxError = std::max(maxError, e);
      differ += !(e <= 2e-6);
      wrongDiffer += !(std::fabs(static_cast<double>(gpu) - wrong[p * Q + static_cast<size_t>(j)]) <= 2e-6);
      partial += c > 0.01f && c < 0.99f;
    }
  }
  std::printf("resolve %dx%d radius %d min variance %g: %zu visibilities (%.1f%% partial), %zu differ "
              "> 2e-6 (max %.2g); twin with radius %d: %zu differ\n",
    w, h, radius, static_cast<double>(minVariance), compared, 100.0 * partial / compared, differ,
    maxError, radius + 1, wrongDiffer);
  MRGI_TEST_CHECK(differ == 0);
  MRGI_TEST_CHECK(radius == 0 ? partial == 0 : partial > compared / 20); // radius 0: binary
  MRGI_TEST_CHECK(wrongDiffer > compared / 10);
  for (auto& t : inputs)
  {
    t->ReleaseGraphicsResources(window);
  }
}

// ===========================================================================
// 3. Through the pass on random box scenes.
struct SceneCase
{
  const char* Name;
  unsigned Seed;
  int Samples;
  bool TwoSided;
  bool Textured;
};

// Eye -> world of G-buffer pixel i as the shaders compute it (float,
// column-major m): position, normal, and the view direction.
void ToWorld(const float m[16], vtkDataArray* P, vtkDataArray* N, vtkIdType i, float p[3],
  float n[3], float v[3])
{
  for (int r = 0; r < 3; ++r)
  {
    p[r] = m[12 + r];
    n[r] = 0.0f;
    v[r] = 0.0f;
    for (int k = 0; k < 3; ++k)
    {
      p[r] += m[4 * k + r] * static_cast<float>(P->GetComponent(i, k));
      n[r] += m[4 * k + r] * static_cast<float>(N->GetComponent(i, k));
      v[r] -= m[4 * k + r] * static_cast<float>(P->GetComponent(i, k));
    }
  }
}

std::vector<float> AreaBuffer(vtkMRGIPass* pass, vtkRenderWindow* window)
{
  vtkNew<vtkImageData> image;
  MRGI_TEST_CHECK(pass->GetAreaLightBuffer(window, image));
  vtkDataArray* a = image->GetPointData()->GetScalars();
  std::vector<float> out(static_cast<size_t>(a->GetNumberOfTuples()) * 3);
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      out[3 * static_cast<size_t>(i) + static_cast<size_t>(k)] = static_cast<float>(a->GetComponent(i, k));
    }
  }
  return out;
}

struct PassTotals
{
  size_t Queries = 0, QueryDiffer = 0, Pixels = 0, PixelDiffer = 0, MaskChanges = 0;
} passTotals;

void PassCase(const SceneCase& sc)
{
  const int W = 128, H = 96;
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(W, H);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  Random g(sc.Seed);
  // A glossy floor and boxes standing or floating above it.
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-4, 0, -4);
  plane->SetPoint1(4, 0, -4);
  plane->SetPoint2(-4, 0, 4);
  vtkSmartPointer<vtkActor> floor = mrgitest::MakeActor(plane);
  floor->GetProperty()->SetColor(0.4, 0.4, 0.4);
  floor->GetProperty()->SetSpecular(1.0);
  floor->GetProperty()->SetSpecularPower(g.Uniform(40, 128));
  renderer->AddActor(floor);
  for (int b = 0; b < 8; ++b)
  {
    vtkNew<vtkCubeSource> cube;
    const double x = g.Uniform(-2.5, 2.5), z = g.Uniform(-2.5, 2.5), y = g.Uniform(0, 1.5);
    const double sx = g.Uniform(0.2, 0.9), sy = g.Uniform(0.1, 0.8), sz = g.Uniform(0.2, 0.9);
    cube->SetBounds(x - sx, x + sx, y, y + sy, z - sz, z + sz);
    vtkSmartPointer<vtkActor> actor = mrgitest::MakeActor(cube);
    actor->GetProperty()->SetColor(g.Uniform(0.2, 0.8), g.Uniform(0.2, 0.8), g.Uniform(0.2, 0.8));
    if (b % 2 == 0)
    {
      actor->GetProperty()->SetSpecular(g.Uniform(0.3, 1.0));
      actor->GetProperty()->SetSpecularPower(g.Uniform(10, 128));
    }
    renderer->AddActor(actor);
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(g.Uniform(-1.5, 1.5), g.Uniform(3.5, 5), g.Uniform(5.5, 7));
  camera->SetFocalPoint(0, 0.3, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(45);
  renderer->ResetCameraClippingRange();

  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> pass;
  pass->SetDelegatePass(steps);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  renderer->SetPass(pass);
  vtkNew<vtkMRGIAreaLight> light;
  light->SetCenter(g.Uniform(-0.5, 0.5), g.Uniform(3.0, 3.5), g.Uniform(-1.0, 0.0));
  const double lu = g.Uniform(0.8, 1.6), lv = g.Uniform(0.8, 1.6);
  light->SetEdgeU(lu, 0, 0);
  light->SetEdgeV(0, 0, lv); // u x v = -y: faces down
  light->SetIntensity(3.0);
  light->SetNumberOfSamples(sc.Samples);
  light->SetTwoSided(sc.TwoSided);
  if (sc.Textured)
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(8, 6, 1);
    image->AllocateScalars(VTK_FLOAT, 3);
    auto* s = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
    for (vtkIdType i = 0; i < s->GetNumberOfValues(); ++i)
    {
      s->SetValue(i, static_cast<float>(g.Uniform(0.2, 1.5)));
    }
    light->SetTextureData(image);
  }
  pass->AddAreaLight(light);
  mrgi_area_light_uniforms uniforms;
  MRGI_TEST_CHECK(light->GetCoreUniforms(&uniforms));
  const mrgi_area_light_texture_pyramid* pyramid = nullptr;
  MRGI_TEST_CHECK(light->GetCorePyramid(&pyramid));
  int count = 0;
  const mrgi_area_light_sample* samples = light->GetCoreSamples(&count);
  MRGI_TEST_CHECK(samples && count > 0);

  const int modes[2] = { vtkMRGIPass::VisibilityNaive, vtkMRGIPass::VisibilityIncremental };
  for (int mode : modes)
  {
    const bool incremental = mode == vtkMRGIPass::VisibilityIncremental;
    pass->SetAreaLightVisibility(mode);
    // Most reuse: level-0 bits that differ from the naive query's, so that
    // the comparison tells the masks from marches.
    pass->GetVisibilityPyramid()->SetRefineFraction(1.0);
    pass->SetAreaLightSpecular(false);
    window->Render();
    const std::vector<float> matte = AreaBuffer(pass, window);
    pass->SetAreaLightSpecular(true);
    window->Render();
    const std::vector<float> glossy = AreaBuffer(pass, window);

    // What the GPU used: G-buffer, voxels, masks, moments.
    vtkNew<vtkImageData> gP, gN, gA, gK, gE;
    MRGI_TEST_CHECK(pass->GetGBuffer(window, gP, gN, gA));
    MRGI_TEST_CHECK(pass->GetSpecularGBuffer(window, gK, gE));
    vtkDataArray* P = gP->GetPointData()->GetScalars();
    vtkDataArray* N = gN->GetPointData()->GetScalars();
    vtkDataArray* K = gK->GetPointData()->GetScalars();
    vtkDataArray* E = gE->GetPointData()->GetScalars();
    vtkMRGIVoxelization* voxelization = pass->GetVoxelization();
    vtkNew<vtkTypeUInt32Array> voxelWords;
    double w2vd[16];
    const mrgi_voxel_view view = mrgitest::ReadVoxelView(voxelization, window, voxelWords, w2vd);
    mrgi_error err;
    float w2v[16], v2w[16];
    std::copy(w2vd, w2vd + 16, w2v);
    std::copy(pass->GetLastViewToWorld(), pass->GetLastViewToWorld() + 16, v2w);
    vtkMRGIVarianceShadowQuery* vsq = pass->GetVarianceShadowQuery();
    vtkNew<vtkFloatArray> gpuMoments;
    vtkNew<vtkUnsignedCharArray> gpuPhases;
    MRGI_TEST_CHECK(vsq->ReadMoments(window, gpuMoments, gpuPhases));
    MRGI_TEST_CHECK(gpuPhases->GetNumberOfTuples() == static_cast<vtkIdType>(W) * H);
    vtkNew<vtkTypeUInt32Array> masks;
    int words = 0, flatW = 0;
    if (incremental)
    {
      vtkMRGIVisibilityPyramid* vp = pass->GetVisibilityPyramid();
      MRGI_TEST_CHECK(vp->ReadMasks(window, masks));
      words = vp->GetNumberOfMaskWords();
      MRGI_TEST_CHECK(words == (count + 31) / 32);
      flatW = pass->GetMultiresolution()->GetFlattenedWidth();
    }

    // a. The moments pass.
    const int Q = MRGI_VOXEL_VSM_QUERIES;
    size_t computed = 0, queries = 0, flagDiffer = 0, differ = 0, shadowedQueries = 0, wrongDiffer = 0;
    double maxError = 0;
    std::vector<float> twinMoments(2 * Q), wrongMoments(2 * Q);
    const float* gm = gpuMoments->GetPointer(0);
    for (vtkIdType i = 0; i < P->GetNumberOfTuples(); ++i)
    {
      const int x = static_cast<int>(i % W), y = static_cast<int>(i / W);
      const bool specular = P->GetComponent(i, 3) > 0.5 &&
        K->GetComponent(i, 0) + K->GetComponent(i, 1) + K->GetComponent(i, 2) > 0.0;
      int twinComputed = 0;
      const int phase = mrgi_voxel_interleave_phase(x, y);
      if (specular)
      {
        float p[3], n[3], v[3], pv[3], nv[3];
        ToWorld(v2w, P, N, i, p, n, v);
        for (int r = 0; r < 3; ++r)
        {
          pv[r] = static_cast<float>(P->GetComponent(i, r));
          nv[r] = static_cast<float>(N->GetComponent(i, r));
        }
        const float power = static_cast<float>(E->GetComponent(i, 0));
        twinComputed = mrgi_voxel_vsm_specular_moments(&view, &uniforms, samples, count, w2v, p, n, v,
          power, pv, nv, 1u << phase, twinMoments.data());
        if (twinComputed)
        {
          mrgi_voxel_vsm_specular_moments(&view, &uniforms, samples, count, w2v, p, n, v, power, pv,
            nv, 1u << ((phase + 1) & 3), wrongMoments.data());
        }
      }
      const int gpuComputed = gpuPhases->GetValue(i) != 0;
      if (gpuComputed != twinComputed)
      {
        ++flagDiffer;
        continue;
      }
      if (!twinComputed)
      {
        continue;
      }
      ++computed;
      MRGI_TEST_CHECK(gpuPhases->GetValue(i) == (1u << phase));
      for (int k = 0; k < Q / 4; ++k)
      {
        const int j = 4 * k + phase;
        const int wj = 4 * k + ((phase + 1) & 3);
        const float* g2 = gm + (static_cast<size_t>(i) * Q + static_cast<size_t>(j)) * 2;
        const double e = std::max(std::fabs(g2[0] - twinMoments[2 * static_cast<size_t>(j)]),
          std::fabs(g2[1] - twinMoments[2 * static_cast<size_t>(j) + 1]));
        ++queries;
        shadowedQueries += twinMoments[2 * static_cast<size_t>(j)] < 1.0f;
        if (e <= 1e-4)
        {
          maxError = std::max(maxError, e);
        }
        else
        {
          ++differ;
        }
        wrongDiffer += !(std::fabs(g2[0] - wrongMoments[2 * static_cast<size_t>(wj)]) <= 1e-4);
      }
    }
    std::printf("%s, %s, %d samples: moments: %zu pixels computed (%zu differ in whether), %zu "
                "queries (%.1f%% shadowed), %zu differ > 1e-4 = %.3f%% (max agreeing error %.2g); "
                "twin of the wrong phase: %zu differ\n",
      sc.Name, incremental ? "incremental" : "naive", count, computed, flagDiffer, queries,
      100.0 * shadowedQueries / std::max<size_t>(queries, 1), differ,
      100.0 * differ / std::max<size_t>(queries, 1), maxError, wrongDiffer);
    std::fflush(stdout);
    MRGI_TEST_CHECK(computed > 100 && queries > 0);
    MRGI_TEST_CHECK(shadowedQueries > queries / 100);
    MRGI_TEST_CHECK(flagDiffer < MaxRate * computed + 1);
    MRGI_TEST_CHECK(differ < MaxRate * queries);
    MRGI_TEST_CHECK(wrongDiffer > shadowedQueries / 2 && wrongDiffer > 10 * (differ + 10));
    passTotals.Queries += queries;
    passTotals.QueryDiffer += differ;

    // b. The highlight: resolve the GPU's moments with the C twin, then the
    // visible specular twin per pixel.
    std::vector<float> visibility(static_cast<size_t>(W) * H * Q);
    MRGI_TEST_CHECK(mrgi_voxel_vsm_resolve(W, H, Q, gm, gpuPhases->GetPointer(0), vsq->GetBlurRadius(),
                      static_cast<float>(vsq->GetMinVariance()), visibility.data(), &err) == MRGI_OK);
    size_t highlighted = 0, pixelDiffer = 0, shadowedPixels = 0, wrongPixels = 0;
    size_t onPath[2] = { 0, 0 };
    double num = 0, den = 0, peak = 0;
    std::vector<float> expected(static_cast<size_t>(W) * H * 3, 0.0f), unshadowed(expected.size(), 0.0f);
    std::vector<uint32_t> mask(static_cast<size_t>((count + 31) / 32));
    size_t maskChanges = 0;
    for (vtkIdType i = 0; i < P->GetNumberOfTuples(); ++i)
    {
      const int x = static_cast<int>(i % W), y = static_cast<int>(i / W);
      if (!(P->GetComponent(i, 3) > 0.5) ||
        !(K->GetComponent(i, 0) + K->GetComponent(i, 1) + K->GetComponent(i, 2) > 0.0))
      {
        continue;
      }
      float p[3], n[3], v[3], pv[3], nv[3];
      ToWorld(v2w, P, N, i, p, n, v);
      for (int r = 0; r < 3; ++r)
      {
        pv[r] = static_cast<float>(P->GetComponent(i, r));
        nv[r] = static_cast<float>(N->GetComponent(i, r));
      }
      const float power = static_cast<float>(E->GetComponent(i, 0));
      mrgi_area_light_specular_info info;
      mrgi_area_light_specular_classify(&uniforms, samples, count, p, n, v, power, &info);
      const uint32_t* bits = nullptr;
      if (info.path == MRGI_AREA_LIGHT_SPECULAR_SAMPLES)
      {
        {
          // The naive query, as the shader marches it (eye space).
          std::fill(mask.begin(), mask.end(), 0u);
          for (int j = 0; j < count; ++j)
          {
            const float* s = samples[j].position;
            const float* sn = samples[j].normal;
            float L[3], NL[3];
            for (int r = 0; r < 3; ++r)
            {
              L[r] = w2v[r] * s[0] + w2v[4 + r] * s[1] + w2v[8 + r] * s[2] + w2v[12 + r];
              NL[r] = w2v[r] * sn[0] + w2v[4 + r] * sn[1] + w2v[8 + r] * sn[2];
            }
            const float d[3] = { pv[0] - L[0], pv[1] - L[1], pv[2] - L[2] };
            if (uniforms.two_sided && NL[0] * d[0] + NL[1] * d[1] + NL[2] * d[2] < 0.0f)
            {
              NL[0] = -NL[0];
              NL[1] = -NL[1];
              NL[2] = -NL[2];
            }
            if (mrgi_voxel_march(&view, pv, nv, L, NL))
            {
              mask[static_cast<size_t>(j >> 5)] |= 1u << (j & 31);
            }
          }
          bits = mask.data();
        }
        if (incremental)
        {
          // The pyramid's level-0 bits; count the pixels where they change
          // the highlight from the naive bits (the GPU must follow them).
          const uint32_t* level0 = masks->GetPointer(static_cast<vtkIdType>(y * flatW + x) * words);
          float Sm[3], Sn[3];
          mrgi_area_light_specular_visible(&uniforms, samples, count, pyramid, p, n, v, power, level0,
            nullptr, Sm, nullptr);
          mrgi_area_light_specular_visible(&uniforms, samples, count, pyramid, p, n, v, power,
            mask.data(), nullptr, Sn, nullptr);
          maskChanges += std::fabs(Sm[0] - Sn[0]) > 1e-3 * std::fabs(Sn[0]) + 1e-6;
          bits = level0;
        }
      }
      float S[3], U[3];
      mrgi_area_light_specular_visible(&uniforms, samples, count, pyramid, p, n, v, power, bits,
        visibility.data() + static_cast<size_t>(i) * Q, S, nullptr);
      mrgi_area_light_specular(&uniforms, samples, count, pyramid, p, n, v, power, U, nullptr);
      for (int k = 0; k < 3; ++k)
      {
        expected[3 * static_cast<size_t>(i) + static_cast<size_t>(k)] = static_cast<float>(K->GetComponent(i, k)) * S[k];
        unshadowed[3 * static_cast<size_t>(i) + static_cast<size_t>(k)] = static_cast<float>(K->GetComponent(i, k)) * U[k];
        peak = std::max(peak, static_cast<double>(unshadowed[3 * static_cast<size_t>(i) + static_cast<size_t>(k)]));
      }
      if (info.path == MRGI_AREA_LIGHT_SPECULAR_SAMPLES || info.path == MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID)
      {
        ++onPath[info.path];
      }
    }
    for (size_t i = 0; i < expected.size() / 3; ++i)
    {
      bool agrees = true, wrongAgrees = true, lit = false, shadowed = false;
      for (int k = 0; k < 3; ++k)
      {
        const size_t c = 3 * i + static_cast<size_t>(k);
        const double got = static_cast<double>(glossy[c]) - matte[c];
        const double e = expected[c];
        const double tolerance = Relative * std::fabs(e) + 3e-7 * std::fabs(glossy[c]) + 1e-6 * peak;
        agrees = agrees && std::fabs(got - e) <= tolerance;
        wrongAgrees = wrongAgrees && std::fabs(got - unshadowed[c]) <= tolerance;
        num += (got - e) * (got - e);
        den += e * e;
        lit = lit || unshadowed[c] > 1e-3 * peak;
        shadowed = shadowed || e < 0.9 * unshadowed[c] - 1e-3 * peak;
      }
      if (!lit)
      {
        continue;
      }
      ++highlighted;
      pixelDiffer += !agrees;
      shadowedPixels += shadowed;
      wrongPixels += !wrongAgrees;
      if (!agrees && pixelDiffer <= 3)
      {
        std::printf("    pixel %zu differs: GPU (%.7g %.7g %.7g) twin (%.7g %.7g %.7g) unshadowed (%.7g)\n",
          i, glossy[3 * i] - matte[3 * i], glossy[3 * i + 1] - matte[3 * i + 1],
          glossy[3 * i + 2] - matte[3 * i + 2], expected[3 * i], expected[3 * i + 1],
          expected[3 * i + 2], unshadowed[3 * i]);
      }
    }
    const double rms = std::sqrt(num / (den > 0 ? den : 1.0));
    std::printf("  highlight: specular pixels on the sample sum %zu (%zu of them lit otherwise by the "
                "level-0 bits than by the naive ones), on the lobe grid %zu; %zu lit, %zu of them shadowed; "
                "%zu differ = %.3f%%, relative RMS %.2g; twin without visibility differs on %zu\n",
      onPath[0], maskChanges, onPath[1], highlighted, shadowedPixels, pixelDiffer,
      100.0 * pixelDiffer / std::max<size_t>(highlighted, 1), rms, wrongPixels);
    std::fflush(stdout);
    MRGI_TEST_CHECK(highlighted > 200 && onPath[0] > 20 && onPath[1] > 20);
    MRGI_TEST_CHECK(shadowedPixels > highlighted / 50);
    MRGI_TEST_CHECK(pixelDiffer < MaxRate * highlighted);
    MRGI_TEST_CHECK(rms < 1e-3);
    MRGI_TEST_CHECK(wrongPixels > shadowedPixels / 2 && wrongPixels > 10 * (pixelDiffer + 1));
    passTotals.Pixels += highlighted;
    passTotals.MaskChanges += maskChanges;
    passTotals.PixelDiffer += pixelDiffer;
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
}
}

int main()
{
  {
    vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(64, 48);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    window->Render();
    vtkOpenGLRenderWindow* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
    MRGI_TEST_CHECK(gl);

    // 1. The shadowed sum.
    vtkOpenGLQuadHelper* sumQuad = MakeQuad(gl,
      std::string("#define MRGI_AREA_SPECULAR_VISIBILITY 1\n") +
        vtkMRGIAreaLight::GetShaderSource(true, true) + SumBody);
    const LightCase cases[] = {
      { "untextured one-sided", 0, 0, false, 16, false, 21 },
      { "textured 37x23 two-sided", 37, 23, true, 256, false, 22 },
      { "textured 64x64 one-sided, jittered", 64, 64, false, 64, true, 23 },
      { "untextured two-sided, 4 samples", 0, 0, true, 4, false, 24 },
    };
    for (const LightCase& c : cases)
    {
      SumCase(c, gl, sumQuad);
    }
    std::printf("shadowed sum, all cases: %zu receivers, %zu differ (%zu path flips), max rel. error "
                "%.2g; no-visibility twin differs on %zu of %zu lit, transposed queries on %zu of "
                "%zu lit lobe-grid receivers\n",
      sumTotals.Receivers, sumTotals.Differ, sumTotals.PathFlips, sumTotals.MaxError,
      sumTotals.WrongNone, sumTotals.Lit, sumTotals.WrongTransposed, sumTotals.GridLit);
    MRGI_TEST_CHECK(sumTotals.WrongNone > sumTotals.Lit / 2 && sumTotals.WrongNone > 20 * (sumTotals.Differ + 10));
    MRGI_TEST_CHECK(sumTotals.WrongTransposed > sumTotals.GridLit / 2);
    sumQuad->ReleaseGraphicsResources(gl);
    delete sumQuad;

    // 2. The resolve.
    vtkOpenGLQuadHelper* resolveQuad =
      MakeQuad(gl, std::string(vtkMRGIVarianceShadowQuery::GetResolveShaderSource()) + ResolveBody);
    ResolveCase(gl, resolveQuad, 96, 64, 0, 0.0f, 31);
    ResolveCase(gl, resolveQuad, 96, 64, 1, 1e-4f, 32);
    ResolveCase(gl, resolveQuad, 61, 37, 2, 1e-4f, 33);
    ResolveCase(gl, resolveQuad, 96, 64, 3, 1e-2f, 34);
    resolveQuad->ReleaseGraphicsResources(gl);
    delete resolveQuad;
  }

  // 3. Through the pass.
  const SceneCase scenes[] = {
    { "boxes A", 41, 64, false, false },
    { "boxes B, two-sided textured", 42, 16, true, true },
  };
  for (const SceneCase& sc : scenes)
  {
    PassCase(sc);
  }
  std::printf("pass, all cases: moments %zu of %zu queries differ; highlight %zu of %zu pixels differ "
              "(%zu where the level-0 bits light otherwise than the naive ones)\n",
    passTotals.QueryDiffer, passTotals.Queries, passTotals.PixelDiffer, passTotals.Pixels,
    passTotals.MaskChanges);
  // The incremental case can tell the masks from marches.
  MRGI_TEST_CHECK(passTotals.MaskChanges > 20);
  return 0;
}
