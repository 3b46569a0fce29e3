#include "vtk_glew.h"

#include "vtkMRGIVoxelization.h"

#include "vtkCamera.h"
#include "vtkMRGIShaderLibraries.h"
#include "vtkMRGIResourceStatistics.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIVoxelGeometry.h"
#include "vtkMRGIVoxelTexture.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkTypeUInt32Array.h"
#include "vtkWeakPointer.h"

#include "vtkMRGIVoxelMarch.h"
#include "vtkMRGIVoxelBits.h"
#include "vtkMRGIVoxelizeFS.h"
#include "vtkMRGIVoxelizeGS.h"
#include "vtkMRGIVoxelizeVS.h"

#include "mrgi_voxel.h"
#include "mrgi_voxel_march.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

static_assert(vtkMRGIVoxelization::OffsetNormals == MRGI_VOXEL_OFFSET_NORMALS &&
    vtkMRGIVoxelization::OffsetRayAtReceiver == MRGI_VOXEL_OFFSET_RAY_AT_RECEIVER &&
    vtkMRGIVoxelization::OffsetRayAtBoth == MRGI_VOXEL_OFFSET_RAY_AT_BOTH,
  "the offset modes are the core's");

vtkStandardNewMacro(vtkMRGIVoxelization);

namespace
{
// The voxel projection of `ren`'s active camera over its viewport (section
// 4: the window's own aspect, so the voxel buffer covers exactly the
// renderer's frustum), as VTK's camera builds it. False, with `message`
// naming why, for a viewport of zero size or a projection the voxel
// projection (a scale and an offset per axis) cannot express.
bool CameraVoxelProjection(vtkRenderer* ren, mrgi_voxel_projection& projection, std::string& message)
{
  int viewW = 0, viewH = 0, viewX = 0, viewY = 0;
  ren->GetTiledSizeAndOrigin(&viewW, &viewH, &viewX, &viewY);
  if (viewW < 1 || viewH < 1)
  {
    message = "the renderer's viewport has zero size (" + std::to_string(viewW) + " x " +
      std::to_string(viewH) + " pixels)";
    return false;
  }
  const double aspect = static_cast<double>(viewW) / static_cast<double>(viewH);
  vtkMatrix4x4* P = ren->GetActiveCamera()->GetProjectionTransformMatrix(aspect, -1, 1);
  double columnMajor[16];
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      columnMajor[4 * c + r] = P->GetElement(r, c);
    }
  }
  mrgi_error err;
  if (mrgi_voxel_projection_from_matrix(&projection, columnMajor, &err) != MRGI_OK)
  {
    message = std::string("the camera's projection cannot be voxelized: ") + err.message;
    return false;
  }
  // Terms the voxel projection (a scale and an offset per axis) cannot hold.
  const bool parallel = projection.parallel != 0;
  if (P->GetElement(0, 1) != 0.0 || P->GetElement(1, 0) != 0.0 ||
    (parallel ? (P->GetElement(0, 2) != 0.0 || P->GetElement(1, 2) != 0.0)
              : (P->GetElement(0, 3) != 0.0 || P->GetElement(1, 3) != 0.0)))
  {
    message = "the camera's projection is sheared or off-axis, which the voxel projection "
              "(scale and offset per axis, mrgi_voxel.h section 4) cannot express";
    return false;
  }
  return true;
}

// Errors left by earlier GL calls are not ours (vtkOpenGLClearErrorMacro is
// compiled out in release builds of VTK).
void ClearGLErrors()
{
  for (int k = 0; k < 16 && glGetError() != GL_NO_ERROR; ++k)
  {
  }
}

// Restores what vtkOpenGLState does not track: logic op, depth clamp,
// polygon mode, rasterizer discard.
struct RawState
{
  RawState()
  {
    this->LogicOp = glIsEnabled(GL_COLOR_LOGIC_OP) == GL_TRUE;
    glGetIntegerv(GL_LOGIC_OP_MODE, &this->LogicOpMode);
    this->DepthClamp = glIsEnabled(GL_DEPTH_CLAMP) == GL_TRUE;
    this->Discard = glIsEnabled(GL_RASTERIZER_DISCARD) == GL_TRUE;
    GLint modes[2] = { GL_FILL, GL_FILL };
    glGetIntegerv(GL_POLYGON_MODE, modes);
    this->PolygonMode = modes[0];
  }
  ~RawState()
  {
    Set(GL_COLOR_LOGIC_OP, this->LogicOp);
    glLogicOp(static_cast<GLenum>(this->LogicOpMode));
    Set(GL_DEPTH_CLAMP, this->DepthClamp);
    Set(GL_RASTERIZER_DISCARD, this->Discard);
    glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(this->PolygonMode));
  }
  static void Set(GLenum cap, bool on)
  {
    if (on)
    {
      glEnable(cap);
    }
    else
    {
      glDisable(cap);
    }
  }
  bool LogicOp, DepthClamp, Discard;
  GLint LogicOpMode = GL_COPY;
  GLint PolygonMode = GL_FILL;
};
}

struct vtkMRGIVoxelization::Internals
{
  // The window whose context holds the resources below (weak: a window that
  // goes away takes its context, and the GL objects, with it).
  vtkWeakPointer<vtkOpenGLRenderWindow> Window;
  // The voxels: one depth layer of a 3D texture per 128 slices.
  vtkMRGIVoxelTexture Voxels;
  vtkOpenGLFramebufferObject* FrameBuffer = nullptr;
  // What is drawn: vertex buffers per polydata, the vertex array.
  vtkMRGIVoxelGeometry Geometry;
  // The last successful voxelization.
  bool HasGrid = false;
  mrgi_voxel_grid Grid{};
  mrgi_voxel_projection Projection{};
  double WorldToView[16] = { 0 }; // column-major
  vtkIdType Triangles = 0;
  int DrawnProps = 0;
  int SkippedProps = 0;

  bool HasResources() const
  {
    return this->Voxels.GetTexture() || this->FrameBuffer || this->Geometry.HoldsResources();
  }
};

//------------------------------------------------------------------------------
vtkMRGIVoxelization::vtkMRGIVoxelization()
  : Internal(new Internals)
{
  this->VoxelSize[0] = MRGI_VOXEL_DEFAULT_SIZE;
  this->VoxelSize[1] = MRGI_VOXEL_DEFAULT_SIZE;
  this->NumberOfSlices = MRGI_VOXEL_DEFAULT_SLICES;
  mrgi_voxel_march_params params;
  mrgi_voxel_march_params_default(&params);
  this->MaxSteps = params.max_steps;
  this->NormalOffset = params.normal_offset;
  this->OffsetAlongRay = params.offset_along_ray;
  this->SkipRadius = params.skip_radius;
}

//------------------------------------------------------------------------------
vtkMRGIVoxelization::~vtkMRGIVoxelization()
{
  Internals& in = *this->Internal;
  if (in.HasResources())
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  in.Geometry.Release(false);
  in.Voxels.Release(nullptr);
  if (in.FrameBuffer)
  {
    in.FrameBuffer->Delete();
  }
}

//------------------------------------------------------------------------------
void vtkMRGIVoxelization::ReleaseGraphicsResources(vtkWindow* w)
{
  Internals& in = *this->Internal;
  in.Geometry.Release(w != nullptr);
  in.Voxels.Release(w);
  if (in.FrameBuffer)
  {
    if (w)
    {
      in.FrameBuffer->ReleaseGraphicsResources(w);
    }
    in.FrameBuffer->Delete();
    in.FrameBuffer = nullptr;
  }
  in.HasGrid = false;
  in.Window = nullptr;
}

//------------------------------------------------------------------------------
void vtkMRGIVoxelization::SetNumberOfSlices(int slices)
{
  // Up to the next layer of 128, clamped (mrgi_voxel.h section 1).
  slices = std::min(std::max(slices, MRGI_VOXEL_LAYER_SLICES), MRGI_VOXEL_MAX_SLICES);
  slices =
    (slices + MRGI_VOXEL_LAYER_SLICES - 1) / MRGI_VOXEL_LAYER_SLICES * MRGI_VOXEL_LAYER_SLICES;
  if (slices != this->NumberOfSlices)
  {
    this->NumberOfSlices = slices;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkMRGIVoxelization::SetVoxelSize(int width, int height)
{
  // Clamped like vtkSetClampMacro: the core's limits (mrgi_voxel.h section 3).
  width = std::min(std::max(width, 1), MRGI_VOXEL_MAX_SIZE);
  height = std::min(std::max(height, 1), MRGI_VOXEL_MAX_SIZE);
  if (this->VoxelSize[0] != width || this->VoxelSize[1] != height || this->AutomaticVoxelSize)
  {
    this->VoxelSize[0] = width;
    this->VoxelSize[1] = height;
    this->AutomaticVoxelSize = false;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIVoxelization::ComputeVoxelSize(
  vtkRenderer* ren, double nearDepth, double farDepth, int size[2]) const
{
  size[0] = this->VoxelSize[0];
  size[1] = this->VoxelSize[1];
  if (!this->AutomaticVoxelSize)
  {
    return true;
  }
  mrgi_voxel_projection projection;
  std::string message;
  if (!ren || !ren->IsActiveCameraCreated() || !CameraVoxelProjection(ren, projection, message))
  {
    return false;
  }
  return this->VoxelSizeFor(projection, nearDepth, farDepth, size);
}

//------------------------------------------------------------------------------
bool vtkMRGIVoxelization::VoxelSizeFor(
  const mrgi_voxel_projection& projection, double nearDepth, double farDepth, int size[2]) const
{
  size[0] = this->VoxelSize[0];
  size[1] = this->VoxelSize[1];
  // Pixels as wide as 128 slices are deep, whatever NumberOfSlices: a
  // march's steps follow the pixels, so more slices refine the depth at
  // little cost, and the side stays the caller's choice (header).
  int32_t automatic[2];
  if (!this->AutomaticVoxelSize ||
    mrgi_voxel_isotropic_size(
      &projection, MRGI_VOXEL_LAYER_SLICES, nearDepth, farDepth, automatic, nullptr) != MRGI_OK)
  {
    return !this->AutomaticVoxelSize;
  }
  size[0] = automatic[0];
  size[1] = automatic[1];
  return true;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIVoxelization::GetVoxelTexture() const
{
  return this->Internal->HasGrid ? this->Internal->Voxels.GetTexture() : nullptr;
}

int vtkMRGIVoxelization::GetMarchStepBound() const
{
  const Internals& in = *this->Internal;
  return in.HasGrid ? mrgi_voxel_step_bound(&in.Grid, this->MaxSteps) : this->MaxSteps;
}

void vtkMRGIVoxelization::GetLastVoxelSize(int size[2]) const
{
  const Internals& in = *this->Internal;
  size[0] = in.HasGrid ? in.Grid.width : 0;
  size[1] = in.HasGrid ? in.Grid.height : 0;
}

int vtkMRGIVoxelization::GetLastNumberOfSlices() const
{
  const Internals& in = *this->Internal;
  return in.HasGrid ? in.Grid.slices : 0;
}

void vtkMRGIVoxelization::GetLastDepthRange(double range[2]) const
{
  const Internals& in = *this->Internal;
  range[0] = in.HasGrid ? in.Grid.near_depth : 0.0;
  range[1] = in.HasGrid ? in.Grid.far_depth : 0.0;
}

bool vtkMRGIVoxelization::GetLastParallelProjection() const
{
  return this->Internal->HasGrid && this->Internal->Projection.parallel != 0;
}

bool vtkMRGIVoxelization::GetLastWorldToView(double worldToView[16]) const
{
  if (!this->Internal->HasGrid)
  {
    return false;
  }
  std::copy(this->Internal->WorldToView, this->Internal->WorldToView + 16, worldToView);
  return true;
}

vtkIdType vtkMRGIVoxelization::GetNumberOfTriangles() const
{
  return this->Internal->Triangles;
}

int vtkMRGIVoxelization::GetNumberOfDrawnProps() const
{
  return this->Internal->DrawnProps;
}

int vtkMRGIVoxelization::GetNumberOfSkippedProps() const
{
  return this->Internal->SkippedProps;
}

bool vtkMRGIVoxelization::GetGrid(mrgi_voxel_grid* grid, mrgi_voxel_projection* projection) const
{
  const Internals& in = *this->Internal;
  if (!in.HasGrid)
  {
    return false;
  }
  if (grid)
  {
    *grid = in.Grid;
  }
  if (projection)
  {
    *projection = in.Projection;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIVoxelization::SetMaxSteps(int steps)
{
  steps = std::min(std::max(steps, 1), MRGI_VOXEL_MAX_STEPS);
  if (steps != this->MaxSteps)
  {
    this->MaxSteps = steps;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkMRGIVoxelization::SetNormalOffset(double offset)
{
  if (std::isnan(offset))
  {
    vtkErrorMacro("SetNormalOffset: NaN ignored (the offset stays " << this->NormalOffset << ")");
    return;
  }
  offset = std::min(std::max(offset, 0.0), static_cast<double>(MRGI_VOXEL_MAX_NORMAL_OFFSET));
  if (offset != this->NormalOffset)
  {
    this->NormalOffset = offset;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkMRGIVoxelization::SetOffsetAlongRay(int mode)
{
  mode = std::min(std::max(mode, static_cast<int>(OffsetNormals)), static_cast<int>(OffsetRayAtBoth));
  if (mode != this->OffsetAlongRay)
  {
    this->OffsetAlongRay = mode;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkMRGIVoxelization::SetSkipRadius(int radius)
{
  radius = std::min(std::max(radius, 0), MRGI_VOXEL_MAX_SKIP_RADIUS);
  if (radius != this->SkipRadius)
  {
    this->SkipRadius = radius;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkMRGIVoxelization::GetMarchParams(mrgi_voxel_march_params* params) const
{
  if (params)
  {
    params->max_steps = this->MaxSteps;
    params->normal_offset = static_cast<float>(this->NormalOffset);
    params->skip_radius = this->SkipRadius;
    params->offset_along_ray = this->OffsetAlongRay;
  }
}

//------------------------------------------------------------------------------
const char* vtkMRGIVoxelization::GetMarchShaderSource()
{
  // The slicing and masks first (shared with the voxelization), then the march.
  static const std::string source = vtkMRGIShaderLibraries::Compose({ "vtkMRGIVoxelMarch" });
  return source.c_str();
}

//------------------------------------------------------------------------------
bool vtkMRGIVoxelization::SetMarchUniforms(vtkShaderProgram* program)
{
  mrgi_voxel_march_params params;
  this->GetMarchParams(&params);
  return this->SetMarchUniforms(program, params);
}

//------------------------------------------------------------------------------
bool vtkMRGIVoxelization::SetMarchUniforms(
  vtkShaderProgram* program, const mrgi_voxel_march_params& params)
{
  Internals& in = *this->Internal;
  if (!program)
  {
    vtkErrorMacro("SetMarchUniforms: no shader program");
    return false;
  }
  if (!in.HasGrid || !in.Voxels.GetTexture())
  {
    vtkErrorMacro("SetMarchUniforms: nothing voxelized yet (no successful Voxelize())");
    return false;
  }
  mrgi_error err;
  if (mrgi_voxel_march_params_validate(&params, &err) != MRGI_OK)
  {
    vtkErrorMacro("SetMarchUniforms: " << err.message);
    return false;
  }
  // The same numbers the C twin reads (mrgi_voxel_view: grid, projection,
  // params), so that GPU and twin march the same steps (nichols-penmatsa-
  // wyman-2010 3.3.1; parity in TestMRGIVoxelMarch).
  const mrgi_voxel_grid& g = in.Grid;
  const mrgi_voxel_projection& p = in.Projection;
  const int size[2] = { g.width, g.height };
  const float scale[2] = { p.scale_x, p.scale_y };
  const float offset[2] = { p.offset_x, p.offset_y };
  auto used = [program](const char* name) { return program->IsUniformUsed(name); };
  if (used("mrgiVoxelTexture"))
  {
    in.Voxels.GetTexture()->Activate();
    program->SetUniformi("mrgiVoxelTexture", in.Voxels.GetTexture()->GetTextureUnit());
  }
  if (used("mrgiVoxelGridSize"))
  {
    program->SetUniform2i("mrgiVoxelGridSize", size);
  }
  if (used("mrgiVoxelSlices"))
  {
    program->SetUniformi("mrgiVoxelSlices", g.slices);
  }
  if (used("mrgiVoxelNear"))
  {
    program->SetUniformf("mrgiVoxelNear", g.near_depth);
  }
  if (used("mrgiVoxelFar"))
  {
    program->SetUniformf("mrgiVoxelFar", g.far_depth);
  }
  if (used("mrgiVoxelSliceScale"))
  {
    program->SetUniformf("mrgiVoxelSliceScale", g.slice_scale);
  }
  if (used("mrgiVoxelProjectionScale"))
  {
    program->SetUniform2f("mrgiVoxelProjectionScale", scale);
  }
  if (used("mrgiVoxelProjectionOffset"))
  {
    program->SetUniform2f("mrgiVoxelProjectionOffset", offset);
  }
  if (used("mrgiVoxelParallel"))
  {
    program->SetUniformi("mrgiVoxelParallel", p.parallel ? 1 : 0);
  }
  if (used("mrgiVoxelMaxSteps"))
  {
    program->SetUniformi("mrgiVoxelMaxSteps", params.max_steps);
  }
  if (used("mrgiVoxelNormalOffset"))
  {
    program->SetUniformf("mrgiVoxelNormalOffset", params.normal_offset);
  }
  if (used("mrgiVoxelSkipRadius"))
  {
    program->SetUniformi("mrgiVoxelSkipRadius", params.skip_radius);
  }
  if (used("mrgiVoxelOffsetAlongRay"))
  {
    program->SetUniformi("mrgiVoxelOffsetAlongRay", params.offset_along_ray);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIVoxelization::ComputeDepthRange(vtkRenderer* ren, double range[2])
{
  vtkCamera* camera = ren ? ren->GetActiveCamera() : nullptr;
  if (!camera)
  {
    return false;
  }
  double clip[2], bounds[6];
  camera->GetClippingRange(clip);
  ren->ComputeVisiblePropBounds(bounds);
  if (mrgi_voxel_fit_depth_range(
        camera->GetModelViewTransformMatrix()->GetData(), bounds, clip, range, nullptr) != MRGI_OK)
  {
    range[0] = clip[0];
    range[1] = clip[1];
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIVoxelization::Voxelize(
  vtkRenderer* ren, double nearDepth, double farDepth, vtkRenderTimerLog* timer)
{
  Internals& in = *this->Internal;
  // ---- arguments (nothing touched on error: the previous buffer stays) ----
  if (!ren)
  {
    vtkErrorMacro("Voxelize: no renderer");
    return false;
  }
  vtkOpenGLRenderWindow* window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!window)
  {
    vtkErrorMacro("Voxelize: the renderer is not in an OpenGL render window");
    return false;
  }
  if (window->GetNeverRendered())
  {
    vtkErrorMacro("Voxelize: the window has never rendered (no OpenGL context yet); render once first");
    return false;
  }
  if (!ren->IsActiveCameraCreated())
  {
    vtkErrorMacro("Voxelize: the renderer has no active camera");
    return false;
  }
  if (!std::isfinite(nearDepth) || !std::isfinite(farDepth))
  {
    vtkErrorMacro("Voxelize: depth range [" << nearDepth << ", " << farDepth
                                            << "] is not finite (NaN or infinite)");
    return false;
  }
  if (!(nearDepth < farDepth))
  {
    vtkErrorMacro("Voxelize: near depth " << nearDepth << " must be less than far depth "
                                          << farDepth);
    return false;
  }
  mrgi_voxel_projection projection;
  std::string problem;
  if (!CameraVoxelProjection(ren, projection, problem))
  {
    vtkErrorMacro("Voxelize: " << problem);
    return false;
  }
  const bool parallel = projection.parallel != 0;
  // Slicing (mrgi_voxel.h section 2): the core rounds near/far and the scale to
  // float exactly as the shader's uniforms, and rejects ranges too small for floats.
  int size[2];
  this->VoxelSizeFor(projection, nearDepth, farDepth, size);
  mrgi_voxel_grid grid;
  mrgi_error err;
  if (mrgi_voxel_grid_init(
        &grid, size[0], size[1], this->NumberOfSlices, nearDepth, farDepth, &err) != MRGI_OK)
  {
    vtkErrorMacro("Voxelize: " << err.message);
    return false;
  }
  if (!parallel && !(grid.near_depth > 0.0f))
  {
    vtkErrorMacro("Voxelize: near depth " << nearDepth
                                          << " must be > 0 with a perspective camera");
    return false;
  }

  // Resources live in one context: moving to another window frees them in
  // the old one (or forgets them when that window, and its context, is gone).
  if (in.Window != window && in.HasResources())
  {
    vtkOpenGLRenderWindow* old = in.Window;
    if (old)
    {
      old->MakeCurrent();
    }
    this->ReleaseGraphicsResources(old);
  }
  in.Window = window;

  // ---- what to draw ----
  // Matrices in double; one model-view per item (view x actor x centre shift).
  vtkMatrix4x4* view = ren->GetActiveCamera()->GetModelViewTransformMatrix();
  double worldToView[16];
  std::copy(view->GetData(), view->GetData() + 16, worldToView);
  window->MakeCurrent();
  ClearGLErrors();
  in.Geometry.Collect(ren);

  // ---- resources ----
  const int layers = mrgi_voxel_layers(&grid);
  if (!in.Voxels.Ensure(window, grid.width, grid.height, layers, problem))
  {
    vtkErrorMacro("Voxelize: " << problem);
    in.HasGrid = false;
    return false;
  }
  if (!in.FrameBuffer)
  {
    in.FrameBuffer = vtkOpenGLFramebufferObject::New();
    in.FrameBuffer->SetContext(window);
  }
  const std::string header = "//VTK::System::Dec\n" + vtkMRGIShaderUtilities::Defines();
  const std::string vs = header + vtkMRGIVoxelizeVS;
  const std::string gs = header + vtkMRGIVoxelizeGS;
  const std::string fs = header + vtkMRGIShaderLibraries::Compose({ "vtkMRGIVoxelizeFS" });
  vtkShaderProgram* program =
    window->GetShaderCache()->ReadyShaderProgram(vs.c_str(), fs.c_str(), gs.c_str());
  if (!program || !program->GetCompiled())
  {
    vtkErrorMacro("Voxelize: could not build the voxelization shader"
      << (program ? ": " + program->GetError() : std::string()));
    return false;
  }

  // ---- the pass ----
  vtkMRGIShaderUtilities::ScopedStage stage(timer, "voxelize");
  vtkOpenGLState* ostate = window->GetState();
  bool ok = true;
  {
    // Every surface counts, hidden or back-facing (no depth test, no
    // culling); fragments combine by OR (logic ops apply to integer targets,
    // blending does not), all four channels written.
    vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
    vtkOpenGLState::ScopedglEnableDisable depth(ostate, GL_DEPTH_TEST);
    vtkOpenGLState::ScopedglEnableDisable cull(ostate, GL_CULL_FACE);
    vtkOpenGLState::ScopedglEnableDisable scissor(ostate, GL_SCISSOR_TEST);
    vtkOpenGLState::ScopedglEnableDisable stencil(ostate, GL_STENCIL_TEST);
    vtkOpenGLState::ScopedglViewport viewport(ostate);
    vtkOpenGLState::ScopedglColorMask colorMask(ostate);
    RawState raw;
    ostate->vtkglDisable(GL_BLEND);
    ostate->vtkglDisable(GL_DEPTH_TEST);
    ostate->vtkglDisable(GL_CULL_FACE);
    ostate->vtkglDisable(GL_SCISSOR_TEST);
    ostate->vtkglDisable(GL_STENCIL_TEST);
    ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    // Depth clamp would keep what lies beyond near/far: clipping must drop it.
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_RASTERIZER_DISCARD);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);

    vtkOpenGLFramebufferObject* fbo = in.FrameBuffer;
    fbo->SaveCurrentBindingsAndBuffers();
    fbo->Bind();
    // One render target per layer of 128 slices, all written by one draw
    // (NPW10 3.3: "more bits may be obtained using multiple render targets").
    in.Voxels.AttachLayers();
    vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, static_cast<unsigned int>(layers));
    if (glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    {
      vtkErrorMacro(
        "Voxelize: the RGBA32UI voxel framebuffer (" << layers << " layers) is incomplete");
      ok = false;
    }
    if (ok)
    {
      // Explicit viewport: the voxel buffer, whatever the window's size.
      ostate->vtkglViewport(0, 0, grid.width, grid.height);
      const GLuint zero[4] = { 0u, 0u, 0u, 0u };
      for (int l = 0; l < layers; ++l)
      {
        glClearBufferuiv(GL_COLOR, l, zero);
      }
      glEnable(GL_COLOR_LOGIC_OP);
      glLogicOp(GL_OR);

      // Eye -> clip from the voxel projection (so GPU and C twin use the same
      // float numbers) with near/far as clip planes (section 2: fragments
      // outside [near, far] are dropped). Column-major.
      const double n = grid.near_depth, f = grid.far_depth;
      float clip[16] = { 0 };
      clip[0] = projection.scale_x;
      clip[5] = projection.scale_y;
      if (parallel)
      {
        clip[10] = static_cast<float>(-2.0 / (f - n));
        clip[12] = projection.offset_x;
        clip[13] = projection.offset_y;
        clip[14] = static_cast<float>(-(f + n) / (f - n));
        clip[15] = 1.0f;
      }
      else
      {
        clip[8] = -projection.offset_x;
        clip[9] = -projection.offset_y;
        clip[10] = static_cast<float>(-(f + n) / (f - n));
        clip[11] = -1.0f;
        clip[14] = static_cast<float>(-2.0 * f * n / (f - n));
      }
      program->SetUniformMatrix4x4("mrgiProjection", clip);
      program->SetUniformi("mrgiVoxelSlices", grid.slices);
      program->SetUniformf("mrgiVoxelNear", grid.near_depth);
      program->SetUniformf("mrgiVoxelFar", grid.far_depth);
      program->SetUniformf("mrgiVoxelSliceScale", grid.slice_scale);
      const float voxelViewport[2] = { static_cast<float>(grid.width),
        static_cast<float>(grid.height) };
      program->SetUniform2f("mrgiVoxelViewport", voxelViewport);

      in.Triangles = in.Geometry.Draw(program, worldToView);
    }
    in.Voxels.DetachLayers();
    fbo->UnBind();
    fbo->RestorePreviousBindingsAndBuffers();
  }
  const GLenum error = glGetError();
  if (ok && error != GL_NO_ERROR)
  {
    vtkErrorMacro("Voxelize: OpenGL error 0x" << std::hex << error << std::dec);
    ok = false;
  }
  in.HasGrid = ok;
  if (!ok)
  {
    return false;
  }
  in.Grid = grid;
  in.Projection = projection;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      in.WorldToView[4 * c + r] = worldToView[4 * r + c];
    }
  }
  in.DrawnProps = in.Geometry.GetNumberOfDrawnProps();
  in.SkippedProps = in.Geometry.GetNumberOfSkippedProps();
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIVoxelization::WriteVoxels(vtkRenderWindow* window, vtkTypeUInt32Array* voxels)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!renWin || !voxels || !in.HasGrid || !in.Voxels.GetTexture() || renWin != in.Window)
  {
    vtkErrorMacro("WriteVoxels: needs the window of a successful Voxelize() and an array");
    return false;
  }
  const int w = in.Grid.width, h = in.Grid.height;
  const int words = mrgi_voxel_pixel_words(&in.Grid);
  if (voxels->GetNumberOfComponents() != words ||
    voxels->GetNumberOfTuples() != static_cast<vtkIdType>(w) * h)
  {
    vtkErrorMacro(
      "WriteVoxels: the array is not " << w << " x " << h << " x " << words << " words");
    return false;
  }
  renWin->MakeCurrent();
  ClearGLErrors();
  std::string problem;
  if (!in.Voxels.Write(in.Grid, voxels, problem))
  {
    vtkErrorMacro("WriteVoxels: " << problem);
    return false;
  }
  return true;
}

bool vtkMRGIVoxelization::ReadVoxels(vtkRenderWindow* window, vtkTypeUInt32Array* voxels)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!renWin || !voxels)
  {
    vtkErrorMacro("ReadVoxels: needs an OpenGL render window and an array");
    return false;
  }
  if (!in.HasGrid || !in.Voxels.GetTexture())
  {
    vtkErrorMacro("ReadVoxels: nothing voxelized yet (no successful Voxelize())");
    return false;
  }
  if (renWin != in.Window)
  {
    vtkErrorMacro("ReadVoxels: the voxels were made in another window");
    return false;
  }
  renWin->MakeCurrent();
  ClearGLErrors();
  std::string problem;
  if (!in.Voxels.Read(in.Grid, voxels, problem))
  {
    vtkErrorMacro("ReadVoxels: " << problem);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIVoxelization::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const Internals& in = *this->Internal;
  os << indent << "VoxelSize: " << this->VoxelSize[0] << " x " << this->VoxelSize[1] << "\n";
  os << indent << "NumberOfSlices: " << this->NumberOfSlices << "\n";
  os << indent << "AutomaticVoxelSize: " << (this->AutomaticVoxelSize ? "on" : "off") << "\n";
  os << indent << "MaxSteps: " << this->MaxSteps << "\n";
  os << indent << "NormalOffset: " << this->NormalOffset << "\n";
  os << indent << "OffsetAlongRay: "
     << (this->OffsetAlongRay == OffsetRayAtBoth ? "both ends"
         : this->OffsetAlongRay == OffsetRayAtReceiver ? "receiver end" : "off (normals)")
     << "\n";
  os << indent << "SkipRadius: " << this->SkipRadius << "\n";
  os << indent << "Voxelized: " << (in.HasGrid ? "yes" : "no") << "\n";
  if (in.HasGrid)
  {
    os << indent << "LastGrid: " << in.Grid.width << " x " << in.Grid.height << " x "
       << in.Grid.slices << " over [" << in.Grid.near_depth << ", " << in.Grid.far_depth << "]\n";
    os << indent << "LastProjection: " << (in.Projection.parallel ? "parallel" : "perspective")
       << "\n";
  }
  os << indent << "Triangles: " << in.Triangles << "\n";
  os << indent << "DrawnProps: " << in.DrawnProps << "\n";
  os << indent << "SkippedProps: " << in.SkippedProps << "\n";
  os << indent << "CachedGeometries: " << in.Geometry.GetNumberOfCachedGeometries() << "\n";
}
