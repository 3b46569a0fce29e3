// The GLSL Phong specular of area lights (vtkMRGIAreaLightSpecular.glsl,
// nichols-penmatsa-wyman-2010 section 3.2.1) against its C twins
// (mrgi_area_light_specular(), mrgi_area_light_phong_lobe(),
// mrgi_area_light_phong_refinement(), mrgi_area_light_texture_sample(),
// mrgi_area_light.h) on the same receivers, samples and pyramid: the light's
// samples and pyramid reach the GPU through vtkMRGIAreaLight::
// GetSampleTexture() / GetPyramidTexture() and its uniforms through
// SetShaderUniforms(); the GLSL runs once per receiver in a full-screen pass
// whose fragment i reads receiver i from an RGBA32F texture and writes S,
// the path, the lobe, the refinement metric and a direct pyramid lookup
// into five RGBA32F targets.
//
// Receivers: lobes aimed at (and just off) the light, random ones, surfaces
// below it, grazing views, zero normals and views, behind the light, in its
// plane, far and very near, non-unit vectors, reflections along the light's
// normal; powers 0, 1, 10, 128, uniform in [0, 128] and tiny. Lights:
// untextured and textured (NPOT, 1-row and wide float pictures), one- and
// two-sided, 16 and 256 samples, centred and jittered, axis-aligned and
// oblique.
//
// Bounds (mrgi_area_light.h "Precision": GLSL's pow, exp2, log2, sqrt and
// division need not round as C's, and GLSL may fuse a * b + c): S agrees to
// relative 1e-4 with an absolute floor of 1e-7 times the case's largest S,
// and the path agrees. A disagreement is explained when the receiver lies
// in the light's plane up to rounding (early-out 1's boundary), or when the
// twin itself gives the GPU's path and value once the receiver's inputs
// move by a few float ulps (relative 2e-7 .. 4e-6: a lobe value at the
// cutoff, the peak at the discard threshold, a receiver a hair above the
// light where the lobe grid's vectors are cancellations). Per case: paths
// differ for under 0.5% of the receivers, S or path for under 2%, and
// unexplained disagreements stay under 0.05% (for S, the lobe, the counts
// and the refinement metric alike); direct pyramid lookups agree everywhere.
// A twin with a perturbed power (the cutoff and the lobe read at the wrong
// place) and, on textured lights, one without the pyramid must fail.
#include "mrgiTestUtilities.h"

#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIAreaLight.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPixelBufferObject.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "mrgi_area_light.h"
#include "mrgi_glsl_defines.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace
{
// ---------------------------------------------------------------------------
// One receiver: 4 RGBA32F texels (P, N.x) (N.yz, V.xy) (V.z, power, e, s)
// (tex s, tex t, lod, 0).
struct Receiver
{
  float P[3], N[3], V[3];
  float Power;
  float EyeDistance, TexelSize;
  float S, T, Lod, Pad;
};
static_assert(sizeof(Receiver) == 16 * sizeof(float), "4 RGBA texels per receiver");

const int GridW = 128;
const int GridH = 128;
const int Count = GridW * GridH;
const int Targets = 5;

const char* const Body = R"(
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; receivers are addressed by gl_FragCoord
uniform sampler2D mrgiReceivers;
uniform int mrgiUseWrapper; // 1: mrgiAreaLightSpecular() (no counts), 0: ...Info()
//VTK::Output::Dec
void main()
{
  if (texCoord.x < -1.0) { discard; } // never true: keeps texCoord alive
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 t0 = texelFetch(mrgiReceivers, ivec2(4 * p.x, p.y), 0);
  vec4 t1 = texelFetch(mrgiReceivers, ivec2(4 * p.x + 1, p.y), 0);
  vec4 t2 = texelFetch(mrgiReceivers, ivec2(4 * p.x + 2, p.y), 0);
  vec4 t3 = texelFetch(mrgiReceivers, ivec2(4 * p.x + 3, p.y), 0);
  vec3 P = t0.xyz;
  vec3 N = vec3(t0.w, t1.xy);
  vec3 V = vec3(t1.zw, t2.x);
  float power = t2.y;
  int path;
  int inLobe = 0;
  int cells = 0;
  vec3 S;
  if (mrgiUseWrapper != 0)
  {
    S = mrgiAreaLightSpecular(P, N, V, power, path);
  }
  else
  {
    mrgiAreaLightLobe info;
    S = mrgiAreaLightSpecularInfo(P, N, V, power, path, inLobe, cells, info);
  }
  mrgiAreaLightLobe lobe = mrgiAreaLightPhongLobe(P, N, V, power);
  float m = mrgiAreaLightPhongRefinement(lobe, t2.z, t2.w);
  vec3 texel = mrgiAreaTextureSample(t3.x, t3.y, t3.z);
  gl_FragData[0] = vec4(S, float(path));
  gl_FragData[1] = vec4(lobe.peak, lobe.tanHalf, lobe.distance, lobe.width);
  gl_FragData[2] = vec4(lobe.hitU, lobe.hitV,
    float((lobe.reachesPlane ? 1 : 0) + (lobe.hitsLight ? 2 : 0)), m);
  gl_FragData[3] = vec4(lobe.reflect, float(inLobe * 32 + cells));
  gl_FragData[4] = vec4(texel, lobe.inverseDistance);
}
)";

std::string CoreDefines()
{
  std::vector<char> buffer(mrgi_glsl_defines_size());
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_glsl_defines(buffer.data(), buffer.size(), nullptr, &err) == MRGI_OK);
  return std::string(buffer.data());
}

std::string ShaderSource(const std::string& libraries)
{
  return std::string("//VTK::System::Dec\n") + CoreDefines() + libraries + Body;
}

class GPUSpecular
{
public:
  explicit GPUSpecular(vtkOpenGLRenderWindow* window)
    : Window(window)
  {
    window->MakeCurrent();
    // Both libraries, as a gather that shows diffuse and specular has them.
    const std::string fs = ShaderSource(vtkMRGIAreaLight::GetShaderSource(true, true));
    this->Quad = new vtkOpenGLQuadHelper(
      window, vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), fs.c_str(), "");
    MRGI_TEST_CHECK(this->Quad->Program && this->Quad->Program->GetCompiled());
    auto setup = [window](vtkTextureObject* t) {
      t->SetContext(window);
      t->SetInternalFormat(GL_RGBA32F);
      t->SetFormat(GL_RGBA);
      t->SetDataType(GL_FLOAT);
      t->SetMinificationFilter(vtkTextureObject::Nearest);
      t->SetMagnificationFilter(vtkTextureObject::Nearest);
    };
    setup(this->Input);
    for (auto& output : this->Outputs)
    {
      setup(output);
      MRGI_TEST_CHECK(output->Allocate2D(GridW, GridH, 4, VTK_FLOAT));
    }
    this->Fbo->SetContext(window);
  }

  ~GPUSpecular()
  {
    this->Window->MakeCurrent();
    delete this->Quad;
    this->Input->ReleaseGraphicsResources(this->Window);
    for (auto& output : this->Outputs)
    {
      output->ReleaseGraphicsResources(this->Window);
    }
    this->Fbo->ReleaseGraphicsResources(this->Window);
  }

  // out[k]: target k, 4 floats per receiver.
  void Run(vtkMRGIAreaLight* light, const std::vector<Receiver>& receivers, bool wrapper,
    std::vector<float> out[Targets])
  {
    MRGI_TEST_CHECK(static_cast<int>(receivers.size()) == Count);
    vtkOpenGLRenderWindow* window = this->Window;
    window->MakeCurrent();
    MRGI_TEST_CHECK(this->Input->Create2DFromRaw(
      4 * GridW, GridH, 4, VTK_FLOAT, const_cast<float*>(&receivers[0].P[0])));
    window->GetShaderCache()->ReadyShaderProgram(this->Quad->Program);
    vtkShaderProgram* program = this->Quad->Program;
    MRGI_TEST_CHECK(light->SetShaderUniforms(program, window));
    this->Input->Activate();
    program->SetUniformi("mrgiReceivers", this->Input->GetTextureUnit());
    program->SetUniformi("mrgiUseWrapper", wrapper ? 1 : 0);

    vtkOpenGLState* ostate = window->GetState();
    {
      vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
      vtkOpenGLState::ScopedglEnableDisable depth(ostate, GL_DEPTH_TEST);
      vtkOpenGLState::ScopedglViewport viewport(ostate);
      ostate->vtkglDisable(GL_BLEND);
      ostate->vtkglDisable(GL_DEPTH_TEST);
      this->Fbo->SaveCurrentBindingsAndBuffers();
      this->Fbo->Bind();
      for (int k = 0; k < Targets; ++k)
      {
        this->Fbo->AddColorAttachment(k, this->Outputs[k]);
      }
      this->Fbo->ActivateDrawBuffers(Targets);
      const char* status = nullptr;
      MRGI_TEST_CHECK(vtkOpenGLFramebufferObject::GetFrameBufferStatus(GL_FRAMEBUFFER, status));
      ostate->vtkglViewport(0, 0, GridW, GridH);
      this->Quad->Render();
      for (int k = 0; k < Targets; ++k)
      {
        // Read back through VTK (a pixel buffer object): no GL entry points.
        this->Fbo->ActivateReadBuffer(k);
        int extent[4] = { 0, GridW - 1, 0, GridH - 1 };
        vtkPixelBufferObject* pbo = this->Fbo->DownloadColor4(extent, VTK_FLOAT);
        MRGI_TEST_CHECK(pbo);
        const float* mapped = static_cast<const float*>(pbo->MapPackedBuffer());
        MRGI_TEST_CHECK(mapped);
        out[k].assign(mapped, mapped + 4 * static_cast<size_t>(Count));
        pbo->UnmapPackedBuffer();
        pbo->Delete();
      }
      this->Fbo->RemoveColorAttachments(Targets);
      this->Fbo->UnBind();
      this->Fbo->RestorePreviousBindingsAndBuffers();
    }
    this->Input->Deactivate();
    light->DeactivateTextures();
  }

private:
  vtkOpenGLRenderWindow* Window;
  vtkOpenGLQuadHelper* Quad = nullptr;
  vtkNew<vtkTextureObject> Input;
  vtkNew<vtkTextureObject> Outputs[Targets];
  vtkNew<vtkOpenGLFramebufferObject> Fbo;
};

// ---------------------------------------------------------------------------
// Lights and receivers.
struct LightCase
{
  const char* Name;
  int TextureW, TextureH; // 0: untextured
  bool TwoSided;
  int Samples;
  bool Jitter;
  bool AxisAligned;
  unsigned Seed;
};

double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void Cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

void Normalize(double v[3])
{
  const double l = std::sqrt(Dot(v, v));
  for (int k = 0; k < 3; ++k)
  {
    v[k] /= l;
  }
}

class Generator
{
public:
  explicit Generator(unsigned seed)
    : Rng(seed)
  {
  }

  double Uniform(double lo, double hi)
  {
    return lo + (hi - lo) * (static_cast<double>(this->Rng() >> 5) / 134217728.0);
  }

  void Direction(double v[3])
  {
    double l2;
    do
    {
      for (int k = 0; k < 3; ++k)
      {
        v[k] = this->Uniform(-1, 1);
      }
      l2 = Dot(v, v);
    } while (l2 > 1 || l2 < 1e-4);
    Normalize(v);
  }

  // A unit vector at a random angle from `axis` in its hemisphere, at least
  // `minCos` from the horizon.
  void Around(const double axis[3], double minCos, double out[3])
  {
    double d[3];
    do
    {
      this->Direction(d);
      if (Dot(d, axis) < 0)
      {
        for (double& c : d)
        {
          c = -c;
        }
      }
    } while (Dot(d, axis) < minCos);
    std::copy(d, d + 3, out);
  }

  float Power()
  {
    const double pick = this->Uniform(0, 1);
    if (pick < 0.4)
    {
      static const float fixed[] = { 0.0f, 1.0f, 10.0f, 128.0f };
      return fixed[static_cast<int>(this->Uniform(0, 4)) & 3];
    }
    if (pick < 0.5)
    {
      // Small powers, from 0.01: below 1/126, C's exp2f(-1/n) is a
      // subnormal float, which GPUs flush to 0 (the twins then differ; see
      // vtkMRGIAreaLightSpecular.glsl).
      return static_cast<float>(std::pow(10.0, this->Uniform(-2, 0)));
    }
    return static_cast<float>(this->Uniform(0, 128));
  }

  std::mt19937 Rng;
};

struct LightFrame
{
  double C[3], U[3], V[3], N[3]; // centre, FULL edges, unit normal
  double Size;                   // the longer edge
};

// The receiver generator; `frame` is the light.
Receiver MakeReceiver(Generator& g, const LightFrame& f, bool twoSided, int levels)
{
  Receiver r;
  std::memset(&r, 0, sizeof(r));
  double P[3], N[3], V[3];
  auto point = [&](double a, double b, double h, double out[3]) {
    for (int k = 0; k < 3; ++k)
    {
      out[k] = f.C[k] + a * f.U[k] + b * f.V[k] + h * f.N[k];
    }
  };
  // The mirror direction: N around w, V = reflect(-w, N) so that R = w.
  auto aimAt = [&](const double target[3]) {
    double w[3] = { target[0] - P[0], target[1] - P[1], target[2] - P[2] };
    Normalize(w);
    g.Around(w, 0.02, N);
    const double nw = Dot(N, w);
    for (int k = 0; k < 3; ++k)
    {
      V[k] = 2 * nw * N[k] - w[k];
    }
  };
  auto randomSide = [&]() { return (twoSided && g.Uniform(0, 1) < 0.4) ? -1.0 : 1.0; };
  const double kind = g.Uniform(0, 1);
  if (kind < 0.30) // a lobe aimed at the light or just off it
  {
    const double h = f.Size * std::pow(10.0, g.Uniform(-1.5, 1.0)) * randomSide();
    point(g.Uniform(-2, 2), g.Uniform(-2, 2), h, P);
    double target[3];
    const double reach = g.Uniform(0, 1) < 0.7 ? 0.5 : 0.75;
    point(g.Uniform(-reach, reach), g.Uniform(-reach, reach), 0, target);
    aimAt(target);
  }
  else if (kind < 0.48) // anywhere, any directions
  {
    point(g.Uniform(-3, 3), g.Uniform(-3, 3), f.Size * g.Uniform(-3, 3), P);
    g.Direction(N);
    g.Direction(V);
  }
  else if (kind < 0.58) // a surface below the light, facing it roughly
  {
    point(g.Uniform(-3, 3), g.Uniform(-3, 3), f.Size * g.Uniform(0.2, 2) * randomSide(), P);
    double toLight[3] = { f.C[0] - P[0], f.C[1] - P[1], f.C[2] - P[2] };
    Normalize(toLight);
    g.Around(toLight, 0.1, N);
    g.Around(N, 0.0, V);
  }
  else if (kind < 0.63) // grazing views
  {
    const double h = f.Size * g.Uniform(0.1, 2) * randomSide();
    point(g.Uniform(-1, 1), g.Uniform(-1, 1), h, P);
    double toLight[3] = { f.C[0] - P[0], f.C[1] - P[1], f.C[2] - P[2] };
    Normalize(toLight);
    g.Around(toLight, 0.1, N);
    double d[3];
    g.Direction(d);
    const double along = Dot(d, N);
    for (int k = 0; k < 3; ++k)
    {
      d[k] -= along * N[k];
    }
    Normalize(d);
    static const double tilts[] = { 0.0, 1e-7, -1e-7, 1e-5, -1e-5, 1e-3, 3e-2 };
    const double tilt = tilts[static_cast<int>(g.Uniform(0, 7)) % 7];
    for (int k = 0; k < 3; ++k)
    {
      V[k] = d[k] + tilt * N[k];
    }
  }
  else if (kind < 0.66) // zero normal or zero view
  {
    point(g.Uniform(-1, 1), g.Uniform(-1, 1), f.Size * g.Uniform(0.1, 2), P);
    g.Direction(N);
    g.Direction(V);
    if (g.Uniform(0, 1) < 0.5)
    {
      std::fill(N, N + 3, 0.0);
    }
    else
    {
      std::fill(V, V + 3, 0.0);
    }
  }
  else if (kind < 0.71) // behind the light
  {
    point(g.Uniform(-1.5, 1.5), g.Uniform(-1.5, 1.5), -f.Size * g.Uniform(0.01, 2), P);
    double target[3];
    point(g.Uniform(-0.5, 0.5), g.Uniform(-0.5, 0.5), 0, target);
    aimAt(target);
  }
  else if (kind < 0.725) // in the light's plane (centre, corners, inside, outside)
  {
    const double pick = g.Uniform(0, 1);
    const double a = pick < 0.1 ? 0.0 : (pick < 0.2 ? 0.5 : g.Uniform(-1.5, 1.5));
    const double b = pick < 0.1 ? 0.0 : (pick < 0.2 ? -0.5 : g.Uniform(-1.5, 1.5));
    point(a, b, 0, P);
    g.Direction(N);
    g.Direction(V);
  }
  else if (kind < 0.81) // far
  {
    double d[3];
    g.Direction(d);
    if (!twoSided && Dot(d, f.N) < 0)
    {
      for (double& c : d)
      {
        c = -c;
      }
    }
    const double distance = f.Size * std::pow(10.0, g.Uniform(2, 4));
    for (int k = 0; k < 3; ++k)
    {
      P[k] = f.C[k] + distance * d[k];
    }
    double target[3];
    point(g.Uniform(-0.6, 0.6), g.Uniform(-0.6, 0.6), 0, target);
    aimAt(target);
  }
  else if (kind < 0.88) // very near the light
  {
    const double h = f.Size * std::pow(10.0, g.Uniform(-5, -2)) * randomSide();
    point(g.Uniform(-0.55, 0.55), g.Uniform(-0.55, 0.55), h, P);
    double target[3];
    point(g.Uniform(-0.5, 0.5), g.Uniform(-0.5, 0.5), 0, target);
    aimAt(target);
  }
  else if (kind < 0.93) // non-unit vectors
  {
    const double h = f.Size * g.Uniform(0.1, 3) * randomSide();
    point(g.Uniform(-1, 1), g.Uniform(-1, 1), h, P);
    double target[3];
    point(g.Uniform(-0.6, 0.6), g.Uniform(-0.6, 0.6), 0, target);
    aimAt(target);
    const double a = std::pow(10.0, g.Uniform(-3, 3)), b = std::pow(10.0, g.Uniform(-3, 3));
    for (int k = 0; k < 3; ++k)
    {
      N[k] *= a;
      V[k] *= b;
    }
  }
  else // R along the light's normal (the lobe grid's axis fallback)
  {
    const double side = randomSide();
    point(g.Uniform(-0.5, 0.5), g.Uniform(-0.5, 0.5), side * f.Size * g.Uniform(0.05, 2), P);
    static const double tilts[] = { 0.0, 1e-7, 1e-6, 3e-6, 1e-5, 1e-3 };
    const double tilt = tilts[static_cast<int>(g.Uniform(0, 6)) % 6];
    double d[3];
    g.Direction(d);
    for (int k = 0; k < 3; ++k)
    {
      N[k] = -side * f.N[k];
      V[k] = -side * f.N[k] + tilt * d[k];
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    r.P[k] = static_cast<float>(P[k]);
    r.N[k] = static_cast<float>(N[k]);
    r.V[k] = static_cast<float>(V[k]);
  }
  r.Power = g.Power();
  // The refinement metric's inputs: eye distance (sometimes 0 or negative)
  // and texel size.
  const double e = g.Uniform(0, 1);
  r.EyeDistance = e < 0.04 ? 0.0f : (e < 0.06 ? -1.0f : static_cast<float>(std::pow(10.0, g.Uniform(-2, 3))));
  r.TexelSize = g.Uniform(0, 1) < 0.05 ? 0.0f : static_cast<float>(std::pow(10.0, g.Uniform(-5, 0)));
  // A direct pyramid lookup: coordinates around [0, 1], integral lods too.
  r.S = static_cast<float>(g.Uniform(-0.2, 1.2));
  r.T = static_cast<float>(g.Uniform(-0.2, 1.2));
  r.Lod = g.Uniform(0, 1) < 0.15 ? static_cast<float>(static_cast<int>(g.Uniform(0, levels)))
                                 : static_cast<float>(g.Uniform(-1.5, levels + 0.5));
  return r;
}

// ---------------------------------------------------------------------------
// The comparison.
const double Relative = 1e-4;
const double Floor = 1e-7; // of the case's largest S
const double MaxRate = 0.005;
const double MaxUnexplainedRate = 5e-4;

struct Twin
{
  const mrgi_area_light_uniforms* Light;
  const mrgi_area_light_sample* Samples;
  int Count;
  const mrgi_area_light_texture_pyramid* Pyramid;
};

void TwinSpecular(const Twin& t, const Receiver& r, float power, float S[3],
  mrgi_area_light_specular_info* info)
{
  mrgi_area_light_specular(
    t.Light, t.Samples, t.Count, t.Pyramid, r.P, r.N, r.V, power, S, info);
}

bool Close(double gpu, double twin, double floor)
{
  return std::fabs(gpu - twin) <= Relative * std::fabs(twin) + floor;
}

bool SClose(const float gpu[3], const float twin[3], double floor)
{
  for (int c = 0; c < 3; ++c)
  {
    if (!Close(gpu[c], twin[c], floor))
    {
      return false;
    }
  }
  return true;
}

// What the twin computes for one receiver, as one discrete key (a path,
// flags) and continuous values, each with its absolute tolerance floor.
struct Outcome
{
  int Key = 0;
  std::vector<double> Values;
  std::vector<double> Floors;
};

bool Agrees(int gpuKey, const double* gpu, const Outcome& twin)
{
  if (gpuKey != twin.Key)
  {
    return false;
  }
  for (size_t k = 0; k < twin.Values.size(); ++k)
  {
    if (!Close(gpu[k], twin.Values[k], twin.Floors[k]))
    {
      return false;
    }
  }
  return true;
}

// Whether the GPU's answer is within the twin's own rounding sensitivity:
// with the receiver's inputs moved by a few float ulps (relative 2e-7 ..
// 4e-6; 48 trials), some trials give the GPU's key, and every GPU value lies
// in the envelope of those trials' values (widened by the tolerance). This
// explains path flips at thresholds and values of ill-conditioned receivers
// (a reflection grazing the light's plane, a lobe grid a hair above the
// light) where one differently rounded operation (GLSL may fuse a * b + c)
// moves the result as much as an ulp of input does.
template <typename F>
bool WithinRounding(const Receiver& receiver, int gpuKey, const double* gpu, F twin, unsigned seed)
{
  std::mt19937 rng(seed);
  std::vector<double> lo, hi;
  const Outcome original = twin(receiver);
  if (original.Key == gpuKey)
  {
    lo = hi = original.Values;
  }
  for (int trial = 0; trial < 48; ++trial)
  {
    Receiver r = receiver;
    const double scale = trial < 16 ? 2e-7 : (trial < 32 ? 1e-6 : 4e-6);
    float* values = &r.P[0];
    for (int k = 0; k < 12; ++k) // P, N, V, power, eye distance, texel size
    {
      const double e = scale * (static_cast<double>(rng()) / 4294967296.0 * 2.0 - 1.0);
      values[k] = static_cast<float>(values[k] * (1.0 + e));
    }
    const Outcome o = twin(r);
    if (o.Key != gpuKey)
    {
      continue;
    }
    if (lo.empty())
    {
      lo = hi = o.Values;
    }
    for (size_t k = 0; k < o.Values.size(); ++k)
    {
      lo[k] = std::min(lo[k], o.Values[k]);
      hi[k] = std::max(hi[k], o.Values[k]);
    }
  }
  if (lo.empty())
  {
    return false;
  }
  for (size_t k = 0; k < lo.size(); ++k)
  {
    const double slack = Relative * std::max(std::fabs(lo[k]), std::fabs(hi[k])) + original.Floors[k];
    if (!(gpu[k] >= lo[k] - slack && gpu[k] <= hi[k] + slack))
    {
      return false;
    }
  }
  return true;
}

// Whether the receiver lies in the light's plane up to the rounding of
// n.(P - c) (8 float ulps of its terms): early-out 1's boundary. Its side
// of the light, and so every cosine towards the light, is rounding noise.
bool InPlane(const mrgi_area_light_uniforms& light, const Receiver& r)
{
  double side = 0, scale = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double term = static_cast<double>(light.normal[k]) * (r.P[k] - light.center[k]);
    side += term;
    scale += std::fabs(term) + std::fabs(light.normal[k] * r.P[k]);
  }
  return std::fabs(side) <= 8.0 * FLT_EPSILON * scale;
}

// A comparison's tally.
struct Tally
{
  size_t Differ = 0, InPlane = 0, Explained = 0; // Explained includes InPlane
  void Add(bool agrees, bool inPlane, bool explained)
  {
    this->Differ += !agrees;
    this->InPlane += !agrees && inPlane;
    this->Explained += !agrees && (inPlane || explained);
  }
  size_t OffPlane() const { return this->Differ - this->InPlane; }
  size_t Other() const { return this->Differ - this->Explained; }
};

struct Totals
{
  size_t Receivers = 0, PathFlips = 0;
  Tally Specular, Counts, Lobe, Refinement, Lookups;
  size_t Paths[5] = { 0, 0, 0, 0, 0 };
  double MaxError = 0, MaxBound = 0;
} totals;

const char* const PathNames[5] = { "samples", "lobe grid", "behind", "facing away", "lobe miss" };

vtkSmartPointer<vtkImageData> MakeTexture(int w, int h, unsigned seed)
{
  std::mt19937 rng(seed);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  image->AllocateScalars(VTK_FLOAT, 3);
  auto* s = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  for (vtkIdType i = 0; i < s->GetNumberOfValues(); ++i)
  {
    // HDR: mostly [0, 2], a few bright texels.
    const double u = static_cast<double>(rng()) / 4294967296.0;
    s->SetValue(i, static_cast<float>(u < 0.05 ? 20.0 * u * 20.0 : 2.0 * u));
  }
  return image;
}

void SetupLight(vtkMRGIAreaLight* light, const LightCase& c, LightFrame& f)
{
  Generator g(c.Seed);
  double lu = g.Uniform(0.5, 2.5), lv = g.Uniform(0.5, 2.5);
  double u[3], v[3];
  if (c.AxisAligned)
  {
    lu = 1.5;
    lv = 0.75;
    const double uu[3] = { 1, 0, 0 }, vv[3] = { 0, 1, 0 };
    std::copy(uu, uu + 3, u);
    std::copy(vv, vv + 3, v);
  }
  else
  {
    g.Direction(u);
    double d[3];
    g.Direction(d);
    Cross(u, d, v);
    Normalize(v);
  }
  double center[3] = { g.Uniform(-3, 3), g.Uniform(-3, 3), g.Uniform(-3, 3) };
  if (c.AxisAligned)
  {
    center[0] = 0.25;
    center[1] = -0.5;
    center[2] = 2.0;
  }
  for (int k = 0; k < 3; ++k)
  {
    f.C[k] = center[k];
    f.U[k] = lu * u[k];
    f.V[k] = lv * v[k];
  }
  Cross(f.U, f.V, f.N);
  Normalize(f.N);
  f.Size = std::max(lu, lv);
  light->SetCenter(f.C);
  light->SetEdgeU(f.U);
  light->SetEdgeV(f.V);
  light->SetColor(g.Uniform(0.2, 1.5), g.Uniform(0.2, 1.5), g.Uniform(0.2, 1.5));
  light->SetIntensity(g.Uniform(0.5, 5));
  light->SetTwoSided(c.TwoSided);
  light->SetNumberOfSamples(c.Samples);
  light->SetJitter(c.Jitter);
  light->SetSeed(c.Seed);
  light->SetTextureData(c.TextureW > 0 ? MakeTexture(c.TextureW, c.TextureH, c.Seed + 1).Get() : nullptr);
}

struct CaseResult
{
  size_t Mismatch = 0;
  size_t Lit = 0, WrongPower = 0, GridLit = 0, WrongPyramid = 0;
};

void PrintTally(const char* name, const Tally& t)
{
  std::printf(" %s %zu (%zu in the plane, %zu other boundary, %zu unexplained)", name, t.Differ,
    t.InPlane, t.Explained - t.InPlane, t.Other());
}

CaseResult RunCase(const LightCase& c, vtkOpenGLRenderWindow* window, GPUSpecular& gpu,
  bool wrapper = false)
{
  vtkNew<vtkMRGIAreaLight> light;
  LightFrame frame;
  SetupLight(light, c, frame);
  mrgi_area_light_uniforms uniforms;
  MRGI_TEST_CHECK(light->GetCoreUniforms(&uniforms));
  const mrgi_area_light_texture_pyramid* pyramid = nullptr;
  MRGI_TEST_CHECK(light->GetCorePyramid(&pyramid));
  MRGI_TEST_CHECK((pyramid != nullptr) == (c.TextureW > 0));
  int count = 0;
  const mrgi_area_light_sample* samples = light->GetCoreSamples(&count);
  MRGI_TEST_CHECK(samples && count > 0 && count <= c.Samples);
  // The direct lookups read the uploaded pyramid: the 1 x 1 white one
  // without a texture.
  mrgi_area_light_texture_pyramid white{};
  float whiteTexel[3];
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_area_light_texture_pyramid_init(&white, nullptr, whiteTexel, 3, &err) == MRGI_OK);
  const mrgi_area_light_texture_pyramid* lookup = pyramid ? pyramid : &white;

  Generator g(c.Seed + 7);
  std::vector<Receiver> receivers(Count);
  for (Receiver& r : receivers)
  {
    r = MakeReceiver(g, frame, c.TwoSided, lookup->level_count);
  }
  std::vector<float> out[Targets];
  gpu.Run(light, receivers, wrapper, out);

  const Twin twin = { &uniforms, samples, count, pyramid };
  double peak = 0;
  for (const Receiver& r : receivers)
  {
    float S[3];
    TwinSpecular(twin, r, r.Power, S, nullptr);
    peak = std::max({ peak, static_cast<double>(S[0]), static_cast<double>(S[1]),
      static_cast<double>(S[2]) });
  }
  const double floor = Floor * peak;
  double texelPeak = 0;
  for (size_t k = 0; k < lookup->float_count; ++k)
  {
    texelPeak = std::max(texelPeak, static_cast<double>(lookup->texels[k]));
  }

  // The twins as outcomes: S with its path; the path's counts; the lobe
  // with its flags; the refinement metric.
  auto specular = [&](const Receiver& r) {
    Outcome o;
    float S[3];
    mrgi_area_light_specular_info info;
    TwinSpecular(twin, r, r.Power, S, &info);
    o.Key = info.path;
    o.Values = { S[0], S[1], S[2] };
    o.Floors = { floor, floor, floor };
    return o;
  };
  auto counts = [&](const Receiver& r) {
    Outcome o;
    float S[3];
    mrgi_area_light_specular_info info;
    TwinSpecular(twin, r, r.Power, S, &info);
    o.Key = info.path * 1000000 + info.samples_in_lobe * 32 + info.grid_cells;
    return o;
  };
  auto lobeOf = [&](const Receiver& r) {
    Outcome o;
    mrgi_area_light_lobe lobe;
    mrgi_area_light_phong_lobe(&uniforms, r.P, r.N, r.V, r.Power, &lobe);
    o.Key = (lobe.reaches_plane ? 1 : 0) + (lobe.hits_light ? 2 : 0);
    // hit_u, hit_v: differences of terms of size t and |P - c|.
    const double toCenter = std::sqrt(std::pow(r.P[0] - uniforms.center[0], 2) +
      std::pow(r.P[1] - uniforms.center[1], 2) + std::pow(r.P[2] - uniforms.center[2], 2));
    const double hitFloor = Relative * (lobe.distance + toCenter);
    o.Values = { lobe.peak, lobe.tan_half, lobe.distance, lobe.width, lobe.hit_u, lobe.hit_v,
      lobe.inverse_distance, lobe.reflect[0], lobe.reflect[1], lobe.reflect[2] };
    o.Floors = { 1e-7, 0, 0, 0, hitFloor, hitFloor, 0, 1e-6, 1e-6, 1e-6 };
    return o;
  };
  auto refinement = [&](const Receiver& r) {
    Outcome o;
    mrgi_area_light_lobe lobe;
    mrgi_area_light_phong_lobe(&uniforms, r.P, r.N, r.V, r.Power, &lobe);
    o.Values = { mrgi_area_light_phong_refinement(&lobe, r.EyeDistance, r.TexelSize) };
    o.Floors = { 0 };
    return o;
  };

  CaseResult result;
  Tally tSpecular, tCounts, tLobe, tRefinement, tLookups;
  size_t pathFlips = 0;
  size_t paths[5] = { 0, 0, 0, 0, 0 };
  double maxError = 0, maxBound = 0;
  for (int i = 0; i < Count; ++i)
  {
    const Receiver& r = receivers[i];
    const float* o0 = &out[0][4 * i];
    const float* o1 = &out[1][4 * i];
    const float* o2 = &out[2][4 * i];
    const float* o3 = &out[3][4 * i];
    const float* o4 = &out[4][4 * i];
    const unsigned seed = static_cast<unsigned>(i) + 1000u * c.Seed;

    // S and its path.
    const Outcome sTwin = specular(r);
    const int gpuPath = static_cast<int>(std::lround(o0[3]));
    MRGI_TEST_CHECK(gpuPath >= 0 && gpuPath < 5);
    ++paths[sTwin.Key];
    const double gpuS[3] = { o0[0], o0[1], o0[2] };
    const bool sAgrees = Agrees(gpuPath, gpuS, sTwin);
    const bool inPlane = InPlane(uniforms, r);
    const bool sExplained =
      !sAgrees && (inPlane || WithinRounding(r, gpuPath, gpuS, specular, seed));
    tSpecular.Add(sAgrees, inPlane, sExplained);
    pathFlips += gpuPath != sTwin.Key;
    if (sAgrees)
    {
      for (int k = 0; k < 3; ++k)
      {
        const double e = std::fabs(gpuS[k] - sTwin.Values[k]);
        maxBound = std::max(maxBound, e / (Relative * std::fabs(sTwin.Values[k]) + floor));
        if (sTwin.Values[k] > 1e-3 * peak)
        {
          maxError = std::max(maxError, e / sTwin.Values[k]);
        }
      }
    }
    else if (!sExplained && tSpecular.Other() <= 5)
    {
      std::printf("    unexplained #%d: P (%.9g %.9g %.9g) N (%.9g %.9g %.9g) V (%.9g %.9g "
                  "%.9g) n %.9g | twin %s S (%.9g %.9g %.9g) | GPU %s S (%.9g %.9g %.9g) "
                  "counts %g\n",
        i, r.P[0], r.P[1], r.P[2], r.N[0], r.N[1], r.N[2], r.V[0], r.V[1], r.V[2],
        static_cast<double>(r.Power), PathNames[sTwin.Key], sTwin.Values[0], sTwin.Values[1],
        sTwin.Values[2], PathNames[gpuPath], o0[0], o0[1], o0[2], static_cast<double>(o3[3]));
    }
    // The counts behind the path (not written by the wrapper).
    if (!wrapper)
    {
      const Outcome cTwin = counts(r);
      const int gpuKey = gpuPath * 1000000 + static_cast<int>(std::lround(o3[3]));
      const bool agrees = gpuKey == cTwin.Key;
      const bool explained =
        !agrees && (inPlane || WithinRounding(r, gpuKey, nullptr, counts, seed));
      tCounts.Add(agrees, inPlane, explained);
      if (!agrees && !explained && tCounts.Other() <= 3)
      {
        std::printf("    counts #%d n %.9g: GPU path %d counts %g | twin key %d (path %d)\n", i,
          static_cast<double>(r.Power), gpuPath, static_cast<double>(o3[3]), cTwin.Key,
          cTwin.Key / 1000000);
      }
    }
    // The lobe, called directly on every receiver.
    {
      const Outcome lTwin = lobeOf(r);
      const double gpuLobe[10] = { o1[0], o1[1], o1[2], o1[3], o2[0], o2[1], o4[3], o3[0], o3[1],
        o3[2] };
      const int gpuFlags = static_cast<int>(std::lround(o2[2]));
      const bool agrees = Agrees(gpuFlags, gpuLobe, lTwin);
      const bool explained =
        !agrees && (inPlane || WithinRounding(r, gpuFlags, gpuLobe, lobeOf, seed));
      tLobe.Add(agrees, inPlane, explained);
      if (!agrees && !explained && tLobe.Other() <= 5)
      {
        std::printf("    lobe #%d n %.9g: GPU/twin peak %.9g/%.9g tan %.9g/%.9g t %.9g/%.9g "
                    "width %.9g/%.9g hit %.9g/%.9g %.9g/%.9g flags %d/%d\n",
          i, static_cast<double>(r.Power), gpuLobe[0], lTwin.Values[0], gpuLobe[1],
          lTwin.Values[1], gpuLobe[2], lTwin.Values[2], gpuLobe[3], lTwin.Values[3], gpuLobe[4],
          lTwin.Values[4], gpuLobe[5], lTwin.Values[5], gpuFlags, lTwin.Key);
      }
    }
    {
      const Outcome mTwin = refinement(r);
      const double gpuM = o2[3];
      const bool agrees = Agrees(0, &gpuM, mTwin);
      tRefinement.Add(agrees, inPlane,
        !agrees && (inPlane || WithinRounding(r, 0, &gpuM, refinement, seed)));
    }
    // The direct pyramid lookup: no rounding allowance.
    float texel[3];
    mrgi_area_light_texture_sample(lookup, r.S, r.T, r.Lod, texel);
    bool textureOK = true;
    for (int k = 0; k < 3; ++k)
    {
      textureOK = textureOK && Close(o4[k], texel[k], 1e-7 * texelPeak);
    }
    tLookups.Add(textureOK, false, false);
    if (!textureOK && tLookups.Differ <= 4)
    {
      std::printf("    lookup #%d (s %.9g t %.9g lod %.9g): GPU %.9g %.9g %.9g twin %.9g %.9g %.9g\n",
        i, static_cast<double>(r.S), static_cast<double>(r.T), static_cast<double>(r.Lod), o4[0],
        o4[1], o4[2], texel[0], texel[1], texel[2]);
    }

    // Twins that must fail: a perturbed power; no pyramid on a textured light.
    const float* S = &o0[0];
    const bool lit = sTwin.Values[0] > 1e-3 * peak || sTwin.Values[1] > 1e-3 * peak ||
      sTwin.Values[2] > 1e-3 * peak;
    if (lit && r.Power > 0.5f)
    {
      ++result.Lit;
      float wrongS[3];
      TwinSpecular(twin, r, r.Power * 1.05f + 0.05f, wrongS, nullptr);
      result.WrongPower += !SClose(S, wrongS, floor);
    }
    if (lit && pyramid && sTwin.Key == MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID)
    {
      ++result.GridLit;
      const Twin untextured = { &uniforms, samples, count, nullptr };
      float wrongS[3];
      TwinSpecular(untextured, r, r.Power, wrongS, nullptr);
      result.WrongPyramid += !SClose(S, wrongS, floor);
    }
  }
  result.Mismatch = tSpecular.Differ;
  const double n = static_cast<double>(Count);
  std::printf("%-42s %3d samples %3dx%-3d | paths:", c.Name, count, lookup->width[0],
    lookup->height[0]);
  for (int p = 0; p < 5; ++p)
  {
    std::printf(" %s %.1f%%", PathNames[p], 100.0 * paths[p] / n);
  }
  std::printf("\n  path differs: %zu = %.3f%%; S or path differ: %zu = %.3f%% (%zu in the plane, %zu other boundary, %zu "
              "unexplained); where they agree: max rel. error %.2g (S > 1e-3 peak), max error "
              "/ bound %.2g\n  differ:",
    pathFlips, 100.0 * pathFlips / n, tSpecular.Differ, 100.0 * tSpecular.Differ / n, tSpecular.InPlane,
    tSpecular.Explained - tSpecular.InPlane, tSpecular.Other(), maxError, maxBound);
  PrintTally("counts", tCounts);
  PrintTally("lobe", tLobe);
  PrintTally("refinement", tRefinement);
  std::printf(" lookups %zu\n", tLookups.Differ);
  std::fflush(stdout);

  // The receivers exercise the function: both computing paths occur.
  MRGI_TEST_CHECK(paths[MRGI_AREA_LIGHT_SPECULAR_SAMPLES] > Count / 50);
  MRGI_TEST_CHECK(paths[MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID] > Count / 100);
  for (const Tally* t : { &tSpecular, &tCounts, &tLobe, &tRefinement })
  {
    MRGI_TEST_CHECK(t->Other() <= MaxUnexplainedRate * n);
  }
  // S and its path: under 0.5% differ, boundary cases included. The lobe,
  // the counts and the refinement metric are ill-conditioned where S is
  // not: for receivers in (or a rounding error off) the light's plane (5%
  // of them by construction; early-out 1's boundary), t = (c - P).n / R.n
  // is a ratio of rounding noise, and so are width, hit point and metric,
  // and every sample is seen edge-on, so which ones count is noise (S is ~0
  // either way); for reflections grazing the plane R.n is a cancellation.
  // Their disagreements must all be explained, and stay under 5%.
  // Paths: under 0.5% differ (early-out 1 in the plane, the discard
  // threshold, the lobe count at the cutoff). S beyond the bound where the
  // paths agree: only ill-conditioned receivers, all within the twin's own
  // rounding sensitivity (mostly a hair above the light, where the lobe
  // grid's cell-to-receiver vector c + u_a u + v_b v - P is a cancellation
  // of O(1) terms into O(1e-4)), under 2% with the path flips.
  MRGI_TEST_CHECK(pathFlips < MaxRate * n);
  MRGI_TEST_CHECK(tSpecular.Differ < 4 * MaxRate * n);
  for (const Tally* t : { &tSpecular, &tCounts, &tLobe, &tRefinement })
  {
    MRGI_TEST_CHECK(t->Other() <= MaxUnexplainedRate * n);
    MRGI_TEST_CHECK(t->Differ < 10 * MaxRate * n);
  }
  MRGI_TEST_CHECK(tLookups.Differ == 0);
  totals.Receivers += Count;
  totals.PathFlips += pathFlips;
  for (auto pair : { std::make_pair(&totals.Specular, &tSpecular),
         std::make_pair(&totals.Counts, &tCounts), std::make_pair(&totals.Lobe, &tLobe),
         std::make_pair(&totals.Refinement, &tRefinement),
         std::make_pair(&totals.Lookups, &tLookups) })
  {
    pair.first->Differ += pair.second->Differ;
    pair.first->Explained += pair.second->Explained;
    pair.first->InPlane += pair.second->InPlane;
  }
  totals.MaxError = std::max(totals.MaxError, maxError);
  totals.MaxBound = std::max(totals.MaxBound, maxBound);
  for (int p = 0; p < 5; ++p)
  {
    totals.Paths[p] += paths[p];
  }
  light->ReleaseGraphicsResources(window);
  return result;
}

// The GPU resources: uploaded once per rebuild, the mip levels as the core's
// pyramid, released on request; sources and error handling.
void Api(vtkOpenGLRenderWindow* window)
{
  const std::string specular = vtkMRGIAreaLight::GetSpecularShaderSource();
  MRGI_TEST_CHECK(specular.find("vec3 mrgiAreaLightSpecular(") != std::string::npos);
  MRGI_TEST_CHECK(specular.find("void main") == std::string::npos);
  MRGI_TEST_CHECK(specular.find("\n#version") == std::string::npos && specular.rfind("#version", 0) == std::string::npos);
  const std::string both = vtkMRGIAreaLight::GetShaderSource(true, true);
  MRGI_TEST_CHECK(both.find("MRGI_AREA_LIGHT_DIFFUSE_DECLARED") != std::string::npos);
  MRGI_TEST_CHECK(both.find("mrgiAreaLightDiffuse(") < both.find("mrgiAreaLightSpecular("));
  MRGI_TEST_CHECK(vtkMRGIAreaLight::GetShaderSource(false, true) == specular);
  {
    // The specular library alone compiles (it declares the shared uniforms).
    const std::string fs = ShaderSource(specular);
    vtkOpenGLQuadHelper quad(
      window, vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), fs.c_str(), "");
    MRGI_TEST_CHECK(quad.Program && quad.Program->GetCompiled());
  }

  vtkNew<vtkMRGIAreaLight> light;
  vtkNew<mrgitest::ErrorCatcher> errors;
  light->AddObserver(vtkCommand::ErrorEvent, errors);
  MRGI_TEST_CHECK(!light->GetPyramidTexture(nullptr));
  MRGI_TEST_CHECK(errors->Caught("no window"));
  MRGI_TEST_CHECK(!light->SetShaderUniforms(nullptr, window));
  MRGI_TEST_CHECK(errors->Caught("no shader program"));

  // Untextured: a 1 x 1 texture, uploaded once.
  vtkTextureObject* tex = light->GetPyramidTexture(window);
  MRGI_TEST_CHECK(tex && tex->GetWidth() == 1 && tex->GetHeight() == 1);
  MRGI_TEST_CHECK(light->GetNumberOfPyramidUploads() == 1);
  MRGI_TEST_CHECK(light->GetPyramidTexture(window) == tex);
  MRGI_TEST_CHECK(light->GetNumberOfPyramidUploads() == 1);

  // A texture: a new upload, with every level (MAX_LEVEL = levels - 1).
  vtkSmartPointer<vtkImageData> image = MakeTexture(37, 23, 5);
  light->SetTextureData(image);
  tex = light->GetPyramidTexture(window);
  const mrgi_area_light_texture_pyramid* pyramid = nullptr;
  MRGI_TEST_CHECK(light->GetCorePyramid(&pyramid) && pyramid);
  MRGI_TEST_CHECK(tex && tex->GetWidth() == 37 && tex->GetHeight() == 23);
  MRGI_TEST_CHECK(tex->GetMaxLevel() == pyramid->level_count - 1 && pyramid->level_count == 6);
  MRGI_TEST_CHECK(light->GetNumberOfPyramidUploads() == 2);
  // Geometry changes rebuild the samples, not the pyramid.
  int count = 0;
  MRGI_TEST_CHECK(light->GetSampleTexture(window, &count) && count == 256);
  MRGI_TEST_CHECK(light->GetNumberOfSampleUploads() == 1);
  MRGI_TEST_CHECK(light->GetSampleTexture(window) && light->GetNumberOfSampleUploads() == 1);
  light->SetCenter(1, 2, 3);
  MRGI_TEST_CHECK(light->GetSampleTexture(window) && light->GetNumberOfSampleUploads() == 2);
  MRGI_TEST_CHECK(light->GetPyramidTexture(window) == tex);
  MRGI_TEST_CHECK(light->GetNumberOfPyramidUploads() == 2);
  // The next video frame: one rebuild, one upload, however often asked.
  const int builds = light->GetNumberOfTextureBuilds();
  image->Modified();
  MRGI_TEST_CHECK(light->GetPyramidTexture(window) && light->GetPyramidTexture(window));
  MRGI_TEST_CHECK(light->GetNumberOfTextureBuilds() == builds + 1);
  MRGI_TEST_CHECK(light->GetNumberOfPyramidUploads() == 3);
  // Released: handles gone, the next request uploads again.
  light->ReleaseGraphicsResources(window);
  tex = light->GetPyramidTexture(window);
  MRGI_TEST_CHECK(tex && tex->GetHandle() != 0 && light->GetNumberOfPyramidUploads() == 4);
  // An invalid light: errors, no texture.
  light->SetEdgeV(1, 0, 0);
  MRGI_TEST_CHECK(!light->GetSampleTexture(window));
  MRGI_TEST_CHECK(errors->Caught("EdgeV"));
  light->SetEdgeV(0, 1, 0);
  MRGI_TEST_CHECK(light->GetSampleTexture(window));
  MRGI_TEST_CHECK(errors->Count == 0);
  light->ReleaseGraphicsResources(window);
}
}

int main()
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(64, 48);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  window->Render();
  vtkOpenGLRenderWindow* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  MRGI_TEST_CHECK(gl);
  Api(gl);

  GPUSpecular gpu(gl);
  const LightCase cases[] = {
    { "untextured one-sided, axis-aligned", 0, 0, false, 16, false, true, 11 },
    { "untextured two-sided", 0, 0, true, 256, false, false, 12 },
    { "textured 37x23 one-sided", 37, 23, false, 256, false, false, 13 },
    { "textured 64x64 two-sided, jittered", 64, 64, true, 16, true, false, 14 },
    { "textured 128x40 one-sided", 128, 40, false, 16, false, false, 15 },
    { "textured 5x1 two-sided, axis-aligned", 5, 1, true, 256, false, true, 16 },
    { "untextured one-sided, jittered", 0, 0, false, 256, true, false, 17 },
    { "untextured two-sided", 0, 0, true, 16, false, false, 18 },
  };
  size_t lit = 0, wrongPower = 0, gridLit = 0, wrongPyramid = 0, parity = 0;
  for (const LightCase& c : cases)
  {
    const CaseResult r = RunCase(c, gl, gpu);
    lit += r.Lit;
    wrongPower += r.WrongPower;
    gridLit += r.GridLit;
    wrongPyramid += r.WrongPyramid;
    parity += r.Mismatch;
  }
  // The wrapper mrgiAreaLightSpecular() gives the same S and paths.
  RunCase({ "textured 37x23 one-sided (wrapper)", 37, 23, false, 256, false, false, 13 }, gl, gpu,
    true);

  std::printf("all cases: %zu receivers | paths:", totals.Receivers);
  for (int p = 0; p < 5; ++p)
  {
    std::printf(" %s %zu", PathNames[p], totals.Paths[p]);
  }
  std::printf("\n  path differs: %zu = %.4f%%; S or path differ: %zu = %.4f%% (%zu in the plane, %zu other boundary, %zu "
              "unexplained); where they agree: max rel. error %.2g (S > 1e-3 peak), max error "
              "/ bound %.2g (bound %g relative + %g x peak)\n  differ:",
    totals.PathFlips, 100.0 * totals.PathFlips / totals.Receivers, totals.Specular.Differ, 100.0 * totals.Specular.Differ / totals.Receivers,
    totals.Specular.InPlane, totals.Specular.Explained - totals.Specular.InPlane,
    totals.Specular.Other(), totals.MaxError, totals.MaxBound, Relative, Floor);
  PrintTally("counts", totals.Counts);
  PrintTally("lobe", totals.Lobe);
  PrintTally("refinement", totals.Refinement);
  std::printf(" lookups %zu\n", totals.Lookups.Differ);
  std::printf("twin with power x 1.05 + 0.05: %zu of %zu lit receivers differ (%.1f%%; parity: "
              "%zu of all)\n",
    wrongPower, lit, 100.0 * wrongPower / std::max<size_t>(lit, 1), parity);
  std::printf("twin without the pyramid (textured lights): %zu of %zu lit lobe-grid receivers "
              "differ (%.1f%%)\n",
    wrongPyramid, gridLit, 100.0 * wrongPyramid / std::max<size_t>(gridLit, 1));
  MRGI_TEST_CHECK(totals.Paths[MRGI_AREA_LIGHT_SPECULAR_BEHIND] > totals.Receivers / 200);
  MRGI_TEST_CHECK(totals.Paths[MRGI_AREA_LIGHT_SPECULAR_FACING_AWAY] > totals.Receivers / 200);
  MRGI_TEST_CHECK(totals.Paths[MRGI_AREA_LIGHT_SPECULAR_LOBE_MISS] > totals.Receivers / 200);
  // The comparison can fail: both wrong twins far beyond the parity bound.
  MRGI_TEST_CHECK(lit > 1000 && wrongPower > 0.2 * lit && wrongPower > 20 * (parity + 10));
  MRGI_TEST_CHECK(gridLit > 100 && wrongPyramid > 0.5 * gridLit);
  gl->MakeCurrent();
  return 0;
}
