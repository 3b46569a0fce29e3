#include "vtk_glew.h"

#include "vtkMRGIImperfectShadowMaps.h"

#include "vtkActor.h"
#include "vtkAssemblyNode.h"
#include "vtkAssemblyPath.h"
#include "vtkCellArray.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIResourceStatistics.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIStageResources.h"
#include "vtkMRGIViewSamples.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkOpenGLVertexBufferObject.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include "vtkMRGIISMPointsFS.h"
#include "vtkMRGIISMPointsVS.h"
#include "vtkMRGIISMProjection.h"
#include "vtkMRGIISMPushPullFS.h"

#include "mrgi_vpl.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIImperfectShadowMaps);

namespace
{
void ClearGLErrors()
{
  for (int k = 0; k < 16 && glGetError() != GL_NO_ERROR; ++k)
  {
  }
}

// One polydata the scene draws opaque, with its object -> world matrix.
struct Piece
{
  vtkMatrix4x4* Matrix;
  vtkPolyData* Data;
};

// The polydata `mapper` draws: its vtkPolyData input, or the vtkPolyData
// leaves of a composite input (ParaView's representations) that a
// vtkCompositePolyDataMapper2's display attributes leave visible and
// opaque; as vtkMRGIVoxelGeometry collects them.
void PolyDataLeaves(vtkMapper* mapper, std::vector<vtkPolyData*>& leaves)
{
  leaves.clear();
  vtkDataObject* input = mapper->GetInputDataObject(0, 0);
  if (auto* data = vtkPolyData::SafeDownCast(input))
  {
    leaves.push_back(data);
    return;
  }
  auto* composite = vtkCompositeDataSet::SafeDownCast(input);
  auto* compositeMapper = vtkCompositePolyDataMapper2::SafeDownCast(mapper);
  if (!composite || !compositeMapper)
  {
    return;
  }
  vtkCompositeDataDisplayAttributes* attributes =
    compositeMapper->GetCompositeDataDisplayAttributes();
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(composite->NewIterator());
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    auto* data = vtkPolyData::SafeDownCast(it->GetCurrentDataObject());
    if (data &&
      !(attributes && attributes->HasBlockVisibility(data) && !attributes->GetBlockVisibility(data)) &&
      !(attributes && attributes->HasBlockOpacity(data) && attributes->GetBlockOpacity(data) < 1.0))
    {
      leaves.push_back(data);
    }
  }
}

vtkTextureObject* NewDepthTexture(vtkOpenGLRenderWindow* window, int w, int h)
{
  vtkTextureObject* t = vtkTextureObject::New();
  t->SetContext(window);
  t->SetMinificationFilter(vtkTextureObject::Nearest);
  t->SetMagnificationFilter(vtkTextureObject::Nearest);
  t->SetWrapS(vtkTextureObject::ClampToEdge);
  t->SetWrapT(vtkTextureObject::ClampToEdge);
  if (!t->Allocate2D(static_cast<unsigned int>(w), static_cast<unsigned int>(h), 1, VTK_FLOAT))
  {
    t->Delete();
    return nullptr;
  }
  vtkMRGIResourceStatistics::RecordTextureAllocation(w, h, 4);
  return t;
}
}

struct vtkMRGIImperfectShadowMaps::Internals
{
  vtkWeakPointer<vtkOpenGLRenderWindow> Window;
  vtkMRGIStageResources GL;
  // Mip levels of the atlas: Pulled[0] receives the points, Pulled[k] the
  // pull of level k; Pushed[k] (k < L) the push; Pushed[0] is the atlas.
  std::vector<vtkTextureObject*> Pulled;
  std::vector<vtkTextureObject*> Pushed;
  vtkOpenGLVertexBufferObject* PointBuffer = nullptr;
  vtkOpenGLVertexArrayObject* PointArray = nullptr;
  mrgi_ism_atlas_layout Layout{};
  bool HasAtlas = false;
  bool AtlasPushPulled = false; // the atlas is Pushed[0] (else Pulled[0])

  // The scene's point set (Update()).
  std::vector<float> Vertices;    // world xyz (actor matrices applied)
  std::vector<int32_t> Triangles; // 3 per triangle; empty for a point cloud
  std::vector<double> ViewSamples, Weights, Cdf;
  std::vector<mrgi_ism_point> Records;
  std::vector<float> Points; // world xyz of the records
  std::string Topology;      // what restarts the records when it changes
  vtkMTimeType VertexTime = 0;
  long long Frame = 0;
  int RecordsMode = -1;        // the PointMode the records were drawn for
  unsigned int RecordsSeed = 0; // and the Seed
  vtkIdType Resampled = 0;
  vtkMRGIViewSamples OwnSamples; // view samples when Update() is given none
  vtkRenderTimerLog* Timer = nullptr; // Update()'s, for Render()'s steps

  bool HasResources() const
  {
    return !this->Pulled.empty() || this->PointBuffer || this->PointArray ||
      this->GL.FrameBuffer;
  }

  void ReleaseTextures(vtkWindow* w)
  {
    for (std::vector<vtkTextureObject*>* chain : { &this->Pulled, &this->Pushed })
    {
      for (vtkTextureObject* t : *chain)
      {
        if (w)
        {
          t->ReleaseGraphicsResources(w);
        }
        t->Delete();
      }
      chain->clear();
    }
    this->HasAtlas = false;
  }

  void ReleaseGL(vtkWindow* w)
  {
    this->ReleaseTextures(w);
    this->GL.Release(w);
    if (this->PointBuffer)
    {
      if (w)
      {
        this->PointBuffer->ReleaseGraphicsResources();
      }
      this->PointBuffer->Delete();
      this->PointBuffer = nullptr;
    }
    if (this->PointArray)
    {
      if (w)
      {
        this->PointArray->ReleaseGraphicsResources();
      }
      this->PointArray->Delete();
      this->PointArray = nullptr;
    }
    this->Window = nullptr;
    this->Layout = mrgi_ism_atlas_layout{};
  }

  // Resources live in one context: moving to another window frees them in
  // the old one (or forgets them when that window, and its context, is
  // gone). The point set is kept: it does not depend on the context.
  void UseWindow(vtkOpenGLRenderWindow* window)
  {
    if (this->Window != window && this->HasResources())
    {
      vtkOpenGLRenderWindow* old = this->Window;
      if (old)
      {
        old->MakeCurrent();
      }
      this->ReleaseGL(old);
    }
    this->Window = window;
    window->MakeCurrent();
  }
};

//------------------------------------------------------------------------------
vtkMRGIImperfectShadowMaps::vtkMRGIImperfectShadowMaps()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkMRGIImperfectShadowMaps::~vtkMRGIImperfectShadowMaps()
{
  Internals& in = *this->Internal;
  if (in.HasResources())
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  in.ReleaseTextures(nullptr);
  if (in.PointBuffer)
  {
    in.PointBuffer->Delete();
  }
  if (in.PointArray)
  {
    in.PointArray->Delete();
  }
}

//------------------------------------------------------------------------------
void vtkMRGIImperfectShadowMaps::ReleaseGraphicsResources(vtkWindow* w)
{
  Internals& in = *this->Internal;
  in.ReleaseGL(w);
  // The point set goes too (the header's contract): the next Update() restarts it.
  in.Topology.clear();
  in.Records.clear();
  in.Points.clear();
  in.Frame = 0;
  in.OwnSamples.Invalidate(); // read from a G-buffer that may be gone
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIImperfectShadowMaps::GetAtlasTexture() const
{
  const Internals& in = *this->Internal;
  if (!in.HasAtlas || in.Pulled.empty())
  {
    return nullptr;
  }
  // Without push-pull (or a 1 x 1 tile: one level) the drawn level 0 is the atlas.
  return in.AtlasPushPulled && !in.Pushed.empty() ? in.Pushed[0] : in.Pulled[0];
}

const mrgi_ism_atlas_layout& vtkMRGIImperfectShadowMaps::GetLayout() const
{
  return this->Internal->Layout;
}

vtkIdType vtkMRGIImperfectShadowMaps::GetNumberOfPoints() const
{
  return static_cast<vtkIdType>(this->Internal->Records.size());
}

const mrgi_ism_point* vtkMRGIImperfectShadowMaps::GetPointRecords() const
{
  return this->Internal->Records.empty() ? nullptr : this->Internal->Records.data();
}

const float* vtkMRGIImperfectShadowMaps::GetPointPositions() const
{
  return this->Internal->Points.empty() ? nullptr : this->Internal->Points.data();
}

vtkIdType vtkMRGIImperfectShadowMaps::GetNumberOfTriangles() const
{
  return static_cast<vtkIdType>(this->Internal->Triangles.size() / 3);
}

vtkIdType vtkMRGIImperfectShadowMaps::GetNumberOfResampledPoints() const
{
  return this->Internal->Resampled;
}

vtkIdType vtkMRGIImperfectShadowMaps::GetNumberOfViewSamples() const
{
  return static_cast<vtkIdType>(this->Internal->ViewSamples.size() / 3);
}

//------------------------------------------------------------------------------
bool vtkMRGIImperfectShadowMaps::Render(vtkOpenGLRenderWindow* window, const float* points,
  int pointCount, vtkTextureObject* vpls, int vplCount)
{
  Internals& in = *this->Internal;
  in.HasAtlas = false;
  if (!window || window->GetNeverRendered())
  {
    vtkErrorMacro("Render: needs an OpenGL render window that has rendered once");
    return false;
  }
  if (pointCount < 0 || (pointCount > 0 && !points))
  {
    vtkErrorMacro("Render: " << pointCount << " points and " << (points ? "an" : "no")
                             << " array: needs pointCount >= 0 xyz points");
    return false;
  }
  if (!vpls || vplCount < 1 || static_cast<int>(vpls->GetWidth()) < MRGI_VPL_TEXELS ||
    static_cast<int>(vpls->GetHeight()) < vplCount)
  {
    vtkErrorMacro("Render: needs a VPL texture (" << MRGI_VPL_TEXELS << " x V texels, mrgi_vpl.h) "
                                                  << "holding vplCount = " << vplCount
                                                  << " >= 1 VPLs");
    return false;
  }
  mrgi_ism_atlas_layout layout;
  mrgi_error err;
  if (mrgi_ism_atlas_layout_make(vplCount, this->TileSize, &layout, &err) != MRGI_OK)
  {
    vtkErrorMacro("Render: " << err.message);
    return false;
  }
  in.UseWindow(window);
  ClearGLErrors();
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  if (layout.width > maxSize || layout.height > maxSize)
  {
    vtkErrorMacro("Render: the " << layout.width << " x " << layout.height
                                 << " atlas is larger than GL_MAX_TEXTURE_SIZE " << maxSize);
    return false;
  }

  // ---- resources: the mip chains (levels 0..L, L = log2 T) ----
  int levels = 0;
  for (int s = layout.tile_size; s >= 1; s >>= 1)
  {
    ++levels;
  }
  if (in.Pulled.empty() || in.Layout.width != layout.width || in.Layout.height != layout.height ||
    in.Layout.tile_size != layout.tile_size)
  {
    in.ReleaseTextures(window);
    for (int k = 0; k < levels; ++k)
    {
      vtkTextureObject* a = NewDepthTexture(window, layout.width >> k, layout.height >> k);
      vtkTextureObject* b =
        k + 1 < levels ? NewDepthTexture(window, layout.width >> k, layout.height >> k) : nullptr;
      if (a)
      {
        in.Pulled.push_back(a);
      }
      if (b)
      {
        in.Pushed.push_back(b);
      }
      if (!a || (k + 1 < levels && !b))
      {
        vtkErrorMacro("Render: could not allocate the R32F atlas level "
          << k << " (" << (layout.width >> k) << " x " << (layout.height >> k) << ")");
        in.ReleaseTextures(window);
        return false;
      }
    }
  }
  in.Layout = layout;
  in.GL.Prepare(window);
  if (!in.PointBuffer)
  {
    in.PointBuffer = vtkOpenGLVertexBufferObject::New();
    in.PointArray = vtkOpenGLVertexArrayObject::New();
  }

  // ---- programs ----
  const std::string header = "//VTK::System::Dec\n" + vtkMRGIShaderUtilities::Defines();
  const std::string vs = header + vtkMRGIISMProjection + vtkMRGIISMPointsVS;
  const std::string fs = header + vtkMRGIISMPointsFS;
  vtkShaderProgram* program =
    window->GetShaderCache()->ReadyShaderProgram(vs.c_str(), fs.c_str(), "");
  if (!program || !program->GetCompiled())
  {
    vtkErrorMacro("Render: could not build the ISM point shader");
    return false;
  }
  bool ok = true;
  {
    // ---- step 3: all points in one GL_POINTS draw, nearest kept (GL_MIN) ----
    vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
    vtkOpenGLState* ostate = steps.GetState();
    vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
    vtkOpenGLState::ScopedglEnableDisable cull(ostate, GL_CULL_FACE);
    vtkOpenGLState::ScopedglColorMask colorMask(ostate);
    ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    steps.Target(in.Pulled[0], nullptr, 0, 0, layout.width, layout.height);
    // glClearBufferfv: float targets take the value unclamped.
    const GLfloat empty[4] = { MRGI_ISM_EMPTY_DEPTH, 0.0f, 0.0f, 1.0f };
    glClearBufferfv(GL_COLOR, 0, empty);
    if (pointCount > 0)
    {
      vtkMRGIShaderUtilities::ScopedStage draw(in.Timer, "ism.draw");
      program->SetUniformi("mrgiVPLCount", vplCount);
      program->SetUniformi("mrgiTileSize", layout.tile_size);
      program->SetUniformi("mrgiTilesPerRow", layout.tiles_per_row);
      const float atlasSize[2] = { static_cast<float>(layout.width),
        static_cast<float>(layout.height) };
      program->SetUniform2f("mrgiAtlasSize", atlasSize);
      vpls->Activate();
      program->SetUniformi("mrgiVPLs", vpls->GetTextureUnit());
      in.PointArray->Bind();
      in.PointBuffer->Upload(
        points, static_cast<size_t>(pointCount) * 3, vtkOpenGLBufferObject::ArrayBuffer);
      if (!in.PointArray->AddAttributeArray(
            program, in.PointBuffer, "mrgiPoint", 0, 3 * sizeof(float), VTK_FLOAT, 3, false))
      {
        vtkErrorMacro("Render: could not bind the point positions");
        ok = false;
      }
      else
      {
        ostate->vtkglEnable(GL_BLEND);
        ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
        ostate->vtkglBlendEquationSeparate(GL_MIN, GL_MIN);
        // One-texel points whatever glPointSize a VTK mapper left behind:
        // the vertex shader writes gl_PointSize = 1 (vtkOpenGLState does not
        // track GL_PROGRAM_POINT_SIZE; restored by hand).
        const bool programPointSize = glIsEnabled(GL_PROGRAM_POINT_SIZE) == GL_TRUE;
        glEnable(GL_PROGRAM_POINT_SIZE);
        glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(pointCount));
        if (!programPointSize)
        {
          glDisable(GL_PROGRAM_POINT_SIZE);
        }
        ostate->vtkglBlendEquationSeparate(GL_FUNC_ADD, GL_FUNC_ADD);
        ostate->vtkglDisable(GL_BLEND);
      }
      in.PointArray->Release();
      vpls->Deactivate();
    }

    // ---- step 4: push-pull, one full-screen pass per level and direction ----
    vtkMRGIShaderUtilities::ScopedStage pushPull(in.Timer, "ism.pushpull");
    // Levels 0..used-1 take part: the pull fills levels 1..used-1, the push
    // levels used-2..0 (mrgi_ism_push_pull's K = used - 1).
    const int used = std::min(levels, this->PushPullLevels + 1);
    in.AtlasPushPulled = used > 1;
    for (int stage = 0; ok && used > 1 && stage < 2; ++stage)
    {
      vtkOpenGLQuadHelper* quad = in.GL.Programs.Ready(window, stage == 0 ? "ism.pull" : "ism.push",
        "#define MRGI_ISM_PUSH_PULL_STAGE " + std::to_string(stage) + "\n",
        [] { return std::string(vtkMRGIISMPushPullFS); });
      if (!quad)
      {
        vtkErrorMacro("Render: could not build the ISM push-pull shader");
        ok = false;
        break;
      }
      for (int step = 0; step < used - 1; ++step)
      {
        // Pull: levels 1..K from the finer one; push: levels K-1..0.
        const int k = stage == 0 ? step + 1 : used - 2 - step;
        vtkTextureObject* target = stage == 0 ? in.Pulled[k] : in.Pushed[k];
        vtkTextureObject* a = stage == 0 ? in.Pulled[k - 1] : in.Pulled[k];
        vtkTextureObject* b =
          stage == 0 ? in.Pulled[k] : (k + 1 == used - 1 ? in.Pulled[k + 1] : in.Pushed[k + 1]);
        steps.Target(target, nullptr, 0, 0, layout.width >> k, layout.height >> k);
        if (stage == 0)
        {
          vtkMRGIFullScreenStep::BindInputs(quad->Program, { a });
          quad->Render();
          vtkMRGIFullScreenStep::UnbindInputs({ a });
        }
        else
        {
          vtkMRGIFullScreenStep::BindInputs(quad->Program, { a, b });
          quad->Render();
          vtkMRGIFullScreenStep::UnbindInputs({ a, b });
        }
      }
    }
  }
  const GLenum error = glGetError();
  if (ok && error != GL_NO_ERROR)
  {
    vtkErrorMacro("Render: OpenGL error 0x" << std::hex << error << std::dec);
    ok = false;
  }
  in.HasAtlas = ok;
  return ok;
}

//------------------------------------------------------------------------------
// Step 1 (class comment): the world-space triangles of the visible opaque
// actors, or, when there are none, the points of point-cloud actors (verts
// with normals, mrgi_ism_points.h section 4). `topology` names what the
// records index (actors, their data and cells); vertices are re-read when
// only the points or the actor matrices changed.
bool vtkMRGIImperfectShadowMaps::CollectScene(vtkRenderer* ren)
{
  Internals& in = *this->Internal;
  std::vector<Piece> meshes, clouds;
  std::string topology;
  vtkMTimeType vertexTime = 0;
  std::vector<vtkPolyData*> leaves;
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator pit;
  props->InitTraversal(pit);
  while (vtkProp* prop = props->GetNextProp(pit))
  {
    if (!prop->GetVisibility())
    {
      continue;
    }
    prop->InitPathTraversal();
    while (vtkAssemblyPath* path = prop->GetNextPath()) // assemblies: one path per part
    {
      vtkActor* actor = vtkActor::SafeDownCast(path->GetLastNode()->GetViewProp());
      vtkMapper* mapper = actor ? actor->GetMapper() : nullptr;
      if (!mapper || !actor->GetVisibility() || !actor->HasOpaqueGeometry())
      {
        continue; // translucent, invisible, volumes, 2D props
      }
      vtkMatrix4x4* matrix = (path->GetNumberOfItems() > 1 && path->GetLastNode()->GetMatrix())
        ? path->GetLastNode()->GetMatrix()
        : actor->GetMatrix();
      PolyDataLeaves(mapper, leaves);
      for (vtkPolyData* data : leaves)
      {
        const bool surface = data->GetNumberOfPolys() + data->GetNumberOfStrips() > 0;
        const bool cloud =
          !surface && data->GetNumberOfVerts() > 0 && data->GetPointData()->GetNormals();
        if (data->GetNumberOfPoints() == 0 || (!surface && !cloud))
        {
          continue;
        }
        (surface ? meshes : clouds).push_back(Piece{ matrix, data });
        topology += std::to_string(reinterpret_cast<uintptr_t>(data)) + ":" +
          std::to_string(data->GetNumberOfPoints()) + ":" +
          std::to_string(surface ? data->GetPolys()->GetMTime() : data->GetVerts()->GetMTime()) +
          ":" + std::to_string(data->GetStrips()->GetMTime()) + ";";
        vertexTime = std::max(
          { vertexTime, actor->GetMTime(), matrix->GetMTime(), data->GetPoints()->GetMTime() });
      }
    }
  }
  const std::vector<Piece>& used = meshes.empty() ? clouds : meshes;
  if (used.empty())
  {
    return false;
  }
  const bool restart = topology != in.Topology;
  if (!restart && vertexTime == in.VertexTime)
  {
    return true;
  }
  in.Vertices.clear();
  if (restart)
  {
    in.Triangles.clear();
  }
  for (const Piece& piece : used)
  {
    vtkPolyData* data = piece.Data;
    vtkMatrix4x4* m = piece.Matrix;
    const int32_t base = static_cast<int32_t>(in.Vertices.size() / 3);
    for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
    {
      double p[4] = { 0, 0, 0, 1 };
      data->GetPoint(i, p);
      m->MultiplyPoint(p, p);
      for (int k = 0; k < 3; ++k)
      {
        in.Vertices.push_back(static_cast<float>(p[k] / p[3]));
      }
    }
    if (restart && !meshes.empty())
    {
      vtkIdType n = 0;
      const vtkIdType* ids = nullptr;
      vtkCellArray* polys = data->GetPolys();
      for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
      {
        for (vtkIdType k = 1; k + 1 < n; ++k) // fan
        {
          in.Triangles.insert(in.Triangles.end(),
            { base + static_cast<int32_t>(ids[0]), base + static_cast<int32_t>(ids[k]),
              base + static_cast<int32_t>(ids[k + 1]) });
        }
      }
      vtkCellArray* strips = data->GetStrips();
      for (strips->InitTraversal(); strips->GetNextCell(n, ids);)
      {
        for (vtkIdType k = 0; k + 2 < n; ++k) // alternating orientation
        {
          const vtkIdType a = ids[k], b = ids[k + 1 + (k & 1)], c = ids[k + 2 - (k & 1)];
          in.Triangles.insert(in.Triangles.end(), { base + static_cast<int32_t>(a),
                                                    base + static_cast<int32_t>(b),
                                                    base + static_cast<int32_t>(c) });
        }
      }
    }
  }
  in.Topology = topology;
  in.VertexTime = vertexTime;
  if (restart)
  {
    in.Records.clear(); // a new topology restarts the point set
  }
  return !meshes.empty() ? !in.Triangles.empty() : true;
}

//------------------------------------------------------------------------------
// A sparse, regular subsample (at most vtkMRGIViewSamples::MaxPositions) of
// the frame's valid G-buffer positions, in world space: the view samples of
// RIHKS11 5.2, from `samples` (read back only when the frame changed).
void vtkMRGIImperfectShadowMaps::ReadViewSamples(
  const vtkMRGIFrameContext& frame, vtkMRGIViewSamples& samples)
{
  Internals& in = *this->Internal;
  in.ViewSamples.clear();
  std::string error;
  if (frame.Position && samples.Update(frame, vtkMRGIViewSamples::Positions, 0, error))
  {
    in.ViewSamples = samples.GetPositions();
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIImperfectShadowMaps::Update(const vtkMRGIFrameContext& frame, vtkTextureObject* vpls,
  int vplCount, vtkMRGIViewSamples* shared)
{
  Internals& in = *this->Internal;
  in.HasAtlas = false;
  in.Resampled = 0;
  if (!frame.Window || !frame.Renderer)
  {
    vtkErrorMacro("Update: the frame has no window or renderer");
    return false;
  }
  mrgi_ism_atlas_layout layout;
  mrgi_error err;
  if (mrgi_ism_atlas_layout_make(vplCount, this->TileSize, &layout, &err) != MRGI_OK)
  {
    vtkErrorMacro("Update: " << err.message);
    return false;
  }
  const long long total = static_cast<long long>(this->PointsPerVPL) * vplCount;
  if (total > MRGI_ISM_MAX_POINTS)
  {
    vtkErrorMacro("Update: " << this->PointsPerVPL << " points x " << vplCount << " VPLs = "
                             << total << " points, more than MRGI_ISM_MAX_POINTS "
                             << MRGI_ISM_MAX_POINTS);
    return false;
  }
  const int P = static_cast<int>(total);
  {
    vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "ism.points");
    if (!this->CollectScene(frame.Renderer))
    {
      vtkErrorMacro("Update: no opaque geometry to draw shadow-map points from (no visible "
                    "opaque actor with triangles, or point cloud with normals)");
      in.Topology.clear();
      in.Records.clear();
      in.Points.clear();
      return false;
    }
    const bool cloud = in.Triangles.empty();
    const int32_t nv = static_cast<int32_t>(in.Vertices.size() / 3);
    const int32_t nt = static_cast<int32_t>(in.Triangles.size() / 3);
    const int32_t count = cloud ? nv : nt;
    // Weights: this frame's view samples (adaptive modes), uniform without any.
    mrgi_ism_mode mode = static_cast<mrgi_ism_mode>(this->PointMode);
    in.ViewSamples.clear();
    if (mode != MRGI_ISM_UNIFORM)
    {
      in.UseWindow(frame.Window);
      in.GL.Prepare(frame.Window);
      this->ReadViewSamples(frame, shared ? *shared : in.OwnSamples);
    }
    const int32_t views = static_cast<int32_t>(in.ViewSamples.size() / 3);
    if (views == 0)
    {
      mode = MRGI_ISM_UNIFORM;
    }
    in.Weights.resize(static_cast<size_t>(count));
    in.Cdf.resize(static_cast<size_t>(count) + 1);
    const double* viewData = views ? in.ViewSamples.data() : nullptr;
    mrgi_status s = cloud
      ? mrgi_ism_cloud_weights(in.Vertices.data(), nv, mode, viewData, views, in.Weights.data(), &err)
      : mrgi_ism_triangle_weights(in.Vertices.data(), nv, in.Triangles.data(), nt, mode, viewData,
          views, this->Seed, in.Weights.data(), &err);
    if (s == MRGI_OK)
    {
      s = mrgi_ism_cdf_build(in.Weights.data(), count, in.Cdf.data(), &err);
    }
    // Records: a new point set draws all of them (generation 0); otherwise
    // the lazy update redraws 1 / LazyFrames of them (RIHKS11 5.3).
    int32_t begin = 0, end = P;
    uint32_t generation = 0;
    // Another count, point mode or seed is another distribution: the lazy
    // update would mix the two for LazyFrames frames, so all are redrawn.
    if (static_cast<int>(in.Records.size()) != P || in.RecordsMode != this->PointMode ||
      in.RecordsSeed != this->Seed)
    {
      in.Records.assign(static_cast<size_t>(P), mrgi_ism_point{});
      in.Frame = 0;
      in.RecordsMode = this->PointMode;
      in.RecordsSeed = this->Seed;
    }
    else
    {
      mrgi_ism_lazy_range_n(P, in.Frame, this->LazyFrames, &begin, &end);
      generation = mrgi_ism_lazy_generation_n(in.Frame, this->LazyFrames);
      ++in.Frame;
    }
    if (s == MRGI_OK)
    {
      s = mrgi_ism_sample(
        in.Cdf.data(), count, this->Seed, generation, P, begin, end, in.Records.data(), &err);
    }
    in.Points.resize(static_cast<size_t>(P) * 3);
    if (s == MRGI_OK && !cloud)
    {
      s = mrgi_ism_points_evaluate(in.Vertices.data(), nv, in.Triangles.data(), nt,
        in.Records.data(), P, in.Points.data(), nullptr, &err);
    }
    else if (s == MRGI_OK)
    {
      for (int i = 0; i < P; ++i)
      {
        std::copy_n(&in.Vertices[3 * static_cast<size_t>(in.Records[i].index)], 3, &in.Points[3 * i]);
      }
    }
    if (s != MRGI_OK)
    {
      vtkErrorMacro("Update: " << err.message);
      in.Topology.clear();
      in.Records.clear();
      in.Points.clear();
      return false;
    }
    in.Resampled = end - begin;
  }
  in.Timer = frame.Timer;
  const bool ok = this->Render(frame.Window, in.Points.data(), P, vpls, vplCount);
  in.Timer = nullptr;
  return ok;
}

//------------------------------------------------------------------------------
bool vtkMRGIImperfectShadowMaps::ReadAtlas(vtkRenderWindow* window, vtkFloatArray* depth)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!renWin || !depth || renWin != in.Window)
  {
    vtkErrorMacro("ReadAtlas: needs the window of the last Update()/Render() and an array");
    return false;
  }
  vtkTextureObject* atlas = this->GetAtlasTexture();
  if (!atlas)
  {
    vtkErrorMacro("ReadAtlas: no atlas (no successful Update()/Render())");
    return false;
  }
  const int w = in.Layout.width, h = in.Layout.height;
  depth->SetNumberOfComponents(1);
  depth->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  renWin->MakeCurrent();
  ClearGLErrors();
  vtkOpenGLState* ostate = renWin->GetState();
  ostate->PushReadFramebufferBinding();
  in.GL.FrameBuffer->Bind(GL_READ_FRAMEBUFFER);
  in.GL.FrameBuffer->AddColorAttachment(0, atlas);
  in.GL.FrameBuffer->ActivateReadBuffer(0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, w, h, GL_RED, GL_FLOAT, depth->GetPointer(0));
  in.GL.FrameBuffer->RemoveColorAttachments(1);
  ostate->PopReadFramebufferBinding();
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("ReadAtlas: OpenGL error 0x" << std::hex << error << std::dec);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIImperfectShadowMaps::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const Internals& in = *this->Internal;
  static const char* modes[] = { "Uniform", "Adaptive1", "Adaptive8" };
  os << indent << "PointMode: " << modes[this->PointMode] << "\n";
  os << indent << "PointsPerVPL: " << this->PointsPerVPL << "\n";
  os << indent << "TileSize: " << this->TileSize << "\n";
  os << indent << "LazyFrames: " << this->LazyFrames << "\n";
  os << indent << "PushPullLevels: " << this->PushPullLevels << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Atlas: "
     << (in.HasAtlas ? std::to_string(in.Layout.width) + " x " + std::to_string(in.Layout.height) +
           " (" + std::to_string(in.Layout.vpl_count) + " VPLs)"
                     : std::string("none"))
     << "\n";
  os << indent << "Points: " << in.Records.size() << " on " << in.Triangles.size() / 3
     << " triangles\n";
  os << indent << "Frame: " << in.Frame << "\n";
}
