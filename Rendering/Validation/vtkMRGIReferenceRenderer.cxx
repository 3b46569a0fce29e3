#include "vtkMRGIReferenceRenderer.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIImageIO.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include "mrgi_reference.h"
#include "mrgi_scene.h"
#include "vtkMRGIAreaLight.h"

#include <algorithm>
#include <cmath>

static_assert(vtkMRGIReferenceRenderer::PixelBox == MRGI_REFERENCE_PIXEL_BOX &&
    vtkMRGIReferenceRenderer::PixelCenter == MRGI_REFERENCE_PIXEL_CENTER,
  "the pixel filters are the core's");
#include <cstring>
#include <vector>

vtkStandardNewMacro(vtkMRGIReferenceRenderer);

namespace
{
// One triangulated, transformed piece of an actor, before it becomes a mesh.
struct Piece
{
  vtkSmartPointer<vtkPolyData> Triangles;
  vtkSmartPointer<vtkMatrix4x4> Matrix;
  double Albedo[3];
  double Emission[3];
};

// Mean colour the mapper gives `poly` (scalars through its lookup table),
// or false when it colours by the property.
bool MeanMappedColor(vtkMapper* mapper, vtkPolyData* poly, double rgb[3])
{
  if (!mapper->GetScalarVisibility() || !poly->GetPointData()->GetScalars())
  {
    return false;
  }
  vtkUnsignedCharArray* colors = mapper->MapScalars(poly, 1.0);
  if (!colors || colors->GetNumberOfTuples() == 0)
  {
    return false;
  }
  double sum[3] = { 0, 0, 0 };
  for (vtkIdType i = 0; i < colors->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      sum[c] += colors->GetComponent(i, c) / 255.0;
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = sum[c] / static_cast<double>(colors->GetNumberOfTuples());
  }
  return true;
}

// Adds `input`'s triangles; counts in `pointsOnly` a piece that draws
// vertices but no surface (a point cloud without surfels), which the
// ground truth cannot see.
void AddPieces(
  vtkActor* actor, vtkPolyData* input, std::vector<Piece>& pieces, vtkIdType& pointsOnly)
{
  if (!input || input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    pointsOnly += input && input->GetNumberOfVerts() > 0 ? 1 : 0;
    return;
  }
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputData(input);
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  triangulate->Update();
  Piece piece;
  piece.Triangles = triangulate->GetOutput();
  piece.Matrix = vtkSmartPointer<vtkMatrix4x4>::New();
  actor->GetMatrix(piece.Matrix);
  vtkProperty* property = actor->GetProperty();
  double color[3];
  property->GetDiffuseColor(color);
  double mapped[3];
  if (MeanMappedColor(actor->GetMapper(), input, mapped))
  {
    std::memcpy(color, mapped, sizeof(color));
  }
  for (int c = 0; c < 3; ++c)
  {
    piece.Albedo[c] = std::min(1.0, std::max(0.0, color[c] * property->GetDiffuse()));
    piece.Emission[c] = std::max(0.0, property->GetAmbient() * property->GetAmbientColor()[c]);
  }
  pieces.push_back(piece);
}
}

//------------------------------------------------------------------------------
vtkMRGIReferenceRenderer::vtkMRGIReferenceRenderer()
{
  this->DirectImage = vtkImageData::New();
  this->IndirectImage = vtkImageData::New();
  // The stopping rule's defaults are the core's (mrgi_reference.h), not typed twice.
  mrgi_reference_options defaults;
  mrgi_reference_options_default(&defaults);
  this->TargetRelativeError = defaults.target_relative_error;
  this->TargetPercentile = defaults.target_percentile;
  this->MaxPasses = defaults.max_passes;
}

//------------------------------------------------------------------------------
vtkMRGIReferenceRenderer::~vtkMRGIReferenceRenderer()
{
  this->DirectImage->Delete();
  this->IndirectImage->Delete();
}

//------------------------------------------------------------------------------
bool vtkMRGIReferenceRenderer::ExportScene(vtkRenderer* renderer, mrgi_scene* out, std::string& why)
{
  std::memset(out, 0, sizeof(*out));
  std::vector<Piece> pieces;
  vtkIdType pointsOnly = 0;
  vtkActorCollection* actors = renderer->GetActors();
  vtkCollectionSimpleIterator ait;
  actors->InitTraversal(ait);
  while (vtkActor* actor = actors->GetNextActor(ait))
  {
    if (!actor->GetVisibility() || actor->HasTranslucentPolygonalGeometry() || !actor->GetMapper())
    {
      continue;
    }
    vtkMapper* mapper = actor->GetMapper();
    mapper->Update();
    vtkDataObject* data = mapper->GetInputDataObject(0, 0);
    if (auto* poly = vtkPolyData::SafeDownCast(data))
    {
      AddPieces(actor, poly, pieces, pointsOnly);
    }
    else if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
    {
      vtkSmartPointer<vtkCompositeDataIterator> it;
      it.TakeReference(composite->NewIterator());
      for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
      {
        AddPieces(
          actor, vtkPolyData::SafeDownCast(it->GetCurrentDataObject()), pieces, pointsOnly);
      }
    }
  }
  if (pointsOnly > 0)
  {
    vtkWarningWithObjectMacro(renderer, << pointsOnly
                    << " visible data set(s) draw only vertices: the ground truth has no "
                       "surface for them and leaves them out; put vtkMRGIPointCloudNormals "
                       "and vtkMRGISurfels before a point cloud's mapper");
  }
  if (pieces.empty())
  {
    why = "the renderer has no visible opaque polygonal geometry";
    return false;
  }

  mrgi_error err;
  if (mrgi_scene_create(out, static_cast<int32_t>(pieces.size()), &err) != MRGI_OK)
  {
    why = err.message;
    return false;
  }
  for (size_t m = 0; m < pieces.size(); ++m)
  {
    const Piece& piece = pieces[m];
    vtkPolyData* poly = piece.Triangles;
    const vtkIdType nv = poly->GetNumberOfPoints();
    const vtkIdType nt = poly->GetNumberOfPolys();
    vtkDataArray* normals = poly->GetPointData()->GetNormals();
    mrgi_mesh& mesh = out->meshes[m];
    if (mrgi_mesh_create(&mesh, nullptr, nv, nt, normals ? 1 : 0, &err) != MRGI_OK)
    {
      why = err.message;
      mrgi_scene_destroy(out);
      return false;
    }
    // Normals transform with the inverse transpose of the actor matrix.
    vtkNew<vtkMatrix4x4> normalMatrix;
    vtkMatrix4x4::Invert(piece.Matrix, normalMatrix);
    normalMatrix->Transpose();
    for (vtkIdType i = 0; i < nv; ++i)
    {
      double p[4] = { 0, 0, 0, 1 }, q[4];
      poly->GetPoint(i, p);
      piece.Matrix->MultiplyPoint(p, q);
      for (int c = 0; c < 3; ++c)
      {
        mesh.positions[3 * i + c] = static_cast<float>(q[c] / (q[3] != 0 ? q[3] : 1));
      }
      if (normals)
      {
        double n[4] = { 0, 0, 0, 0 }, tn[4];
        normals->GetTuple(i, n);
        n[3] = 0;
        normalMatrix->MultiplyPoint(n, tn);
        const double len = std::sqrt(tn[0] * tn[0] + tn[1] * tn[1] + tn[2] * tn[2]);
        for (int c = 0; c < 3; ++c)
        {
          mesh.normals[3 * i + c] = static_cast<float>(len > 0 ? tn[c] / len : (c == 2 ? 1 : 0));
        }
      }
    }
    vtkCellArray* polys = poly->GetPolys();
    vtkIdType t = 0;
    vtkNew<vtkIdList> ids;
    for (polys->InitTraversal(); polys->GetNextCell(ids) && t < nt; ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        mesh.indices[3 * t + k] = static_cast<uint32_t>(ids->GetId(k));
      }
    }
    for (int c = 0; c < 3; ++c)
    {
      mesh.albedo[c] = static_cast<float>(piece.Albedo[c]);
      mesh.emission[c] = static_cast<float>(piece.Emission[c]);
    }
  }

  // Lights as placed for the last frame.
  vtkLightCollection* lights = renderer->GetLights();
  vtkCollectionSimpleIterator lit;
  lights->InitTraversal(lit);
  while (vtkLight* light = lights->GetNextLight(lit))
  {
    if (!light->GetSwitch() || out->light_count >= MRGI_SCENE_MAX_LIGHTS)
    {
      continue;
    }
    mrgi_light& l = out->lights[out->light_count++];
    light->GetTransformedPosition(l.position);
    light->GetTransformedFocalPoint(l.focal_point);
    light->GetDiffuseColor(l.color);
    l.intensity = light->GetIntensity();
    l.exponent = light->GetExponent();
    if (!light->GetPositional())
    {
      l.type = MRGI_LIGHT_DIRECTIONAL;
      l.cone_angle_deg = 90.0;
    }
    else if (light->GetConeAngle() < 90.0)
    {
      l.type = MRGI_LIGHT_SPOT;
      l.cone_angle_deg = light->GetConeAngle();
    }
    else
    {
      l.type = MRGI_LIGHT_POSITIONAL;
      l.cone_angle_deg = 90.0;
    }
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->GetPosition(out->camera.position);
  camera->GetFocalPoint(out->camera.focal_point);
  camera->GetViewUp(out->camera.view_up);
  out->camera.view_angle_deg = camera->GetViewAngle();
  if (mrgi_scene_validate(out, &err) != MRGI_OK)
  {
    why = err.message;
    mrgi_scene_destroy(out);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIReferenceRenderer::Render(vtkRenderer* renderer)
{
  this->LastErrorMessage.clear();
  if (!renderer)
  {
    this->LastErrorMessage = "no renderer given";
    return false;
  }
  int width = this->Width, height = this->Height;
  if (width == 0 || height == 0)
  {
    int x, y;
    renderer->GetTiledSizeAndOrigin(&width, &height, &x, &y);
  }
  mrgi_scene scene;
  if (!ExportScene(renderer, &scene, this->LastErrorMessage))
  {
    return false;
  }
  this->TriangleCount = mrgi_scene_triangle_count(&scene);
  mrgi_reference_options options;
  mrgi_reference_options_default(&options);
  options.width = width;
  options.height = height;
  options.indirect_samples = this->IndirectSamples;
  options.target_relative_error = this->TargetRelativeError;
  options.target_percentile = this->TargetPercentile;
  options.max_passes = this->MaxPasses;
  options.secondary_visibility = this->SecondaryVisibility ? 1 : 0;
  options.shadows = this->Shadows ? 1 : 0;
  options.pixel_filter = this->PixelFilter;
  options.area_light_samples = this->AreaLightSamples;
  options.seed = this->Seed;
  options.threads = this->Threads;
  options.progress = &vtkMRGIReferenceRenderer::ReportProgress;
  options.progress_user_data = this;
  vtkCamera* camera = renderer->GetActiveCamera();
  if (camera->GetParallelProjection())
  {
    options.parallel_projection = 1;
    options.parallel_scale = camera->GetParallelScale();
  }
  mrgi_reference_result result;
  mrgi_error err;
  std::vector<mrgi_area_light> areaLights;
  for (const auto& light : this->AreaLights)
  {
    mrgi_area_light core;
    if (!light->GetCoreLight(&core))
    {
      mrgi_scene_destroy(&scene);
      this->LastErrorMessage = std::string("area light: ") + light->GetLastErrorMessage();
      return false;
    }
    areaLights.push_back(core);
  }
  this->AbortRender = false;
  this->Cancelled = false;
  this->Progress = 0;
  this->ProgressPasses = 0;
  this->ProgressRelativeError = 0;
  this->ProgressPixelError = 0;
  this->ProgressSecondsLeft = 0;
  this->InvokeEvent(vtkCommand::StartEvent, nullptr);
  const mrgi_status status = mrgi_reference_render_area_lights(&scene, &options,
    areaLights.empty() ? nullptr : areaLights.data(), static_cast<int32_t>(areaLights.size()), &result, &err);
  mrgi_scene_destroy(&scene);
  this->InvokeEvent(vtkCommand::EndEvent, nullptr);
  if (status != MRGI_OK)
  {
    this->LastErrorMessage = err.message;
    return false;
  }
  const bool ok = vtkMRGIImageIO::FromCoreImage(&result.direct, this->DirectImage, this->LastErrorMessage) &&
    vtkMRGIImageIO::FromCoreImage(&result.indirect, this->IndirectImage, this->LastErrorMessage);
  this->RelativeError = result.relative_error;
  this->PixelError = std::max(result.pixel_error, result.direct_pixel_error);
  this->Passes = result.passes;
  this->Seconds = result.seconds;
  this->Cancelled = result.cancelled != 0;
  mrgi_reference_result_destroy(&result);
  this->Modified();
  return ok;
}

//------------------------------------------------------------------------------
int vtkMRGIReferenceRenderer::ReportProgress(void* self, const mrgi_reference_progress* progress)
{
  // Called by the core on the thread that called Render(), between passes.
  vtkMRGIReferenceRenderer* renderer = static_cast<vtkMRGIReferenceRenderer*>(self);
  renderer->Progress = progress->fraction;
  renderer->ProgressPasses = progress->passes;
  renderer->ProgressRelativeError = progress->relative_error;
  renderer->ProgressPixelError = std::max(progress->pixel_error, progress->direct_pixel_error);
  renderer->ProgressSecondsLeft = progress->seconds_left;
  double fraction = progress->fraction;
  renderer->InvokeEvent(vtkCommand::ProgressEvent, &fraction);
  return renderer->AbortRender ? 1 : 0;
}

//------------------------------------------------------------------------------
void vtkMRGIReferenceRenderer::AddAreaLight(vtkMRGIAreaLight* light)
{
  if (light)
  {
    this->AreaLights.emplace_back(light);
    this->Modified();
  }
}

void vtkMRGIReferenceRenderer::RemoveAllAreaLights()
{
  this->AreaLights.clear();
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkMRGIReferenceRenderer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Width << " x " << this->Height << "\n";
  os << indent << "IndirectSamples: " << this->IndirectSamples << "\n";
  os << indent << "TargetRelativeError: " << this->TargetRelativeError << "\n";
  os << indent << "TargetPercentile: " << this->TargetPercentile << "\n";
  os << indent << "MaxPasses: " << this->MaxPasses << "\n";
  os << indent << "SecondaryVisibility: " << (this->SecondaryVisibility ? "On" : "Off") << "\n";
  os << indent << "Shadows: " << (this->Shadows ? "On" : "Off") << "\n";
  os << indent << "PixelFilter: " << (this->PixelFilter == PixelCenter ? "Center" : "Box") << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "AreaLights: " << this->AreaLights.size() << "\n";
  os << indent << "AreaLightSamples: " << this->AreaLightSamples << "\n";
  os << indent << "Threads: " << this->Threads << "\n";
  os << indent << "RelativeError: " << this->RelativeError << "\n";
  os << indent << "PixelError: " << this->PixelError << "\n";
  os << indent << "Passes: " << this->Passes << "\n";
  os << indent << "Seconds: " << this->Seconds << "\n";
  os << indent << "AbortRender: " << this->AbortRender << "\n";
  os << indent << "Cancelled: " << this->Cancelled << "\n";
  os << indent << "Progress: " << this->Progress << "\n";
  os << indent << "ProgressPasses: " << this->ProgressPasses << "\n";
  os << indent << "ProgressRelativeError: " << this->ProgressRelativeError << "\n";
  os << indent << "ProgressPixelError: " << this->ProgressPixelError << "\n";
  os << indent << "ProgressSecondsLeft: " << this->ProgressSecondsLeft << "\n";
}
