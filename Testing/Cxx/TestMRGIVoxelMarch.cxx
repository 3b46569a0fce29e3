// The GPU ray march through the screen-space voxels (vtkMRGIVoxelMarch.glsl,
// naive voxel-space visibility of nichols-penmatsa-wyman-2010 section
// 3.3.1) against its C twin (mrgi_voxel_march() and
// mrgi_voxel_march_occluder_fraction(), mrgi_voxel_march.h) on the same
// rays and the same voxels: the scene is voxelized on the GPU
// (vtkMRGIVoxelization), the buffer is read back for the twin, and the
// GLSL runs once per ray in a full-screen pass whose fragment i reads ray i
// from an RGBA32F texture and writes (visible, occluder fraction), with its
// uniforms set by vtkMRGIVoxelization::SetMarchUniforms().
//
// Rays: receivers on the scene's surfaces (normals facing the viewer, as the
// G-buffer's) or anywhere around the frustum with random normals; light
// samples on surfaces, inside the frustum, behind the camera, beyond far,
// off screen; zero-length and very short segments, grazing and non-unit
// normals, missing normals. Cases: the Cornell box and random boxes,
// perspective and parallel, voxel buffers of 128^2, NPOT 97x61 and 1x1,
// default knobs, no bias at all, a binding step cap.
//
// What may differ (mrgi_voxel_march.h "Precision"): rays on which a step's
// middle, a depth or a clip parameter lies within float rounding of a pixel
// or slice boundary (GLSL's division, 1/d and sqrt need not round as C's).
// Every disagreement is classified: "boundary" when the twin itself gives the
// GPU's answer once the ray's inputs move by a few float ulps (relative
// 2e-7 .. 4e-6). Disagreements must stay under 0.5% of the rays that are
// really marched (not decided by the horizon or zero-length tests), those
// not explained as boundary cases under 0.05%, and occluder fractions that
// differ by more than 1e-4 under 0.5%. (On llvmpipe every case agrees
// exactly: no disagreement at all; a skip box test off by one in the GLSL
// gives 0.16-0.7% disagreements, most of them unexplained.) A twin with a
// deliberately wrong normal offset or skip radius must fail the same bound.
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"
#include "mrgiVoxelTestUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMRGIVoxelization.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPixelBufferObject.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSphereSource.h"
#include "vtkTextureObject.h"
#include "vtkTriangleFilter.h"
#include "vtkTypeUInt32Array.h"
#include "vtk_glew.h"

#include "mrgi_glsl_defines.h"
#include "mrgi_voxel.h"
#include "mrgi_voxel_march.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace
{
using mrgitest::DepthRange;
using mrgitest::MakeActor;
using mrgitest::SceneTriangles;
using mrgitest::Triangle;
// ---------------------------------------------------------------------------
// Scenes as eye-space triangles (for sampling receivers and light samples on
// surfaces; the voxels themselves come from the GPU).
// ---------------------------------------------------------------------------
// Rays: P, Np, L, Nl (eye space; a zero normal is "none").
struct Ray
{
  float P[3], Np[3], L[3], Nl[3];
};

class Sampler
{
public:
  Sampler(const std::vector<Triangle>& tris, const mrgi_voxel_grid& grid,
    const mrgi_voxel_projection& proj, unsigned seed)
    : Tris(tris)
    , Grid(grid)
    , Proj(proj)
    , Rng(seed)
  {
    double total = 0;
    for (const Triangle& t : tris)
    {
      double e1[3], e2[3], c[3];
      for (int k = 0; k < 3; ++k)
      {
        e1[k] = t[3 + k] - t[k];
        e2[k] = t[6 + k] - t[k];
      }
      Cross(e1, e2, c);
      total += 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
      this->Cumulative.push_back(total);
    }
  }

  double Uniform(double lo, double hi)
  {
    return lo + (hi - lo) * (static_cast<double>(this->Rng() >> 5) / 134217728.0);
  }

  // A point on the surfaces (area-weighted) and its normal facing the viewer.
  void Surface(float p[3], float n[3])
  {
    const double r = this->Uniform(0, this->Cumulative.back());
    const size_t i = std::min(this->Tris.size() - 1,
      static_cast<size_t>(std::upper_bound(this->Cumulative.begin(), this->Cumulative.end(), r) -
        this->Cumulative.begin()));
    const Triangle& t = this->Tris[i];
    double a = this->Uniform(0, 1), b = this->Uniform(0, 1);
    if (a + b > 1)
    {
      a = 1 - a;
      b = 1 - b;
    }
    double e1[3], e2[3], c[3], q[3];
    for (int k = 0; k < 3; ++k)
    {
      e1[k] = t[3 + k] - t[k];
      e2[k] = t[6 + k] - t[k];
      q[k] = t[k] + a * e1[k] + b * e2[k];
    }
    Cross(e1, e2, c);
    // Facing the viewer: towards the eye (perspective) or +z (parallel).
    const double facing = this->Proj.parallel ? c[2] : -(c[0] * q[0] + c[1] * q[1] + c[2] * q[2]);
    const double len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const double s = (facing < 0 ? -1.0 : 1.0) / (len > 0 ? len : 1.0);
    for (int k = 0; k < 3; ++k)
    {
      p[k] = static_cast<float>(q[k]);
      n[k] = static_cast<float>(c[k] * s);
    }
  }

  // A point of normalized device coordinates (x, y) at linear depth d.
  void Unproject(double nx, double ny, double d, float p[3])
  {
    const double w = this->Proj.parallel ? 1.0 : d;
    p[0] = static_cast<float>((nx - this->Proj.offset_x) * w / this->Proj.scale_x);
    p[1] = static_cast<float>((ny - this->Proj.offset_y) * w / this->Proj.scale_y);
    p[2] = static_cast<float>(-d);
  }

  double Range() const { return static_cast<double>(this->Grid.far_depth) - this->Grid.near_depth; }

  // Around the frustum: a little beyond the screen and [near, far].
  void Frustum(float p[3])
  {
    const double n = this->Grid.near_depth, r = this->Range();
    const double lo = this->Proj.parallel ? n - 0.1 * r : std::max(0.5 * n, n - 0.1 * r);
    this->Unproject(
      this->Uniform(-1.2, 1.2), this->Uniform(-1.2, 1.2), this->Uniform(lo, n + 1.1 * r), p);
  }

  // Outside the frustum: behind the camera, beyond far, or off the screen.
  void Outside(float p[3])
  {
    const double n = this->Grid.near_depth, f = this->Grid.far_depth, r = this->Range();
    const int which = static_cast<int>(this->Uniform(0, 3));
    if (which == 0)
    {
      // Behind the eye (perspective) or in front of near (parallel).
      const double d = this->Proj.parallel ? this->Uniform(n - r, n) : -this->Uniform(0.01, 1.0) * r;
      const double spread = this->Proj.parallel ? 1.5 : 1.5 * (n + r);
      p[0] = static_cast<float>(this->Uniform(-spread, spread) / this->Proj.scale_x);
      p[1] = static_cast<float>(this->Uniform(-spread, spread) / this->Proj.scale_y);
      p[2] = static_cast<float>(-d);
    }
    else if (which == 1)
    {
      this->Unproject(this->Uniform(-1, 1), this->Uniform(-1, 1), this->Uniform(f, f + r), p);
    }
    else
    {
      const double side = this->Uniform(1.05, 3.0) * (this->Uniform(0, 1) < 0.5 ? -1 : 1);
      const double other = this->Uniform(-1.5, 1.5);
      const double d = this->Uniform(n, f);
      if (this->Uniform(0, 1) < 0.5)
      {
        this->Unproject(side, other, d, p);
      }
      else
      {
        this->Unproject(other, side, d, p);
      }
    }
  }

  void Direction(float v[3])
  {
    double d[3], l2;
    do
    {
      for (double& c : d)
      {
        c = this->Uniform(-1, 1);
      }
      l2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    } while (l2 > 1 || l2 < 1e-4);
    for (int k = 0; k < 3; ++k)
    {
      v[k] = static_cast<float>(d[k] / std::sqrt(l2));
    }
  }

  // A unit normal nearly perpendicular to `dir` (grazing), tilted by eps
  // towards `dir` (eps 0: exactly perpendicular in double, rounded to float).
  void Grazing(const double dir[3], double eps, float n[3])
  {
    float r[3];
    this->Direction(r);
    const double dl = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    double u[3] = { dir[0] / dl, dir[1] / dl, dir[2] / dl };
    const double along = r[0] * u[0] + r[1] * u[1] + r[2] * u[2];
    double t[3];
    for (int k = 0; k < 3; ++k)
    {
      t[k] = r[k] - along * u[k];
    }
    const double tl = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int k = 0; k < 3; ++k)
    {
      n[k] = static_cast<float>(t[k] / (tl > 0 ? tl : 1) + eps * u[k]);
    }
  }

  Ray Next()
  {
    Ray ray;
    std::memset(&ray, 0, sizeof(ray));
    const double kind = this->Uniform(0, 1);
    float scratch[3];
    if (kind < 0.30) // surface to surface (the gather's rays)
    {
      this->Surface(ray.P, ray.Np);
      this->Surface(ray.L, ray.Nl);
      if (this->Uniform(0, 1) < 0.5)
      {
        for (float& c : ray.Nl)
        {
          c = -c; // an emitter facing away from the viewer
        }
      }
    }
    else if (kind < 0.45) // surface to a point around the frustum
    {
      this->Surface(ray.P, ray.Np);
      this->Frustum(ray.L);
      if (this->Uniform(0, 1) < 0.5)
      {
        this->Direction(ray.Nl);
      }
    }
    else if (kind < 0.55) // surface to a point outside the frustum
    {
      this->Surface(ray.P, ray.Np);
      this->Outside(ray.L);
      if (this->Uniform(0, 1) < 0.5)
      {
        this->Direction(ray.Nl);
      }
      if (this->Uniform(0, 1) < 0.3)
      {
        std::swap(ray.P, ray.L);
        std::swap(ray.Np, ray.Nl);
      }
    }
    else if (kind < 0.70) // anywhere to anywhere, random or no normals
    {
      this->Frustum(ray.P);
      this->Frustum(ray.L);
      if (this->Uniform(0, 1) < 0.75)
      {
        this->Direction(ray.Np);
      }
      if (this->Uniform(0, 1) < 0.75)
      {
        this->Direction(ray.Nl);
      }
    }
    else if (kind < 0.75) // zero-length segments
    {
      this->Surface(ray.P, ray.Np);
      std::copy(ray.P, ray.P + 3, ray.L);
      if (this->Uniform(0, 1) < 0.5)
      {
        this->Direction(ray.Nl);
      }
      if (this->Uniform(0, 1) < 0.3)
      {
        std::fill(ray.Np, ray.Np + 3, 0.0f);
      }
    }
    else if (kind < 0.85) // grazing normals at either end
    {
      this->Surface(ray.P, scratch);
      this->Frustum(ray.L);
      const double dir[3] = { static_cast<double>(ray.L[0]) - ray.P[0],
        static_cast<double>(ray.L[1]) - ray.P[1], static_cast<double>(ray.L[2]) - ray.P[2] };
      static const double tilts[] = { 0.0, 1e-7, -1e-7, 1e-5, -1e-5, 1e-3, -1e-3, 3e-2 };
      const int pick = static_cast<int>(this->Uniform(0, 8));
      if (this->Uniform(0, 1) < 0.7)
      {
        this->Grazing(dir, tilts[pick], ray.Np);
      }
      else
      {
        std::copy(scratch, scratch + 3, ray.Np);
        const double back[3] = { -dir[0], -dir[1], -dir[2] };
        this->Grazing(back, tilts[pick], ray.Nl);
      }
    }
    else if (kind < 0.90) // very short segments
    {
      this->Surface(ray.P, ray.Np);
      float dir[3];
      this->Direction(dir);
      const double vs = 2.0 * std::fabs(ray.P[2]) / (this->Proj.scale_y * this->Grid.height);
      const double len = vs * std::pow(10.0, this->Uniform(-6, 0.5));
      for (int k = 0; k < 3; ++k)
      {
        ray.L[k] = static_cast<float>(ray.P[k] + len * dir[k]);
      }
      if (this->Uniform(0, 1) < 0.5)
      {
        this->Direction(ray.Nl);
      }
    }
    else // surface to surface, non-unit normals
    {
      this->Surface(ray.P, ray.Np);
      this->Surface(ray.L, ray.Nl);
      const float a = static_cast<float>(std::pow(10.0, this->Uniform(-3, 3)));
      const float b = static_cast<float>(std::pow(10.0, this->Uniform(-3, 3)));
      for (int k = 0; k < 3; ++k)
      {
        ray.Np[k] *= a;
        ray.Nl[k] *= -b;
      }
    }
    return ray;
  }

private:
  static void Cross(const double a[3], const double b[3], double c[3])
  {
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
  }

  const std::vector<Triangle>& Tris;
  std::vector<double> Cumulative;
  mrgi_voxel_grid Grid;
  mrgi_voxel_projection Proj;
  std::mt19937 Rng;
};

// Whether the march really runs (not decided by the zero-length or horizon
// tests, steps 1-2), computed as the twin does.
bool Marched(const Ray& r)
{
  const float D[3] = { r.L[0] - r.P[0], r.L[1] - r.P[1], r.L[2] - r.P[2] };
  auto dot = [](const float* a, const float* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  if (dot(D, D) == 0.0f)
  {
    return false;
  }
  if (dot(r.Np, r.Np) > 0.0f && dot(r.Np, D) <= 0.0f)
  {
    return false;
  }
  if (dot(r.Nl, r.Nl) > 0.0f && dot(r.Nl, D) >= 0.0f)
  {
    return false;
  }
  return true;
}

// ---------------------------------------------------------------------------
// The GPU side: one fragment per ray.
const int RaysW = 512;
const int RaysH = 256;
const int RayCount = RaysW * RaysH;

const char* const MarchTestBody = R"(
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; rays are addressed by gl_FragCoord
uniform sampler2D mrgiRays; // 3 RGBA32F texels per ray: (P, Np.x) (Np.yz, L.xy) (L.z, Nl)
//VTK::Output::Dec
void main()
{
  if (texCoord.x < -1.0) { discard; } // never true: keeps texCoord alive
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 t0 = texelFetch(mrgiRays, ivec2(3 * p.x, p.y), 0);
  vec4 t1 = texelFetch(mrgiRays, ivec2(3 * p.x + 1, p.y), 0);
  vec4 t2 = texelFetch(mrgiRays, ivec2(3 * p.x + 2, p.y), 0);
  vec3 P = t0.xyz;
  vec3 Np = vec3(t0.w, t1.xy);
  vec3 L = vec3(t1.zw, t2.x);
  vec3 Nl = t2.yzw;
  float visible = mrgiVoxelVisible(P, Np, L, Nl) ? 1.0 : 0.0;
  float fraction = mrgiVoxelOccluderFraction(P, Np, L, Nl);
  gl_FragData[0] = vec4(visible, fraction, 0.0, 1.0);
}
)";

std::string CoreDefines()
{
  std::vector<char> buffer(mrgi_glsl_defines_size());
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_glsl_defines(buffer.data(), buffer.size(), nullptr, &err) == MRGI_OK);
  return std::string(buffer.data());
}

class GPUMarch
{
public:
  explicit GPUMarch(vtkOpenGLRenderWindow* window)
    : Window(window)
  {
    window->MakeCurrent();
    const std::string fs = std::string("//VTK::System::Dec\n") + CoreDefines() +
      vtkMRGIVoxelization::GetMarchShaderSource() + MarchTestBody;
    this->Quad = new vtkOpenGLQuadHelper(window,
      vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), fs.c_str(), "");
    MRGI_TEST_CHECK(this->Quad->Program && this->Quad->Program->GetCompiled());
    this->Rays->SetContext(window);
    this->Rays->SetInternalFormat(GL_RGBA32F);
    this->Rays->SetFormat(GL_RGBA);
    this->Rays->SetDataType(GL_FLOAT);
    this->Rays->SetMinificationFilter(vtkTextureObject::Nearest);
    this->Rays->SetMagnificationFilter(vtkTextureObject::Nearest);
    this->Output->SetContext(window);
    this->Output->SetInternalFormat(GL_RGBA32F);
    this->Output->SetFormat(GL_RGBA);
    this->Output->SetDataType(GL_FLOAT);
    this->Output->SetMinificationFilter(vtkTextureObject::Nearest);
    this->Output->SetMagnificationFilter(vtkTextureObject::Nearest);
    MRGI_TEST_CHECK(this->Output->Allocate2D(RaysW, RaysH, 4, VTK_FLOAT));
    this->Fbo->SetContext(window);
  }

  ~GPUMarch()
  {
    this->Window->MakeCurrent();
    delete this->Quad;
    this->Rays->ReleaseGraphicsResources(this->Window);
    this->Output->ReleaseGraphicsResources(this->Window);
    this->Fbo->ReleaseGraphicsResources(this->Window);
  }

  // (visible, fraction) per ray; objectKnobs: SetMarchUniforms(program)
  // with the object's MaxSteps, NormalOffset and SkipRadius, not `params`.
  void Run(vtkMRGIVoxelization* vox, const mrgi_voxel_march_params& params, bool objectKnobs,
    const std::vector<Ray>& rays, std::vector<float>& out)
  {
    MRGI_TEST_CHECK(static_cast<int>(rays.size()) == RayCount);
    vtkOpenGLRenderWindow* window = this->Window;
    window->MakeCurrent();
    MRGI_TEST_CHECK(this->Rays->Create2DFromRaw(3 * RaysW, RaysH, 4, VTK_FLOAT,
      const_cast<float*>(&rays[0].P[0])));
    window->GetShaderCache()->ReadyShaderProgram(this->Quad->Program);
    vtkShaderProgram* program = this->Quad->Program;
    MRGI_TEST_CHECK(
      objectKnobs ? vox->SetMarchUniforms(program) : vox->SetMarchUniforms(program, params));
    this->Rays->Activate();
    program->SetUniformi("mrgiRays", this->Rays->GetTextureUnit());

    vtkOpenGLState* ostate = window->GetState();
    out.assign(static_cast<size_t>(RayCount) * 4, -1.0f);
    {
      vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
      vtkOpenGLState::ScopedglEnableDisable depth(ostate, GL_DEPTH_TEST);
      vtkOpenGLState::ScopedglViewport viewport(ostate);
      ostate->vtkglDisable(GL_BLEND);
      ostate->vtkglDisable(GL_DEPTH_TEST);
      this->Fbo->SaveCurrentBindingsAndBuffers();
      this->Fbo->Bind();
      this->Fbo->AddColorAttachment(0, this->Output);
      this->Fbo->ActivateDrawBuffers(1);
      const char* status = nullptr;
      MRGI_TEST_CHECK(vtkOpenGLFramebufferObject::GetFrameBufferStatus(GL_FRAMEBUFFER, status));
      ostate->vtkglViewport(0, 0, RaysW, RaysH);
      this->Quad->Render();
      // Read back through VTK (a pixel buffer object): no GL entry points
      // in the test, which links no GL library of its own.
      this->Fbo->ActivateReadBuffer(0);
      int extent[4] = { 0, RaysW - 1, 0, RaysH - 1 };
      vtkPixelBufferObject* pbo = this->Fbo->DownloadColor4(extent, VTK_FLOAT);
      MRGI_TEST_CHECK(pbo);
      const float* mapped = static_cast<const float*>(pbo->MapPackedBuffer());
      MRGI_TEST_CHECK(mapped);
      std::copy(mapped, mapped + out.size(), out.begin());
      pbo->UnmapPackedBuffer();
      pbo->Delete();
      this->Fbo->RemoveColorAttachments(1);
      this->Fbo->UnBind();
      this->Fbo->RestorePreviousBindingsAndBuffers();
    }
    this->Rays->Deactivate();
    vox->GetVoxelTexture()->Deactivate();
    // Every fragment wrote: visible is 0 or 1, the fraction in [0, 1].
    for (int i = 0; i < RayCount; ++i)
    {
      MRGI_TEST_CHECK(out[4 * i] == 0.0f || out[4 * i] == 1.0f);
      MRGI_TEST_CHECK(out[4 * i + 1] >= 0.0f && out[4 * i + 1] <= 1.0f);
    }
  }

private:
  vtkOpenGLRenderWindow* Window;
  vtkOpenGLQuadHelper* Quad = nullptr;
  vtkNew<vtkTextureObject> Rays;
  vtkNew<vtkTextureObject> Output;
  vtkNew<vtkOpenGLFramebufferObject> Fbo;
};

// ---------------------------------------------------------------------------
// The comparison.
struct Comparison
{
  size_t Rays = 0;
  size_t Marched = 0;
  size_t Visible = 0;    // twin
  size_t Occluded = 0;   // twin, marched rays only
  size_t Mismatch = 0;   // binary answers
  size_t Boundary = 0;   // of which the twin gives the GPU's answer within a few ulps
  size_t FractionMismatch = 0;
  double MaxFractionError = 0; // over the rays whose binary answers agree
  double Rate() const { return this->Marched ? double(this->Mismatch) / double(this->Marched) : 0.0; }
  double FractionRate() const
  {
    return this->Marched ? double(this->FractionMismatch) / double(this->Marched) : 0.0;
  }
};

const float FractionTolerance = 1e-4f;

// Whether some input within a few float ulps makes the twin answer `answer`.
bool TwinCanAnswer(const mrgi_voxel_view& view, const Ray& ray, int answer, unsigned seed)
{
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 48; ++trial)
  {
    Ray r = ray;
    const double scale = trial < 16 ? 2e-7 : (trial < 32 ? 1e-6 : 4e-6);
    float* values = &r.P[0];
    for (int k = 0; k < 12; ++k)
    {
      const double e = scale * (static_cast<double>(rng()) / 4294967296.0 * 2.0 - 1.0);
      values[k] = static_cast<float>(values[k] * (1.0 + e));
    }
    if (mrgi_voxel_march(&view, r.P, r.Np, r.L, r.Nl) == answer)
    {
      return true;
    }
  }
  return false;
}

Comparison Compare(const mrgi_voxel_view& view, const std::vector<Ray>& rays,
  const std::vector<float>& gpu, bool classify)
{
  Comparison c;
  c.Rays = rays.size();
  for (size_t i = 0; i < rays.size(); ++i)
  {
    const Ray& r = rays[i];
    const bool marched = Marched(r);
    const int twin = mrgi_voxel_march(&view, r.P, r.Np, r.L, r.Nl);
    const float twinFraction = mrgi_voxel_march_occluder_fraction(&view, r.P, r.Np, r.L, r.Nl);
    const int gpuAnswer = gpu[4 * i] > 0.5f ? 1 : 0;
    const float gpuFraction = gpu[4 * i + 1];
    c.Marched += marched;
    c.Visible += twin;
    c.Occluded += marched && !twin;
    if (twin != gpuAnswer)
    {
      // (A ray decided by the zero-length or horizon tests can differ only
      // when a dot product is within rounding of 0: counted alike.)
      ++c.Mismatch;
      if (classify && TwinCanAnswer(view, r, gpuAnswer, static_cast<unsigned>(i)))
      {
        ++c.Boundary;
      }
    }
    const double fractionError = std::fabs(static_cast<double>(gpuFraction) - twinFraction);
    if (!(fractionError <= FractionTolerance))
    {
      ++c.FractionMismatch;
    }
    else if (twin == gpuAnswer)
    {
      c.MaxFractionError = std::max(c.MaxFractionError, fractionError);
    }
  }
  return c;
}

// ---------------------------------------------------------------------------
struct Totals
{
  size_t Marched = 0, Mismatch = 0, Boundary = 0, FractionMismatch = 0;
} totals;

const double MaxRate = 0.005;          // 0.5% of the marched rays
const double MaxUnexplainedRate = 5e-4; // 0.05%: disagreements must be isolated boundary cases

// Voxelize `ren` at vw x vh over [near, far], march RayCount rays on both
// sides with `params`, compare. Returns the comparison; `wrong` (optional)
// receives the comparison against a twin with the wrong params `wrongParams`.
Comparison RunCase(const std::string& name, vtkRenderWindow* window, vtkRenderer* ren,
  vtkMRGIVoxelization* vox, GPUMarch& gpuMarch, int vw, int vh, const double range[2],
  const mrgi_voxel_march_params& params, unsigned seed,
  const mrgi_voxel_march_params* wrongParams = nullptr, Comparison* wrong = nullptr,
  bool objectKnobs = false, int slices = MRGI_VOXEL_DEFAULT_SLICES)
{
  vox->SetVoxelSize(vw, vh);
  vox->SetNumberOfSlices(slices);
  MRGI_TEST_CHECK(vox->Voxelize(ren, range[0], range[1]));
  mrgi_voxel_grid grid;
  mrgi_voxel_projection proj;
  MRGI_TEST_CHECK(vox->GetGrid(&grid, &proj));
  vtkNew<vtkTypeUInt32Array> voxels;
  MRGI_TEST_CHECK(vox->ReadVoxels(window, voxels));
  size_t bits = 0;
  for (vtkIdType k = 0; k < voxels->GetNumberOfValues(); ++k)
  {
    uint32_t v = voxels->GetValue(k);
    for (; v; v &= v - 1)
    {
      ++bits;
    }
  }

  const std::vector<Triangle> tris = SceneTriangles(ren);
  Sampler sampler(tris, grid, proj, seed);
  std::vector<Ray> rays(RayCount);
  for (Ray& r : rays)
  {
    r = sampler.Next();
  }

  std::vector<float> gpu;
  gpuMarch.Run(vox, params, objectKnobs, rays, gpu);

  mrgi_voxel_view view;
  view.grid = grid;
  view.projection = proj;
  view.params = params;
  view.voxels = voxels->GetPointer(0);
  view.voxel_words = static_cast<size_t>(voxels->GetNumberOfValues());
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_voxel_view_check(&view, &err) == MRGI_OK);
  const Comparison c = Compare(view, rays, gpu, true);
  std::printf("%-40s %4dx%-4dx%-3d %s steps %4d offset %4.2f skip %d | %zu voxel bits | %zu rays, "
              "%zu marched (%zu occluded) | binary: %zu differ = %.4f%% of marched (%zu "
              "boundary, %zu other) | fraction: %zu differ > %g = %.4f%%, max agreeing error "
              "%.2g\n",
    name.c_str(), vw, vh, grid.slices, proj.parallel ? "par " : "persp", params.max_steps,
    static_cast<double>(params.normal_offset), params.skip_radius, bits, c.Rays, c.Marched,
    c.Occluded, c.Mismatch, 100.0 * c.Rate(), c.Boundary, c.Mismatch - c.Boundary,
    c.FractionMismatch, static_cast<double>(FractionTolerance), 100.0 * c.FractionRate(),
    c.MaxFractionError);
  std::fflush(stdout);
  // The rays exercise the march: many are marched, and (with voxels) both
  // answers occur among them.
  MRGI_TEST_CHECK(c.Marched > c.Rays / 4);
  MRGI_TEST_CHECK(bits > 0);
  if (vw * vh > 1)
  {
    MRGI_TEST_CHECK(c.Occluded > c.Marched / 50);
    MRGI_TEST_CHECK(c.Marched - c.Occluded > c.Marched / 50);
  }
  MRGI_TEST_CHECK(c.Rate() < MaxRate);
  MRGI_TEST_CHECK(double(c.Mismatch - c.Boundary) <= MaxUnexplainedRate * double(c.Marched));
  MRGI_TEST_CHECK(c.FractionRate() < MaxRate);
  totals.Marched += c.Marched;
  totals.Mismatch += c.Mismatch;
  totals.Boundary += c.Boundary;
  totals.FractionMismatch += c.FractionMismatch;

  if (wrongParams && wrong)
  {
    mrgi_voxel_view wrongView = view;
    wrongView.params = *wrongParams;
    *wrong = Compare(wrongView, rays, gpu, false);
  }
  if (slices > MRGI_VOXEL_LAYER_SLICES)
  {
    // A twin that sees only the first layer (what a march reading one
    // render target would answer) must disagree: the GPU reads them all.
    std::vector<uint32_t> firstLayer(
      voxels->GetPointer(0), voxels->GetPointer(0) + view.voxel_words);
    const size_t words = static_cast<size_t>(mrgi_voxel_pixel_words(&grid));
    for (size_t k = 0; k < firstLayer.size(); ++k)
    {
      firstLayer[k] = k % words < MRGI_VOXEL_CHANNELS ? firstLayer[k] : 0u;
    }
    mrgi_voxel_view oneLayer = view;
    oneLayer.voxels = firstLayer.data();
    const Comparison blind = Compare(oneLayer, rays, gpu, false);
    std::printf("  twin seeing only the first of %d layers: %zu differ = %.3f%% of marched "
                "(must exceed 10x the parity's %zu)\n",
      slices / MRGI_VOXEL_LAYER_SLICES, blind.Mismatch, 100.0 * blind.Rate(), c.Mismatch);
    MRGI_TEST_CHECK(blind.Mismatch > 10 * (c.Mismatch + 10));
  }
  return c;
}

mrgi_voxel_march_params Params(int steps, float offset, int radius)
{
  mrgi_voxel_march_params p;
  mrgi_voxel_march_params_default(&p);
  p.max_steps = steps;
  p.normal_offset = offset;
  p.skip_radius = radius;
  return p;
}

const int WindowW = 150, WindowH = 110;

void CornellBox(bool parallel)
{
  mrgitest::SceneWindow scene(WindowW, WindowH, "cornell");
  vtkRenderWindow* window = scene.Window;
  vtkRenderer* renderer = scene.Renderer;
  if (parallel)
  {
    renderer->GetActiveCamera()->ParallelProjectionOn();
    renderer->ResetCamera();
  }
  window->Render();
  vtkNew<vtkMRGIVoxelization> vox;
  GPUMarch gpu(vtkOpenGLRenderWindow::SafeDownCast(window));
  double range[2];
  DepthRange(SceneTriangles(renderer), range);
  const double pad = 0.01 * (range[1] - range[0]);
  range[0] -= pad;
  range[1] += pad;
  const std::string name = std::string("cornell ") + (parallel ? "parallel" : "perspective");
  mrgi_voxel_march_params defaults;
  mrgi_voxel_march_params_default(&defaults);
  const unsigned seed = parallel ? 100 : 200;

  // Default knobs at 128^2, with two twins given wrong knobs: the comparison can fail.
  const mrgi_voxel_march_params wrongOffset = Params(defaults.max_steps, 0.5f, defaults.skip_radius);
  const mrgi_voxel_march_params wrongRadius = Params(defaults.max_steps, defaults.normal_offset, 0);
  Comparison wrong;
  const Comparison right = RunCase(name, window, renderer, vox, gpu, 128, 128, range, defaults,
    seed + 1, &wrongOffset, &wrong);
  std::printf("  twin with normal offset 0.5 (GPU 1.5): %zu differ = %.3f%% of marched "
              "(must fail the parity bound %.1f%% and exceed 10x the parity's %zu)\n",
    wrong.Mismatch, 100.0 * wrong.Rate(), 100.0 * MaxRate, right.Mismatch);
  MRGI_TEST_CHECK(wrong.Rate() >= MaxRate && wrong.Mismatch > 10 * (right.Mismatch + 10));
  const Comparison right2 = RunCase(name, window, renderer, vox, gpu, 128, 128, range, defaults,
    seed + 2, &wrongRadius, &wrong);
  std::printf("  twin with skip radius 0 (GPU 1): %zu differ = %.3f%% of marched "
              "(must fail the parity bound %.1f%% and exceed 10x the parity's %zu)\n",
    wrong.Mismatch, 100.0 * wrong.Rate(), 100.0 * MaxRate, right2.Mismatch);
  MRGI_TEST_CHECK(wrong.Rate() >= MaxRate && wrong.Mismatch > 10 * (right2.Mismatch + 10));

  RunCase(name, window, renderer, vox, gpu, 97, 61, range, defaults, seed + 3);
  RunCase(name, window, renderer, vox, gpu, 1, 1, range, defaults, seed + 4);
  // A binding step cap: steps longer than a pixel.
  RunCase(name + ", step cap", window, renderer, vox, gpu, 128, 128, range,
    Params(7, defaults.normal_offset, defaults.skip_radius), seed + 5);
  // No bias at all, and a large one.
  RunCase(name + ", no bias", window, renderer, vox, gpu, 128, 128, range, Params(256, 0.0f, 0),
    seed + 6);
  RunCase(name + ", large bias", window, renderer, vox, gpu, 97, 61, range,
    Params(MRGI_VOXEL_MAX_STEPS, 4.0f, 3), seed + 7);
  // The offset along the ray, at one end and at both; a twin offsetting
  // along the normals must fail (the mode reaches the GPU).
  for (int mode : { MRGI_VOXEL_OFFSET_RAY_AT_RECEIVER, MRGI_VOXEL_OFFSET_RAY_AT_BOTH })
  {
    mrgi_voxel_march_params along = defaults;
    along.offset_along_ray = mode;
    const Comparison alongRight = RunCase(name + (mode == MRGI_VOXEL_OFFSET_RAY_AT_BOTH ?
      ", offset along the ray at both ends" : ", offset along the ray at the receiver"),
      window, renderer, vox, gpu, 128, 128, range, along, seed + 8 + mode, &defaults, &wrong);
    std::printf("  twin offsetting along the normals (GPU along the ray, mode %d): %zu differ = %.3f%% "
                "of marched (must exceed 10x the parity's %zu)\n",
      mode, wrong.Mismatch, 100.0 * wrong.Rate(), alongRight.Mismatch);
    MRGI_TEST_CHECK(wrong.Mismatch > 10 * (alongRight.Mismatch + 10));
  }
  // Thinner slices: 2 to 4 layers, one render target each (mrgi_voxel.h
  // section 1); steps crossing a layer's edge read two.
  for (int slices : { 256, 384, 512 })
  {
    RunCase(name + ", " + std::to_string(slices) + " slices", window, renderer, vox, gpu,
      slices == 384 ? 97 : 128, slices == 384 ? 61 : 128, range, defaults, seed + 11 + slices,
      nullptr, nullptr, false, slices);
  }
  vox->SetNumberOfSlices(MRGI_VOXEL_DEFAULT_SLICES);
  vox->ReleaseGraphicsResources(window);
}

void RandomBoxes(bool parallel)
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(WindowW, WindowH);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  std::mt19937 rng(parallel ? 7 : 5);
  auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng() >> 5) / 134217728.0);
  };
  for (int k = 0; k < 14; ++k)
  {
    vtkNew<vtkCubeSource> cube;
    cube->SetXLength(uniform(0.2, 2.5));
    cube->SetYLength(uniform(0.2, 2.5));
    cube->SetZLength(uniform(0.2, 2.5));
    auto actor = MakeActor(cube);
    actor->SetPosition(uniform(-4, 4), uniform(-4, 4), uniform(-4, 4));
    actor->SetOrientation(uniform(0, 360), uniform(0, 360), uniform(0, 360));
    renderer->AddActor(actor);
  }
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(24);
  sphere->SetRadius(1.2);
  sphere->SetCenter(-1.5, 1.5, 0.5);
  renderer->AddActor(MakeActor(sphere));
  // A ball at the centre of the bounds (the camera's focal point after
  // ResetCamera(), inside the bounds so they do not change): the 1x1
  // buffer's only pixel, at the centre of the view, holds voxels.
  double bounds[6];
  renderer->ComputeVisiblePropBounds(bounds);
  vtkNew<vtkSphereSource> ball;
  ball->SetThetaResolution(16);
  ball->SetPhiResolution(12);
  ball->SetRadius(0.6);
  ball->SetCenter(0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]));
  renderer->AddActor(MakeActor(ball));
  renderer->GetActiveCamera()->SetParallelProjection(parallel);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(25);
  renderer->GetActiveCamera()->Elevation(20);
  renderer->ResetCameraClippingRange();
  window->Render();
  vtkNew<vtkMRGIVoxelization> vox;
  GPUMarch gpu(vtkOpenGLRenderWindow::SafeDownCast(window));
  double range[2];
  DepthRange(SceneTriangles(renderer), range);
  const std::string name = std::string("random boxes ") + (parallel ? "parallel" : "perspective");
  mrgi_voxel_march_params defaults;
  mrgi_voxel_march_params_default(&defaults);
  const unsigned seed = parallel ? 300 : 400;
  RunCase(name, window, renderer, vox, gpu, 128, 128, range, defaults, seed + 1);
  RunCase(name, window, renderer, vox, gpu, 97, 61, range, defaults, seed + 2);
  RunCase(name, window, renderer, vox, gpu, 1, 1, range, defaults, seed + 3);
  RunCase(name + ", step cap", window, renderer, vox, gpu, 97, 61, range,
    Params(3, defaults.normal_offset, defaults.skip_radius), seed + 4);
  vox->ReleaseGraphicsResources(window);
}

// The knobs' defaults and ranges are the core's; SetMarchUniforms refuses
// what it cannot do.
void Api()
{
  vtkNew<vtkMRGIVoxelization> vox;
  mrgi_voxel_march_params defaults, got;
  mrgi_voxel_march_params_default(&defaults);
  vox->GetMarchParams(&got);
  MRGI_TEST_CHECK(got.max_steps == defaults.max_steps && vox->GetMaxSteps() == defaults.max_steps);
  MRGI_TEST_CHECK(got.normal_offset == defaults.normal_offset);
  MRGI_TEST_CHECK(got.skip_radius == defaults.skip_radius);
  vox->SetMaxSteps(0);
  MRGI_TEST_CHECK(vox->GetMaxSteps() == 1);
  vox->SetMaxSteps(MRGI_VOXEL_MAX_STEPS + 1);
  MRGI_TEST_CHECK(vox->GetMaxSteps() == MRGI_VOXEL_MAX_STEPS);
  vox->SetNormalOffset(-1);
  MRGI_TEST_CHECK(vox->GetNormalOffset() == 0.0);
  vox->SetNormalOffset(1e9);
  MRGI_TEST_CHECK(vox->GetNormalOffset() == MRGI_VOXEL_MAX_NORMAL_OFFSET);
  vtkNew<mrgitest::ErrorCatcher> errors;
  vox->AddObserver(vtkCommand::ErrorEvent, errors);
  vox->SetNormalOffset(std::nan(""));
  MRGI_TEST_CHECK(errors->Caught("NaN"));
  MRGI_TEST_CHECK(vox->GetNormalOffset() == MRGI_VOXEL_MAX_NORMAL_OFFSET);
  vox->SetSkipRadius(-3);
  MRGI_TEST_CHECK(vox->GetSkipRadius() == 0);
  vox->SetSkipRadius(100);
  MRGI_TEST_CHECK(vox->GetSkipRadius() == MRGI_VOXEL_MAX_SKIP_RADIUS);
  MRGI_TEST_CHECK(vox->GetOffsetAlongRay() == vtkMRGIVoxelization::OffsetNormals &&
    got.offset_along_ray == MRGI_VOXEL_OFFSET_NORMALS);
  vox->SetOffsetAlongRay(7);
  MRGI_TEST_CHECK(vox->GetOffsetAlongRay() == vtkMRGIVoxelization::OffsetRayAtBoth);
  // Slices: up to a whole layer of 128, clamped to 128..512.
  MRGI_TEST_CHECK(vox->GetNumberOfSlices() == MRGI_VOXEL_DEFAULT_SLICES);
  const int slicesAsked[][2] = { { 200, 256 }, { 384, 384 }, { 4096, 512 }, { 0, 128 }, { -5, 128 } };
  for (const auto& pair : slicesAsked)
  {
    vox->SetNumberOfSlices(pair[0]);
    MRGI_TEST_CHECK(vox->GetNumberOfSlices() == pair[1]);
  }
  vox->SetOffsetAlongRay(-1);
  MRGI_TEST_CHECK(vox->GetOffsetAlongRay() == vtkMRGIVoxelization::OffsetNormals);
  vox->SetOffsetAlongRayToReceiver();
  MRGI_TEST_CHECK(vox->GetOffsetAlongRay() == vtkMRGIVoxelization::OffsetRayAtReceiver);
  vox->GetMarchParams(&got);
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_voxel_march_params_validate(&got, &err) == MRGI_OK);
  const std::string source = vtkMRGIVoxelization::GetMarchShaderSource();
  MRGI_TEST_CHECK(source.find("bool mrgiVoxelVisible(") != std::string::npos);
  MRGI_TEST_CHECK(source.find("void main") == std::string::npos);

  // Before any voxelization, and with bad arguments.
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(64, 48);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkSphereSource> ball;
  renderer->AddActor(MakeActor(ball));
  renderer->ResetCamera();
  window->Render();
  {
    GPUMarch gpu(vtkOpenGLRenderWindow::SafeDownCast(window));
    vtkOpenGLRenderWindow* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
    const std::string fs = std::string("//VTK::System::Dec\n") + CoreDefines() +
      vtkMRGIVoxelization::GetMarchShaderSource() + MarchTestBody;
    vtkOpenGLQuadHelper quad(
      gl, vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), fs.c_str(), "");
    MRGI_TEST_CHECK(quad.Program && quad.Program->GetCompiled());
    MRGI_TEST_CHECK(!vox->SetMarchUniforms(quad.Program));
    MRGI_TEST_CHECK(errors->Caught("nothing voxelized"));
    const double dist = renderer->GetActiveCamera()->GetDistance();
    MRGI_TEST_CHECK(vox->Voxelize(renderer, dist - 0.6, dist + 0.6));
    MRGI_TEST_CHECK(!vox->SetMarchUniforms(nullptr));
    MRGI_TEST_CHECK(errors->Caught("no shader program"));
    MRGI_TEST_CHECK(!vox->SetMarchUniforms(quad.Program, Params(0, 1.5f, 1)));
    MRGI_TEST_CHECK(errors->Caught("max_steps"));
    MRGI_TEST_CHECK(!vox->SetMarchUniforms(quad.Program, Params(16, 1.5f, 9)));
    MRGI_TEST_CHECK(errors->Caught("skip_radius"));
    MRGI_TEST_CHECK(vox->SetMarchUniforms(quad.Program));
    vox->GetVoxelTexture()->Deactivate();
    MRGI_TEST_CHECK(errors->Count == 0);

    // The object's own knobs reach the shader: the same rays as the twin
    // with GetMarchParams().
    vox->SetMaxSteps(9);
    vox->SetNormalOffset(2.0);
    vox->SetSkipRadius(2);
    mrgi_voxel_march_params mine;
    vox->GetMarchParams(&mine);
    MRGI_TEST_CHECK(mine.max_steps == 9 && mine.normal_offset == 2.0f && mine.skip_radius == 2);
    double range[2] = { dist - 0.6, dist + 0.6 };
    RunCase("sphere, object's knobs", window, renderer, vox, gpu, 48, 40, range, mine, 9,
      nullptr, nullptr, true);
    MRGI_TEST_CHECK(errors->Count == 0);
  }
  vox->ReleaseGraphicsResources(window);
}
}

int main(int argc, char* argv[])
{
  const int result = mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(Api), { "CornellBox", [] { CornellBox(false); } },
      { "CornellBoxParallel", [] { CornellBox(true); } },
      { "RandomBoxes", [] { RandomBoxes(false); } },
      { "RandomBoxesParallel", [] { RandomBoxes(true); } } });
  if (totals.Marched > 0)
  {
    std::printf("cases run: %zu marched rays, %zu binary answers differ (%.4f%%; %zu boundary, "
                "%zu other), %zu fractions differ (%.4f%%)\n",
      totals.Marched, totals.Mismatch, 100.0 * totals.Mismatch / totals.Marched, totals.Boundary,
      totals.Mismatch - totals.Boundary, totals.FractionMismatch,
      100.0 * totals.FractionMismatch / totals.Marched);
  }
  return result;
}
