#include "vtkMRGIReflectiveShadowMapPass.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkMapper.h"
#include "vtkPolyData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkInformationObjectBaseVectorKey.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkRenderState.h"
#include "vtkRenderbuffer.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"

#include "vtkMRGIAreaLightRSMViews.h"
#include "vtkMRGIRSMCapture.h"
#include "vtkMRGIRSMCompositor.h"
#include "vtkMRGIRSMDecl.h"
#include "vtkMRGIRSMView.h"
#include "vtkMRGIResourceStatistics.h"
#include "vtkMRGISceneChecks.h"
#include "vtkMRGIShaderUtilities.h"

#include "mrgi_buffers.h"
#include "mrgi_rsm_composite.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkMRGIReflectiveShadowMapPass);
vtkCxxSetObjectMacro(vtkMRGIReflectiveShadowMapPass, Compositor, vtkMRGIRSMCompositor);

namespace
{
using View = vtkMRGIRSMView;

void Normalize(double v[3])
{
  const double n = vtkMath::Norm(v);
  if (n > 0)
  {
    v[0] /= n;
    v[1] /= n;
    v[2] /= n;
  }
}

// Whether the box `bounds` can intersect the frustum of `worldToClip` (all
// eight corners outside one clip plane means it cannot).
bool BoxMayIntersect(vtkMatrix4x4* worldToClip, const double bounds[6])
{
  int outside[6] = { 0, 0, 0, 0, 0, 0 };
  for (int i = 0; i < 8; ++i)
  {
    const double p[4] = { bounds[i & 1], bounds[2 + ((i >> 1) & 1)], bounds[4 + ((i >> 2) & 1)], 1 };
    double c[4];
    worldToClip->MultiplyPoint(p, c);
    outside[0] += c[0] < -c[3];
    outside[1] += c[0] > c[3];
    outside[2] += c[1] < -c[3];
    outside[3] += c[1] > c[3];
    outside[4] += c[2] < -c[3];
    outside[5] += c[2] > c[3];
  }
  return std::none_of(std::begin(outside), std::end(outside), [](int n) { return n == 8; });
}
}

struct vtkMRGIReflectiveShadowMapPass::Internals
{
  // Data time of each prop's input when it was last checked for NaN/Inf.
  std::map<vtkProp*, vtkMTimeType> CheckedInput;
  std::vector<std::unique_ptr<View>> Views;
  vtkOpenGLFramebufferObject* FrameBuffer = nullptr;
  // The maps' depth buffer, sized to Resolution (see Render()).
  vtkSmartPointer<vtkRenderbuffer> Depth;
  std::string Signature;
  vtkTimeStamp ContentTime;
  View* Current = nullptr;
  vtkNew<vtkMRGIAreaLightRSMViews> AreaViews;

  void ReleaseDepth(vtkWindow* w)
  {
    if (this->Depth)
    {
      this->Depth->ReleaseGraphicsResources(w);
    }
    this->Depth = nullptr;
  }

  void ReleaseView(View& view, vtkWindow* w)
  {
    for (auto*& t : view.Textures)
    {
      if (t)
      {
        t->ReleaseGraphicsResources(w);
        t->Delete();
        t = nullptr;
      }
    }
  }
};

//------------------------------------------------------------------------------
vtkMRGIReflectiveShadowMapPass::vtkMRGIReflectiveShadowMapPass()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkMRGIReflectiveShadowMapPass::~vtkMRGIReflectiveShadowMapPass()
{
  this->SetCompositor(nullptr);
  if (this->Internal->FrameBuffer)
  {
    vtkErrorMacro("FrameBuffer should have been deleted in ReleaseGraphicsResources().");
    this->Internal->FrameBuffer->Delete();
  }
  for (auto& view : this->Internal->Views)
  {
    for (auto* t : view->Textures)
    {
      if (t)
      {
        t->Delete();
      }
    }
  }
}

//------------------------------------------------------------------------------
void vtkMRGIReflectiveShadowMapPass::ReleaseGraphicsResources(vtkWindow* w)
{
  for (auto& view : this->Internal->Views)
  {
    this->Internal->ReleaseView(*view, w);
  }
  this->Internal->Views.clear();
  if (this->Internal->FrameBuffer)
  {
    this->Internal->FrameBuffer->ReleaseGraphicsResources(w);
    this->Internal->FrameBuffer->Delete();
    this->Internal->FrameBuffer = nullptr;
  }
  this->Internal->ReleaseDepth(w);
  this->Internal->Signature.clear();
}

//------------------------------------------------------------------------------
int vtkMRGIReflectiveShadowMapPass::GetNumberOfViews() const
{
  return static_cast<int>(this->Internal->Views.size());
}

vtkTextureObject* vtkMRGIReflectiveShadowMapPass::GetPositionTexture(int i) const
{
  return (i >= 0 && i < this->GetNumberOfViews())
    ? this->Internal->Views[i]->Textures[MRGI_RSM_POSITION]
    : nullptr;
}

vtkTextureObject* vtkMRGIReflectiveShadowMapPass::GetNormalTexture(int i) const
{
  return (i >= 0 && i < this->GetNumberOfViews())
    ? this->Internal->Views[i]->Textures[MRGI_RSM_NORMAL]
    : nullptr;
}

vtkTextureObject* vtkMRGIReflectiveShadowMapPass::GetFluxTexture(int i) const
{
  return (i >= 0 && i < this->GetNumberOfViews())
    ? this->Internal->Views[i]->Textures[MRGI_RSM_FLUX]
    : nullptr;
}

bool vtkMRGIReflectiveShadowMapPass::ReadView(
  vtkRenderWindow* window, int i, vtkImageData* position, vtkImageData* normal, vtkImageData* flux)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!renWin || i < 0 || i >= this->GetNumberOfViews())
  {
    vtkErrorMacro("ReadView: no view " << i << " (there are " << this->GetNumberOfViews() << ")");
    return false;
  }
  vtkImageData* images[MRGI_RSM_ATTACHMENTS];
  images[MRGI_RSM_POSITION] = position;
  images[MRGI_RSM_NORMAL] = normal;
  images[MRGI_RSM_FLUX] = flux;
  for (int a = 0; a < MRGI_RSM_ATTACHMENTS; ++a)
  {
    std::vector<float> rgba;
    if (!images[a] ||
      !vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, this->Internal->Views[i]->Textures[a], rgba))
    {
      return false;
    }
    images[a]->SetDimensions(this->Resolution, this->Resolution, 1);
    images[a]->AllocateScalars(VTK_FLOAT, 4);
    std::copy(rgba.begin(), rgba.end(),
      vtkFloatArray::SafeDownCast(images[a]->GetPointData()->GetScalars())->GetPointer(0));
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkMRGIReflectiveShadowMapPass::GetViewLight(int i) const
{
  return (i >= 0 && i < this->GetNumberOfViews()) ? this->Internal->Views[i]->Light : -1;
}

bool vtkMRGIReflectiveShadowMapPass::GetViewWorldToView(int i, double worldToView[16]) const
{
  if (i < 0 || i >= this->GetNumberOfViews() || !worldToView)
  {
    return false;
  }
  vtkMatrix4x4::DeepCopy(worldToView, this->Internal->Views[i]->Camera->GetModelViewTransformMatrix());
  return true;
}

bool vtkMRGIReflectiveShadowMapPass::GetViewProjection(int i, double projection[16]) const
{
  if (i < 0 || i >= this->GetNumberOfViews() || !projection)
  {
    return false;
  }
  // The explicit square projection set when the view was built (the aspect is ignored).
  vtkMatrix4x4::DeepCopy(
    projection, this->Internal->Views[i]->Camera->GetProjectionTransformMatrix(1.0, -1, 1));
  return true;
}

bool vtkMRGIReflectiveShadowMapPass::GetViewPerspective(int i) const
{
  return i >= 0 && i < this->GetNumberOfViews() && this->Internal->Views[i]->Perspective;
}

vtkMTimeType vtkMRGIReflectiveShadowMapPass::GetContentTime() const
{
  return this->Internal->ContentTime.GetMTime();
}

//------------------------------------------------------------------------------
void vtkMRGIReflectiveShadowMapPass::Render(const vtkRenderState* s)
{
  this->RenderWithAreaLights(s, nullptr, 0);
}

//------------------------------------------------------------------------------
void vtkMRGIReflectiveShadowMapPass::RenderWithAreaLights(
  const vtkRenderState* s, vtkMRGIAreaLight* const* areaLights, int areaLightCount)
{
  vtkRenderer* renderer = s->GetRenderer();
  vtkOpenGLRenderWindow* renWin =
    vtkOpenGLRenderWindow::SafeDownCast(renderer ? renderer->GetRenderWindow() : nullptr);
  if (!renWin)
  {
    return;
  }

  // What the maps depend on: the visible opaque props (and their data, via
  // the redraw time), the lights as placed this frame, the resolution.
  std::vector<vtkProp*> props;
  std::vector<std::array<double, 6>> propBounds;
  double bounds[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  std::ostringstream signature;
  signature.precision(17);
  signature << this->Resolution << ';';
  vtkPropCollection* viewProps = renderer->GetViewProps();
  vtkCollectionSimpleIterator pit;
  viewProps->InitTraversal(pit);
  while (vtkProp* prop = viewProps->GetNextProp(pit))
  {
    if (!prop->GetVisibility() || !prop->HasOpaqueGeometry())
    {
      continue;
    }
    const double* b = prop->GetBounds();
    if (!b || !(b[0] <= b[1]) || !std::isfinite(b[0] + b[1] + b[2] + b[3] + b[4] + b[5]))
    {
      continue; // no geometry, or non-finite bounds that cannot place a light view
    }
    for (int k = 0; k < 3; ++k)
    {
      bounds[2 * k] = std::min(bounds[2 * k], b[2 * k]);
      bounds[2 * k + 1] = std::max(bounds[2 * k + 1], b[2 * k + 1]);
    }
    props.push_back(prop);
    propBounds.push_back({ { b[0], b[1], b[2], b[3], b[4], b[5] } });
    this->CheckInput(prop);
    signature << prop << ':' << prop->GetRedrawMTime() << ';';
  }

  struct LightInfo
  {
    int Index;
    vtkLight* Light;
  };
  std::vector<LightInfo> lights;
  std::ostringstream lightSignature; // what every rank must agree on (with the resolution)
  lightSignature.precision(17);
  lightSignature << 'S' << this->Resolution << ';';
  vtkLightCollection* lightCollection = renderer->GetLights();
  vtkCollectionSimpleIterator lit;
  lightCollection->InitTraversal(lit);
  int index = 0;
  while (vtkLight* light = lightCollection->GetNextLight(lit))
  {
    const double* color = light->GetDiffuseColor();
    const double power = light->GetIntensity() * std::max({ color[0], color[1], color[2] });
    if (light->GetSwitch() && power > 0 && std::isfinite(power))
    {
      lights.push_back({ index, light });
      double p[3], f[3];
      light->GetTransformedPosition(p);
      light->GetTransformedFocalPoint(f);
      const double* a = light->GetAttenuationValues();
      lightSignature << 'L' << index << ':' << light->GetIntensity() << ',' << color[0] << ','
                     << color[1] << ',' << color[2] << ',' << p[0] << ',' << p[1] << ',' << p[2]
                     << ',' << f[0] << ',' << f[1] << ',' << f[2] << ',' << light->GetPositional()
                     << ',' << light->GetConeAngle() << ',' << light->GetExponent() << ',' << a[0]
                     << ',' << a[1] << ',' << a[2] << ';';
    }
    ++index;
  }
  // Area lights (mrgi_area_light_rsm.h): views from each emitter's centre.
  std::vector<vtkMRGIAreaLightRSMViews::Emitter> areas;
  this->Internal->AreaViews->SampleEmitters(areaLights, areaLightCount, areas, lightSignature);
  signature << lightSignature.str();
  // Maps rendered alone are not composited ones (and the reverse): a new
  // compositor or a new number of processes renders them again.
  signature << "C" << this->Compositor << ':'
            << (this->Compositor ? this->Compositor->GetNumberOfProcesses() : 1) << ';';
  bool changed = signature.str() != this->Internal->Signature || !this->Internal->FrameBuffer;

  // Distributed: one collective decides for all ranks (any rank's change
  // re-renders and composites everywhere: a rank compositing alone would
  // wait forever) and gives every rank the bounds of all ranks' props, which
  // place the views, so that all ranks render the same views.
  const bool distributed = this->Compositor && this->Compositor->GetNumberOfProcesses() > 1;
  const vtkTypeInt64 bytesBefore = this->Compositor ? this->Compositor->GetBytesSent() : 0;
  bool lightsAgree = true;
  this->CompositeBytes = 0;
  if (distributed)
  {
    // std::hash is the same function in every rank of one program; 52 bits
    // survive the trip through a double.
    const double lightHash =
      static_cast<double>(std::hash<std::string>{}(lightSignature.str()) >> 12);
    double global[9] = { -bounds[0], bounds[1], -bounds[2], bounds[3], -bounds[4], bounds[5],
      changed ? 1.0 : 0.0, lightHash, -lightHash };
    if (!this->Compositor->AllReduceMax(global, 9))
    {
      vtkErrorMacro("the processes could not agree on the reflective shadow maps' inputs");
    }
    this->CompositeBytes = this->Compositor->GetBytesSent() - bytesBefore;
    for (int k = 0; k < 6; ++k)
    {
      bounds[k] = (k % 2 == 0) ? -global[k] : global[k];
    }
    changed = global[6] > 0;
    lightsAgree = global[7] == -global[8];
    if (!lightsAgree && changed)
    {
      vtkErrorMacro("the processes disagree on the lights (position, colour, cone or "
                    "attenuation) or the RSM resolution: each renders its own reflective shadow "
                    "maps, uncomposited, and their VPLs differ");
    }
  }
  const bool anyProps = bounds[0] <= bounds[1];
  if (!anyProps || (!distributed && props.empty()))
  {
    lights.clear();
    areas.clear();
  }

  if (!changed)
  {
    return; // nothing the maps depend on changed, on any rank
  }

  // Build the views of every light that can reach the visible props.
  std::vector<std::unique_ptr<View>> views;
  const double S = this->Resolution;
  const double center[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };
  const double radius = 0.5 *
      std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
        (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
        (bounds[5] - bounds[4]) * (bounds[5] - bounds[4])) +
    1e-30;
  for (const LightInfo& info : lights)
  {
    vtkLight* light = info.Light;
    double position[3], focal[3], axis[3];
    light->GetTransformedPosition(position);
    light->GetTransformedFocalPoint(focal);
    vtkMath::Subtract(focal, position, axis);
    Normalize(axis);
    if (vtkMath::Norm(axis) == 0)
    {
      axis[2] = -1; // degenerate light: VTK lights it along -z as well
    }
    const double* color = light->GetDiffuseColor();
    auto makeView = [&]() {
      auto view = std::make_unique<View>();
      view->Light = info.Index;
      for (int k = 0; k < 3; ++k)
      {
        view->LightColor[k] = light->GetIntensity() * color[k];
        view->Attenuation[k] = light->GetAttenuationValues()[k];
      }
      view->SpotExponent = light->GetExponent();
      view->Camera = vtkSmartPointer<vtkCamera>::New();
      return view;
    };

    // Explicit square projections: the window's aspect must not distort them.
    auto setPerspective = [&](View& view, const double dir[3], double fovDeg) {
      view.SetPerspective(position, dir, fovDeg, center, radius, S);
    };

    if (!light->GetPositional())
    {
      // Directional: an orthographic view along the light, fitted to the
      // bounds of the visible props (a sphere around them, so any direction fits).
      auto view = makeView();
      double eye[3] = { center[0] - axis[0] * 2 * radius, center[1] - axis[1] * 2 * radius,
        center[2] - axis[2] * 2 * radius };
      double up[3];
      View::PickUp(axis, up);
      view->Camera->SetPosition(eye);
      view->Camera->SetFocalPoint(center);
      view->Camera->SetViewUp(up);
      vtkNew<vtkMatrix4x4> proj;
      proj->Identity();
      proj->SetElement(0, 0, 1.0 / radius);
      proj->SetElement(1, 1, 1.0 / radius);
      proj->SetElement(2, 2, -2.0 / (4.0 * radius));
      proj->SetElement(2, 3, -(4.0 * radius + radius * 1e-6) / (4.0 * radius));
      view->Camera->SetExplicitProjectionTransformMatrix(proj);
      view->Camera->SetUseExplicitProjectionTransformMatrix(true);
      view->Perspective = false;
      view->TexelSize = 2.0 * radius / S;
      view->Attenuation[0] = 1;
      view->Attenuation[1] = view->Attenuation[2] = 0;
      views.push_back(std::move(view));
      continue;
    }

    const double cone = light->GetConeAngle();
    const bool spot = cone < 90.0;
    if (spot && cone <= MRGI_RSM_MAX_SPOT_HALF_ANGLE_DEG)
    {
      auto view = makeView();
      setPerspective(*view, axis, 2.0 * std::max(cone, 0.01));
      view->SpotCosCutoff = std::cos(vtkMath::RadiansFromDegrees(cone));
      views.push_back(std::move(view));
      continue;
    }
    // Point light (or a very wide spot): the six faces of a cube.
    static const double faces[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 },
      { 0, 0, 1 }, { 0, 0, -1 } };
    for (const auto& face : faces)
    {
      if (spot)
      {
        // Skip faces whose frustum (half-diagonal 54.74 deg) misses the cone.
        const double angle = vtkMath::DegreesFromRadians(std::acos(
          std::max(-1.0, std::min(1.0, vtkMath::Dot(face, axis)))));
        if (angle > cone + 54.75)
        {
          continue;
        }
      }
      auto view = makeView();
      setPerspective(*view, face, 90.0);
      if (spot)
      {
        view->SpotCosCutoff = std::cos(vtkMath::RadiansFromDegrees(cone));
      }
      views.push_back(std::move(view));
      // The spot axis, in this face's eye coordinates.
      View& v = *views.back();
      vtkMatrix4x4* wcvc = v.Camera->GetModelViewTransformMatrix();
      double axis4[4] = { axis[0], axis[1], axis[2], 0 }, out[4];
      wcvc->MultiplyPoint(axis4, out);
      v.SpotAxisVC[0] = out[0];
      v.SpotAxisVC[1] = out[1];
      v.SpotAxisVC[2] = out[2];
    }
  }

  this->Internal->AreaViews->AddViews(areas, center, radius, S, views);

  // Keep only views that reach the visible props; finish their matrices.
  std::vector<int> reaches(views.size(), 0);
  for (size_t i = 0; i < views.size(); ++i)
  {
    View* view = views[i].get();
    vtkMatrix4x4* wcvc = view->Camera->GetModelViewTransformMatrix();
    vtkMatrix4x4::Invert(wcvc, view->VCToWC);
    vtkNew<vtkMatrix4x4> worldToClip;
    vtkMatrix4x4::Multiply4x4(
      view->Camera->GetProjectionTransformMatrix(1.0, -1, 1), wcvc, worldToClip);
    // Prop by prop: the union of the props' bounds holds empty space that
    // a cube face of a light among the props would always reach.
    reaches[i] = std::any_of(propBounds.begin(), propBounds.end(),
      [&](const std::array<double, 6>& b) { return BoxMayIntersect(worldToClip, b.data()); });
  }
  // Distributed: a view is kept where any rank's props reach it (the same
  // lights and bounds gave every rank the same candidate views).
  if (distributed && lightsAgree && !reaches.empty())
  {
    std::vector<double> anyRank(reaches.begin(), reaches.end());
    this->Compositor->AllReduceMax(anyRank.data(), static_cast<int>(anyRank.size()));
    for (size_t i = 0; i < reaches.size(); ++i)
    {
      reaches[i] = anyRank[i] > 0;
    }
  }
  std::vector<std::unique_ptr<View>> kept;
  for (size_t i = 0; i < views.size(); ++i)
  {
    if (reaches[i])
    {
      kept.push_back(std::move(views[i]));
    }
  }

  // Reuse the textures of the previous views where there are as many.
  vtkOpenGLState* ostate = renWin->GetState();
  auto& old = this->Internal->Views;
  for (size_t i = 0; i < kept.size(); ++i)
  {
    if (i < old.size())
    {
      std::copy(std::begin(old[i]->Textures), std::end(old[i]->Textures), kept[i]->Textures);
      std::fill(std::begin(old[i]->Textures), std::end(old[i]->Textures), nullptr);
    }
    for (int a = 0; a < MRGI_RSM_ATTACHMENTS; ++a)
    {
      vtkTextureObject*& t = kept[i]->Textures[a];
      if (!t)
      {
        t = vtkTextureObject::New();
        t->SetContext(renWin);
        t->SetFormat(GL_RGBA);
        // Positions and flux need float range (scene scale 1e-4..1e5, large
        // intensities); normals are unit vectors.
        t->SetInternalFormat(a == MRGI_RSM_NORMAL ? GL_RGBA16F : GL_RGBA32F);
        t->SetDataType(GL_FLOAT);
        t->SetMinificationFilter(vtkTextureObject::Nearest);
        t->SetMagnificationFilter(vtkTextureObject::Nearest);
        t->Allocate2D(this->Resolution, this->Resolution, 4, VTK_FLOAT);
        vtkMRGIResourceStatistics::RecordTextureAllocation(this->Resolution, this->Resolution,
          vtkMRGIShaderUtilities::BytesPerTexel(static_cast<int>(t->GetInternalFormat(VTK_FLOAT, 4, false))));
      }
      vtkMRGIShaderUtilities::ResizeTexture(t, this->Resolution, this->Resolution);
    }
  }
  for (size_t i = kept.size(); i < old.size(); ++i)
  {
    this->Internal->ReleaseView(*old[i], renWin);
  }
  old = std::move(kept);

  if (!this->Internal->FrameBuffer)
  {
    this->Internal->FrameBuffer = vtkOpenGLFramebufferObject::New();
    this->Internal->FrameBuffer->SetContext(renWin);
  }
  vtkOpenGLFramebufferObject* fbo = this->Internal->FrameBuffer;
  // A depth buffer of the maps' size, remade when Resolution changes (the
  // FBO's own is made once: larger maps later were drawn in its corner only).
  if (!this->Internal->Depth ||
    this->Internal->Depth->GetWidth() != static_cast<unsigned int>(this->Resolution))
  {
    this->Internal->ReleaseDepth(renWin);
    this->Internal->Depth = vtkSmartPointer<vtkRenderbuffer>::New();
    this->Internal->Depth->SetContext(renWin);
    if (!this->Internal->Depth->CreateDepthAttachment(this->Resolution, this->Resolution))
    {
      vtkErrorMacro("could not allocate the " << this->Resolution
                                               << "^2 depth buffer of the reflective shadow maps");
      this->ReleaseGraphicsResources(renWin); // no maps (no VPLs) rather than stale ones
      return;
    }
    vtkMRGIResourceStatistics::RecordTextureAllocation(this->Resolution, this->Resolution, 4);
  }

  vtkCamera* savedCamera = renderer->GetActiveCamera();
  savedCamera->Register(this);
  {
    vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
    vtkOpenGLState::ScopedglEnableDisable depth(ostate, GL_DEPTH_TEST);
    vtkOpenGLState::ScopedglEnableDisable scissor(ostate, GL_SCISSOR_TEST);
    vtkOpenGLState::ScopedglViewport viewport(ostate);
    vtkOpenGLState::ScopedglClearColor clearColor(ostate);
    vtkOpenGLState::ScopedglDepthMask depthMask(ostate);
    ostate->vtkglDisable(GL_BLEND);
    ostate->vtkglEnable(GL_DEPTH_TEST);
    ostate->vtkglDisable(GL_SCISSOR_TEST);
    ostate->vtkglDepthMask(GL_TRUE);

    fbo->SaveCurrentBindingsAndBuffers();
    fbo->Bind();
    for (auto& view : this->Internal->Views)
    {
      for (int a = 0; a < MRGI_RSM_ATTACHMENTS; ++a)
      {
        fbo->AddColorAttachment(a, view->Textures[a]);
      }
      vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, MRGI_RSM_ATTACHMENTS);
      fbo->AddDepthAttachment(this->Internal->Depth);
      // Explicit viewport: StartNonOrtho leaves it alone, and VTK's camera
      // pass restores whatever it found (0 x 0 on a surfaceless context).
      ostate->vtkglViewport(0, 0, this->Resolution, this->Resolution);
      ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
      ostate->vtkglClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

      renderer->SetActiveCamera(view->Camera);
      vtkRenderState state(renderer);
      state.SetPropArrayAndCount(props.data(), static_cast<int>(props.size()));
      state.SetFrameBuffer(fbo);
      this->Internal->Current = view.get();
      // The maps are drawn with this pass's shader code only: an enclosing
      // pass's (vtkSSAOPass writing its own targets and selecting its draw
      // buffers, vtkShadowMapPass's light factors) is set aside meanwhile.
      std::vector<std::vector<vtkSmartPointer<vtkObjectBase>>> enclosing(props.size());
      vtkInformationObjectBaseVectorKey* key = vtkOpenGLRenderPass::RenderPasses();
      for (size_t p = 0; p < props.size(); ++p)
      {
        vtkInformation* info = props[p]->GetPropertyKeys();
        for (int i = 0; info && i < key->Length(info); ++i)
        {
          enclosing[p].emplace_back(key->Get(info, i));
        }
        if (info)
        {
          info->Remove(key);
        }
      }
      this->PreRender(&state);
      for (vtkProp* prop : props)
      {
        prop->RenderOpaqueGeometry(renderer);
      }
      this->PostRender(&state);
      for (size_t p = 0; p < props.size(); ++p)
      {
        vtkInformation* info = props[p]->GetPropertyKeys();
        for (const auto& pass : enclosing[p])
        {
          key->Append(info, pass);
        }
      }
      this->Internal->Current = nullptr;
    }
    fbo->UnBind();
    fbo->RestorePreviousBindingsAndBuffers();
  }
  renderer->SetActiveCamera(savedCamera);
  savedCamera->UnRegister(this);

  if (distributed && lightsAgree && !this->Internal->Views.empty())
  {
    this->CompositeViews(renWin);
  }
  if (this->Compositor)
  {
    this->CompositeBytes = this->Compositor->GetBytesSent() - bytesBefore;
  }

  this->Internal->Signature = signature.str();
  this->Internal->ContentTime.Modified();
  this->NumberOfRenders += static_cast<vtkIdType>(this->Internal->Views.size());
  vtkOpenGLCheckErrorMacro("failed after rendering reflective shadow maps");
}

//------------------------------------------------------------------------------
bool vtkMRGIReflectiveShadowMapPass::CompositeViews(vtkOpenGLRenderWindow* renWin)
{
  // One buffer for all views (planar per view, as mrgi_rsm_composite.h
  // lays it out): one message per tree edge.
  const size_t texels =
    static_cast<size_t>(this->Resolution) * static_cast<size_t>(this->Resolution);
  const size_t viewFloats = texels * MRGI_RSM_COMPOSITE_RECORD_FLOATS;
  const size_t count = this->Internal->Views.size();
  std::vector<float> mine(count * viewFloats, 0.0f);
  bool ok = true;
  std::vector<mrgi_rsm_view_key> keys(count);
  for (size_t v = 0; v < count; ++v)
  {
    const View& view = *this->Internal->Views[v];
    for (int a = 0; a < MRGI_RSM_ATTACHMENTS; ++a)
    {
      std::vector<float> rgba;
      if (vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, view.Textures[a], rgba) &&
        rgba.size() == texels * 4)
      {
        std::copy(rgba.begin(), rgba.end(),
          mine.begin() + static_cast<long>(v * viewFloats + a * texels * 4));
      }
      else
      {
        ok = false; // this rank's view stays empty; the others still get theirs
      }
    }
    // Nearest: from the light (perspective), along the view (orthographic).
    mrgi_rsm_view_key& key = keys[v];
    const double* eye = view.Camera->GetPosition();
    const double* focal = view.Camera->GetFocalPoint();
    for (int k = 0; k < 3; ++k)
    {
      key.origin[k] = eye[k];
      key.direction[k] = focal[k] - eye[k];
    }
    key.perspective = view.Perspective ? 1 : 0;
  }
  if (!ok)
  {
    vtkErrorMacro("could not read this process's reflective shadow maps back: "
                  "its geometry is missing from the composited maps");
  }

  if (!this->Compositor->CompositeViews(mine.data(), texels, static_cast<int>(count), keys.data()))
  {
    vtkErrorMacro("the reflective shadow maps could not be composited across the processes");
    ok = false;
  }

  for (size_t v = 0; v < count; ++v)
  {
    for (int a = 0; a < MRGI_RSM_ATTACHMENTS; ++a)
    {
      vtkTextureObject* t = this->Internal->Views[v]->Textures[a];
      t->Bind();
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, this->Resolution, this->Resolution, GL_RGBA, GL_FLOAT,
        mine.data() + v * viewFloats + static_cast<size_t>(a) * texels * 4);
      t->Deactivate();
    }
  }
  ++this->NumberOfComposites;
  vtkOpenGLCheckErrorMacro("failed after uploading the composited reflective shadow maps");
  return ok;
}

//------------------------------------------------------------------------------
bool vtkMRGIReflectiveShadowMapPass::PreReplaceShaderValues(std::string&, std::string&,
  std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp*)
{
  if (vtkOpenGLPolyDataMapper::SafeDownCast(mapper))
  {
    vtkMRGIShaderUtilities::AddCaptureMarkers(fragmentShader);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIReflectiveShadowMapPass::PostReplaceShaderValues(std::string&, std::string&,
  std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp*)
{
  if (!vtkOpenGLPolyDataMapper::SafeDownCast(mapper))
  {
    return true;
  }
  if (vtkMRGIShaderUtilities::CanCapture(fragmentShader))
  {
    vtkMRGIShaderUtilities::InsertCapture(fragmentShader, vtkMRGIRSMDecl, vtkMRGIRSMCapture);
  }
  else
  {
    // Unlit or normal-less geometry reflects nothing into the scene.
    vtkMRGIShaderUtilities::InsertCapture(fragmentShader, "",
      "  gl_FragData[MRGI_RSM_POSITION] = vec4(0.0);\n"
      "  gl_FragData[MRGI_RSM_NORMAL] = vec4(0.0);\n"
      "  gl_FragData[MRGI_RSM_FLUX] = vec4(0.0);\n");
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIReflectiveShadowMapPass::SetShaderParameters(
  vtkShaderProgram* program, vtkAbstractMapper*, vtkProp*, vtkOpenGLVertexArrayObject*)
{
  const View* view = this->Internal->Current;
  if (view)
  {
    // The maps' three targets, for every draw: measured inside
    // vtkSSAOPass, only the first one was selected (SelectDrawBuffers says
    // why), and the normal and flux maps stayed empty.
    vtkMRGIShaderUtilities::SelectDrawBuffers(this->Internal->FrameBuffer, MRGI_RSM_ATTACHMENTS);
  }
  if (!view || !program->IsUniformUsed("mrgiLightVCToWC"))
  {
    return true;
  }
  // vtkMatrix4x4 is row-major; GLSL wants column-major.
  float m[16];
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      m[c * 4 + r] = static_cast<float>(view->VCToWC->GetElement(r, c));
    }
  }
  program->SetUniformMatrix4x4("mrgiLightVCToWC", m);
  program->SetUniformi("mrgiPerspective", view->Perspective ? 1 : 0);
  program->SetUniformf("mrgiTexelSize", static_cast<float>(view->TexelSize));
  float color[3] = { static_cast<float>(view->LightColor[0]),
    static_cast<float>(view->LightColor[1]), static_cast<float>(view->LightColor[2]) };
  program->SetUniform3f("mrgiLightColor", color);
  float attenuation[3] = { static_cast<float>(view->Attenuation[0]),
    static_cast<float>(view->Attenuation[1]), static_cast<float>(view->Attenuation[2]) };
  program->SetUniform3f("mrgiAttenuationValues", attenuation);
  float axis[3] = { static_cast<float>(view->SpotAxisVC[0]), static_cast<float>(view->SpotAxisVC[1]),
    static_cast<float>(view->SpotAxisVC[2]) };
  program->SetUniform3f("mrgiSpotAxisVC", axis);
  program->SetUniformf("mrgiSpotCosCutoff", static_cast<float>(view->SpotCosCutoff));
  program->SetUniformf("mrgiSpotExponent", static_cast<float>(view->SpotExponent));
  vtkMRGIAreaLightRSMViews::SetShaderParameters(program, *view);
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIReflectiveShadowMapPass::CheckInput(vtkProp* prop)
{
  // NaN/Inf coordinates or normals: the GPU skips what they touch (the
  // captures write "nothing here"), and the user hears of it once per change
  // of the data, not once per frame.
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  vtkPolyData* poly = actor && actor->GetMapper()
    ? vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0))
    : nullptr;
  if (!poly)
  {
    return;
  }
  vtkMTimeType& checked = this->Internal->CheckedInput[prop];
  if (checked == poly->GetMTime())
  {
    return;
  }
  checked = poly->GetMTime();
  const vtkIdType badPoints =
    poly->GetPoints() ? vtkMRGISceneChecks::CountNonFiniteTuples(poly->GetPoints()->GetData()) : 0;
  const vtkIdType badNormals = vtkMRGISceneChecks::CountNonFiniteTuples(poly->GetPointData()->GetNormals());
  if (badPoints > 0 || badNormals > 0)
  {
    vtkWarningMacro("an actor's data has " << badPoints << " points with NaN/Inf coordinates and "
                    << badNormals << " NaN/Inf normals: the surfaces they touch are skipped by "
                    << "indirect lighting");
  }
}

//------------------------------------------------------------------------------
void vtkMRGIReflectiveShadowMapPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "NumberOfViews: " << this->GetNumberOfViews() << "\n";
  os << indent << "NumberOfRenders: " << this->NumberOfRenders << "\n";
  os << indent << "Compositor: " << this->Compositor << "\n";
  os << indent << "CompositeBytes: " << this->CompositeBytes << "\n";
  os << indent << "NumberOfComposites: " << this->NumberOfComposites << "\n";
  os << indent << "AreaViews:\n";
  this->Internal->AreaViews->PrintSelf(os, indent.GetNextIndent());
}
