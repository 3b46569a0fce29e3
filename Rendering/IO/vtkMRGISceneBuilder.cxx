#include "vtkMRGISceneBuilder.h"

#include "vtkMRGIAreaLight.h"
#include "vtkMRGIStaging.h"
#include "vtkImageData.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellTypes.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkFloatArray.h"
#include "vtkGLTFImporter.h"
#include "vtkGenericDataObjectReader.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGILASReader.h"
#include "vtkMRGIPointCloud.h"
#include "vtkMRGIPointCloudNormals.h"
#include "vtkMRGIReaderOutput.h"
#include "vtkMRGISurfels.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkObjectFactory.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSTLReader.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeInt32Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLGenericDataObjectReader.h"

#include "mrgi_error.h"
#include "mrgi_gltf_check.h"
#include "mrgi_input.h"
#include "mrgi_obj_check.h"
#include "mrgi_ply_check.h"
#include "mrgi_scene.h"
#include "mrgi_scene_cornell.h"
#include "mrgi_scene_living_room.h"
#include "mrgi_scene_scaling.h"
#include "mrgi_vtk_check.h"
#include "mrgi_xml_check.h"

// PCD files are read by vtkMRGIPCDReader (MRGI::RenderingPCL overrides it
// with PCL's reader); until that class is in this tree, .pcd is refused with
// the same message its base class gives.
#if __has_include("vtkMRGIPCDReader.h")
#include "vtkMRGIPCDReader.h"
#define MRGI_HAVE_PCD_READER 1
#endif

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <strings.h>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkMRGISceneBuilder);

namespace
{
const char* const BuiltInScenes[] = { "cornell", "cornell-spot", "cornell-area", "living-room",
  "scaling" };

bool EndsWith(const std::string& path, const char* extension)
{
  const size_t e = std::strlen(extension);
  return path.size() > e && strcasecmp(path.c_str() + path.size() - e, extension) == 0;
}

// Owns a core scene for the duration of a call.
struct CoreScene
{
  mrgi_scene Scene{};
  ~CoreScene() { mrgi_scene_destroy(&this->Scene); }
};

// Collects the text of VTK errors raised by a reader, so that the builder can
// report them as its own one-line error instead of letting them scroll by.
class ErrorCatcher
{
public:
  // Warnings count as errors unless `warningsToo` is false (then VTK
  // prints them as usual).
  explicit ErrorCatcher(vtkObject* watched, bool warningsToo = true)
    : Watched(watched)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback(&ErrorCatcher::OnError);
    this->ErrorTag = watched->AddObserver(vtkCommand::ErrorEvent, this->Callback);
    if (warningsToo)
    {
      this->WarningTag = watched->AddObserver(vtkCommand::WarningEvent, this->Callback);
    }
  }
  ~ErrorCatcher()
  {
    this->Watched->RemoveObserver(this->ErrorTag);
    if (this->WarningTag)
    {
      this->Watched->RemoveObserver(this->WarningTag);
    }
  }
  bool HasError() const { return !this->Message.empty(); }
  const std::string& GetMessage() const { return this->Message; }

private:
  static void OnError(vtkObject*, unsigned long, void* clientData, void* callData)
  {
    auto* self = static_cast<ErrorCatcher*>(clientData);
    if (self->Message.empty() && callData)
    {
      std::string text = static_cast<const char*>(callData);
      // VTK prefixes "ERROR: In file, line N\nClass (0x...): "; keep the reason.
      const size_t colon = text.rfind("): ");
      if (colon != std::string::npos)
      {
        text = text.substr(colon + 3);
      }
      while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
      {
        text.pop_back();
      }
      self->Message = text.empty() ? "the reader failed" : text;
    }
  }

  vtkObject* Watched;
  vtkNew<vtkCallbackCommand> Callback;
  unsigned long ErrorTag = 0;
  unsigned long WarningTag = 0;
  std::string Message;
};

// Whether every vertex of `mesh` lies in the rectangle of `light` (up to a
// small fraction of its size).
bool InRectangle(const mrgi_mesh& mesh, const mrgi_area_light& light)
{
  double n[3];
  vtkMath::Cross(light.edge_u, light.edge_v, n);
  const double uu = vtkMath::Dot(light.edge_u, light.edge_u);
  const double vv = vtkMath::Dot(light.edge_v, light.edge_v);
  const double nn = vtkMath::Norm(n);
  if (mesh.vertex_count < 1 || !(uu > 0.0) || !(vv > 0.0) || !(nn > 0.0))
  {
    return false;
  }
  const double tolerance = 1e-4;
  const double size = std::sqrt(uu) + std::sqrt(vv);
  for (int64_t i = 0; i < mesh.vertex_count; ++i)
  {
    double d[3];
    for (int c = 0; c < 3; ++c)
    {
      d[c] = mesh.positions[3 * static_cast<size_t>(i) + static_cast<size_t>(c)] - light.center[c];
    }
    if (std::fabs(vtkMath::Dot(d, n)) / nn > tolerance * size ||
      std::fabs(vtkMath::Dot(d, light.edge_u)) / uu > 0.5 + tolerance ||
      std::fabs(vtkMath::Dot(d, light.edge_v)) / vv > 0.5 + tolerance)
    {
      return false;
    }
  }
  return true;
}


// Flat data (one extent of its bounds much smaller than the others, such as
// a floor) seen along its plane draws nothing: look at it face on instead.
// "Much smaller": at most 5% of the largest extent, so that a slightly skewed
// wall (the Cornell box's red wall spans 6.4 mm in x over 559 mm) counts.
constexpr double FlatExtentRatio = 0.05;
void FaceFlatData(vtkRenderer* renderer)
{
  double b[6];
  renderer->ComputeVisiblePropBounds(b);
  if (!vtkMath::AreBoundsInitialized(b))
  {
    return;
  }
  const double size[3] = { b[1] - b[0], b[3] - b[2], b[5] - b[4] };
  const double largest = std::max(size[0], std::max(size[1], size[2]));
  int thin = -1;
  for (int k = 0; k < 3; ++k)
  {
    if (size[k] <= FlatExtentRatio * largest && (thin < 0 || size[k] < size[thin]))
    {
      thin = k;
    }
  }
  if (thin < 0 || !(largest > 0))
  {
    return;
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  double focal[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  double position[3] = { focal[0], focal[1], focal[2] };
  position[thin] += largest;
  double up[3] = { 0, 0, 0 };
  up[thin == 1 ? 2 : 1] = 1; // y up, or z up for data in the xz plane (a floor)
  camera->SetFocalPoint(focal);
  camera->SetPosition(position);
  camera->SetViewUp(up);
}

// Active scalars colour through a lookup table over their range (ParaView's
// default); only 3- and 4-component unsigned-char scalars are colours used
// directly. VTK's default colour mode would also take 1- and 2-component
// unsigned chars as luminance(-alpha): ironProt.vtk's 0..255 density would
// draw as a near-black grey. `source` is the data before its surface was
// taken (the range of the whole data set, as ParaView shows it: a volume's
// outer surface alone may hold a single value, ironProt.vtk's zeros).
void ColorByScalars(vtkMapper* mapper, vtkDataObject* geometry, vtkDataObject* source)
{
  mapper->SetScalarModeToDefault();
  auto* ds = vtkDataSet::SafeDownCast(geometry);
  if (!ds)
  {
    return;
  }
  vtkDataArray* scalars = ds->GetPointData()->GetScalars();
  if (!scalars)
  {
    mapper->ScalarVisibilityOff();
    return;
  }
  const bool colours = scalars->GetDataType() == VTK_UNSIGNED_CHAR &&
    (scalars->GetNumberOfComponents() == 3 || scalars->GetNumberOfComponents() == 4);
  if (colours)
  {
    mapper->SetColorModeToDirectScalars();
  }
  else
  {
    double range[2];
    scalars->GetRange(range, -1);
    auto* input = vtkDataSet::SafeDownCast(source);
    vtkDataArray* all = input ? input->GetPointData()->GetScalars() : nullptr;
    if (all && all->GetNumberOfComponents() == scalars->GetNumberOfComponents())
    {
      all->GetRange(range, -1);
    }
    if (!std::isfinite(range[0]) || !std::isfinite(range[1]))
    {
      range[0] = 0;
      range[1] = 1;
    }
    mapper->SetColorModeToMapScalars();
    mapper->SetScalarRange(range);
  }
  mapper->ScalarVisibilityOn();
}

vtkSmartPointer<vtkLight> MakeLight(const mrgi_light& in)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->SetPosition(in.position[0], in.position[1], in.position[2]);
  light->SetFocalPoint(in.focal_point[0], in.focal_point[1], in.focal_point[2]);
  light->SetColor(in.color[0], in.color[1], in.color[2]);
  light->SetIntensity(in.intensity);
  switch (in.type)
  {
    case MRGI_LIGHT_DIRECTIONAL:
      light->SetPositional(false);
      break;
    case MRGI_LIGHT_SPOT:
      light->SetPositional(true);
      light->SetConeAngle(in.cone_angle_deg);
      light->SetExponent(in.exponent);
      break;
    case MRGI_LIGHT_POSITIONAL:
    default:
      light->SetPositional(true);
      light->SetConeAngle(90.0);
      break;
  }
  return light;
}
}

//------------------------------------------------------------------------------
vtkMRGISceneBuilder::vtkMRGISceneBuilder() = default;

//------------------------------------------------------------------------------
vtkMRGISceneBuilder::~vtkMRGISceneBuilder() = default;

//------------------------------------------------------------------------------
void vtkMRGISceneBuilder::SetStaging(vtkMRGIStaging* staging)
{
  if (this->Staging != staging)
  {
    this->Staging = staging;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkMRGIStaging* vtkMRGISceneBuilder::GetStaging()
{
  return this->Staging;
}

//------------------------------------------------------------------------------
// A file's view: staged (vtkMRGIStaging), or framed by ResetCamera() under
// VTK's headlight.
bool vtkMRGISceneBuilder::Frame(const std::string& path, vtkRenderer* renderer)
{
  if (!this->Staging)
  {
    FaceFlatData(renderer);
    renderer->ResetCamera();
    return true;
  }
  if (!this->Staging->Stage(renderer))
  {
    return this->Fail("cannot stage '" + path + "': " + this->Staging->GetLastErrorMessage());
  }
  if (vtkMRGIAreaLight* key = this->Staging->GetAreaLight())
  {
    this->AreaLights.emplace_back(key);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGISceneBuilder::IsBuiltInScene(const char* name)
{
  if (!name)
  {
    return false;
  }
  return std::any_of(std::begin(BuiltInScenes), std::end(BuiltInScenes),
    [name](const char* s) { return std::strcmp(s, name) == 0; });
}

//------------------------------------------------------------------------------
const char* vtkMRGISceneBuilder::GetBuiltInSceneNames()
{
  return "cornell cornell-spot cornell-area living-room scaling";
}

//------------------------------------------------------------------------------
bool vtkMRGISceneBuilder::Fail(const std::string& why)
{
  this->LastErrorMessage = why;
  return false;
}

//------------------------------------------------------------------------------
vtkPolyData* vtkMRGISceneBuilder::MeshToPolyData(const mrgi_mesh* mesh)
{
  vtkPolyData* poly = vtkPolyData::New();
  if (!mesh || mesh->vertex_count < 1 || mesh->triangle_count < 1)
  {
    return poly;
  }
  const vtkIdType nv = static_cast<vtkIdType>(mesh->vertex_count);
  const vtkIdType nt = static_cast<vtkIdType>(mesh->triangle_count);

  vtkNew<vtkFloatArray> coords;
  coords->SetNumberOfComponents(3);
  coords->SetNumberOfTuples(nv);
  std::memcpy(coords->GetPointer(0), mesh->positions, sizeof(float) * 3 * static_cast<size_t>(nv));
  vtkNew<vtkPoints> points;
  points->SetData(coords);
  poly->SetPoints(points);

  if (mesh->normals)
  {
    vtkNew<vtkFloatArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(nv);
    std::memcpy(
      normals->GetPointer(0), mesh->normals, sizeof(float) * 3 * static_cast<size_t>(nv));
    poly->GetPointData()->SetNormals(normals);
  }

  // 32-bit cell storage: half the memory of vtkIdType for 1e7-triangle scenes.
  vtkNew<vtkTypeInt32Array> offsets;
  offsets->SetNumberOfTuples(nt + 1);
  vtkNew<vtkTypeInt32Array> connectivity;
  connectivity->SetNumberOfTuples(3 * nt);
  vtkTypeInt32* off = offsets->GetPointer(0);
  vtkTypeInt32* con = connectivity->GetPointer(0);
  for (vtkIdType t = 0; t <= nt; ++t)
  {
    off[t] = static_cast<vtkTypeInt32>(3 * t);
  }
  for (vtkIdType i = 0; i < 3 * nt; ++i)
  {
    con[i] = static_cast<vtkTypeInt32>(mesh->indices[i]);
  }
  vtkNew<vtkCellArray> triangles;
  triangles->SetData(offsets, connectivity);
  poly->SetPolys(triangles);
  return poly;
}

//------------------------------------------------------------------------------
bool vtkMRGISceneBuilder::BuildCoreScene(const mrgi_scene* scene, vtkRenderer* renderer)
{
  vtkIdType triangles = 0;
  std::vector<vtkSmartPointer<vtkActor>> actors;
  std::vector<std::pair<const mrgi_mesh*, vtkActor*>> emitters; // for textured area lights
  for (int32_t m = 0; m < scene->mesh_count; ++m)
  {
    const mrgi_mesh& mesh = scene->meshes[m];
    vtkSmartPointer<vtkPolyData> poly = vtkSmartPointer<vtkPolyData>::Take(MeshToPolyData(&mesh));
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(poly);
    mapper->ScalarVisibilityOff();
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    vtkProperty* property = actor->GetProperty();
    const bool emitter = mesh.emission[0] > 0.f || mesh.emission[1] > 0.f || mesh.emission[2] > 0.f;
    if (emitter)
    {
      // An emitter shows its radiance whatever the lights: VTK's ambient term
      // with the (unclamped) radiance as colour; the float buffers keep it HDR.
      property->SetAmbient(1.0);
      property->SetDiffuse(0.0);
      property->SetSpecular(0.0);
      property->SetAmbientColor(mesh.emission[0], mesh.emission[1], mesh.emission[2]);
      property->SetColor(mesh.emission[0], mesh.emission[1], mesh.emission[2]);
      emitters.emplace_back(&mesh, actor.Get());
    }
    else
    {
      property->SetColor(mesh.albedo[0], mesh.albedo[1], mesh.albedo[2]);
      property->SetAmbient(0.0);
      property->SetDiffuse(1.0);
      property->SetSpecular(0.0);
    }
    actors.push_back(actor);
    triangles += static_cast<vtkIdType>(mesh.triangle_count);
  }

  for (const auto& actor : actors)
  {
    renderer->AddActor(actor);
  }
  for (int32_t l = 0; l < scene->light_count; ++l)
  {
    renderer->AddLight(MakeLight(scene->lights[l]));
  }
  for (int32_t l = 0; l < scene->area_light_count; ++l)
  {
    const mrgi_area_light& core = scene->area_lights[l];
    auto light = vtkSmartPointer<vtkMRGIAreaLight>::New();
    light->SetCenter(const_cast<double*>(core.center));
    light->SetEdgeU(const_cast<double*>(core.edge_u));
    light->SetEdgeV(const_cast<double*>(core.edge_v));
    light->SetColor(const_cast<double*>(core.color));
    light->SetIntensity(core.intensity);
    light->SetTwoSided(core.two_sided != 0);
    light->SetVisible(false); // the scene's emitter mesh shows it
    if (core.texture && core.texture->pixels && core.texture->channels >= 3)
    {
      // Core images run top-down; VTK's bottom-up.
      const mrgi_image& t = *core.texture;
      vtkNew<vtkImageData> image;
      image->SetDimensions(t.width, t.height, 1);
      image->AllocateScalars(VTK_FLOAT, 3);
      auto* out = static_cast<float*>(image->GetScalarPointer());
      for (int32_t y = 0; y < t.height; ++y)
      {
        for (int32_t x = 0; x < t.width; ++x)
        {
          const float* in = t.pixels + (static_cast<size_t>(t.height - 1 - y) * t.width + x) * t.channels;
          float* o = out + 3 * (static_cast<size_t>(y) * t.width + x);
          o[0] = in[0];
          o[1] = in[1];
          o[2] = in[2];
        }
      }
      light->SetTextureData(image);
      // The emitter mesh lying in this light's rectangle (living-room's
      // screen) shows the light's picture instead of its mean radiance: it
      // becomes a view of the light's geometry actor (the same quad, unlit,
      // the picture scaled for display, the next video frame included; see
      // vtkMRGIAreaLight::GetGeometryActor()) with its own visibility.
      for (const auto& emitter : emitters)
      {
        if (InRectangle(*emitter.first, core))
        {
          light->ShareGeometryActor(emitter.second);
        }
      }
    }
    this->AreaLights.push_back(light);
  }
  if (scene->light_count == 0 && scene->area_light_count > 0)
  {
    // Lit by area lights only (vtkMRGIPass adds their light). Without any
    // vtkLight, VTK would draw every surface unlit, at its full colour; a
    // switched-on light of intensity 0 keeps VTK's lighting on, and black.
    vtkNew<vtkLight> dark;
    dark->SetLightTypeToSceneLight();
    dark->SetIntensity(0.0);
    renderer->AddLight(dark);
  }
  // Built-in scenes carry their own lighting: no automatic headlight.
  renderer->AutomaticLightCreationOff();

  vtkCamera* camera = renderer->GetActiveCamera();
  const mrgi_camera& c = scene->camera;
  camera->SetPosition(c.position[0], c.position[1], c.position[2]);
  camera->SetFocalPoint(c.focal_point[0], c.focal_point[1], c.focal_point[2]);
  camera->SetViewUp(c.view_up[0], c.view_up[1], c.view_up[2]);
  camera->SetViewAngle(c.view_angle_deg);
  renderer->ResetCameraClippingRange();
  this->BuiltTriangleCount = triangles;
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGISceneBuilder::BuildFile(const std::string& path, vtkRenderer* renderer)
{
  {
    // Regular files only: a directory, FIFO or device (/dev/zero) would make
    // a reader fail obscurely, hang or read forever.
    mrgi_error err;
    if (mrgi_input_check_regular(path.c_str(), &err) != MRGI_OK)
    {
      return this->Fail(err.message);
    }
  }

  if (EndsWith(path, ".gltf") || EndsWith(path, ".glb"))
  {
    // VTK 9.1's glTF loader trusts accessors, buffer sizes, URIs and the
    // node graph: check them first.
    mrgi_error err;
    if (mrgi_gltf_check(path.c_str(), nullptr, &err) != MRGI_OK)
    {
      return this->Fail(err.message);
    }
    // The importer fills the first renderer of a window: import into a
    // scratch renderer, then move what it made into ours.
    vtkNew<vtkRenderWindow> scratchWindow;
    vtkNew<vtkRenderer> scratch;
    scratchWindow->AddRenderer(scratch);
    vtkNew<vtkGLTFImporter> importer;
    ErrorCatcher errors(importer);
    importer->SetFileName(path.c_str());
    importer->SetRenderWindow(scratchWindow);
    importer->Update();
    vtkActorCollection* imported = scratch->GetActors();
    if (errors.HasError() || imported->GetNumberOfItems() == 0)
    {
      return this->Fail("cannot read glTF '" + path + "': " +
        (errors.HasError() ? errors.GetMessage() : std::string("it holds no meshes")));
    }
    imported->InitTraversal();
    while (vtkActor* actor = imported->GetNextActor())
    {
      std::string why;
      auto* mapper = vtkPolyDataMapper::SafeDownCast(actor->GetMapper());
      if (mapper && mapper->GetInput() && !vtkMRGIReaderOutput::ValidData(mapper->GetInput(), why))
      {
        return this->Fail("cannot draw glTF '" + path + "': " + why);
      }
    }
    vtkIdType triangles = 0;
    imported->InitTraversal();
    while (vtkActor* actor = imported->GetNextActor())
    {
      renderer->AddActor(actor);
      if (auto* mapper = vtkPolyDataMapper::SafeDownCast(actor->GetMapper()))
      {
        if (auto* input = mapper->GetInput())
        {
          triangles += input->GetNumberOfPolys();
        }
      }
    }
    scratch->GetLights()->InitTraversal();
    while (vtkLight* light = scratch->GetLights()->GetNextItem())
    {
      renderer->AddLight(light);
    }
    if (!this->Frame(path, renderer))
    {
      // Leave the renderer as it was.
      imported->InitTraversal();
      while (vtkActor* actor = imported->GetNextActor())
      {
        renderer->RemoveActor(actor);
      }
      scratch->GetLights()->InitTraversal();
      while (vtkLight* light = scratch->GetLights()->GetNextItem())
      {
        renderer->RemoveLight(light);
      }
      return false;
    }
    this->BuiltTriangleCount = triangles;
    return true;
  }

  vtkSmartPointer<vtkAlgorithm> reader;
  if (EndsWith(path, ".ply"))
  {
    // VTK's PLY reader crashes on some malformed headers and accepts
    // truncated bodies: check the structure first.
    mrgi_error err;
    if (mrgi_ply_check(path.c_str(), nullptr, &err) != MRGI_OK)
    {
      return this->Fail(err.message);
    }
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (EndsWith(path, ".obj"))
  {
    // VTK's OBJ reader indexes with the face indices unchecked.
    mrgi_error err;
    if (mrgi_obj_check(path.c_str(), nullptr, &err) != MRGI_OK)
    {
      return this->Fail(err.message);
    }
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (EndsWith(path, ".stl"))
  {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (EndsWith(path, ".vtk"))
  {
    // VTK's legacy readers trust declared counts, sizes and cell types.
    mrgi_error err;
    if (mrgi_vtk_check(path.c_str(), nullptr, &err) != MRGI_OK)
    {
      return this->Fail(err.message);
    }
    auto r = vtkSmartPointer<vtkGenericDataObjectReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (EndsWith(path, ".vtp") || EndsWith(path, ".vtu") || EndsWith(path, ".vti") ||
    EndsWith(path, ".vts") || EndsWith(path, ".vtr") || EndsWith(path, ".vtm"))
  {
    // VTK's XML readers allocate what the attributes declare.
    mrgi_error err;
    if (mrgi_xml_check(path.c_str(), &err) != MRGI_OK)
    {
      return this->Fail(err.message);
    }
    auto r = vtkSmartPointer<vtkXMLGenericDataObjectReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (EndsWith(path, ".las") || EndsWith(path, ".laz"))
  {
    // LAZ goes through the LAS reader too: the core recognizes compression
    // by the header (not the name) and says "compressed LAZ is not supported".
    auto r = vtkSmartPointer<vtkMRGILASReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (EndsWith(path, ".pcd"))
  {
#ifdef MRGI_HAVE_PCD_READER
    vtkSmartPointer<vtkMRGIPCDReader> r;
    r.TakeReference(vtkMRGIPCDReader::New()); // the PCL override where MRGI::RenderingPCL is built
    r->SetFileName(path.c_str());
    reader = r;
#else
    return this->Fail("cannot read '" + path +
      "': reading PCD needs MRGI's PCL module (MRGI::RenderingPCL), which this build lacks");
#endif
  }
  else
  {
    return this->Fail("cannot read '" + path +
      "': unknown extension (known: .vtp .vtu .vti .vts .vtr .vtm .vtk .ply .obj .stl "
      ".gltf .glb .las .pcd)");
  }

  // Data sets that are not polygonal (and multiblocks of them) become their
  // outer surface, as ParaView's Surface representation shows them.
  vtkNew<vtkDataSetSurfaceFilter> surface;
  ErrorCatcher readerErrors(reader);
  ErrorCatcher surfaceErrors(surface);
  // Structured XML data announce their extent before reading: refuse one
  // whose points alone would not fit in memory (VTK allocates it whole).
  reader->UpdateInformation();
  if (vtkInformation* outInfo = reader->GetOutputInformation(0))
  {
    if (outInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    {
      int e[6];
      outInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), e);
      double points = 1;
      for (int k = 0; k < 3; ++k)
      {
        points *= std::max(0.0, static_cast<double>(e[2 * k + 1]) - e[2 * k] + 1.0);
      }
      if (points > static_cast<double>(vtkMRGIReaderOutput::MaxPoints))
      {
        return this->Fail("cannot read '" + path + "': its extent " + std::to_string(e[0]) + ".." +
          std::to_string(e[1]) + " x " + std::to_string(e[2]) + ".." + std::to_string(e[3]) +
          " x " + std::to_string(e[4]) + ".." + std::to_string(e[5]) + " is too large to draw");
      }
    }
  }
  if (readerErrors.HasError())
  {
    return this->Fail("cannot read '" + path + "': " + readerErrors.GetMessage());
  }
  reader->Update();
  vtkDataObject* data = reader->GetOutputDataObject(0);
  if (readerErrors.HasError() || !data)
  {
    const std::string why = readerErrors.HasError() ? readerErrors.GetMessage()
                                                    : std::string("the reader produced nothing");
    // MRGI's own readers (LAS, PCD) name the file themselves.
    return this->Fail(
      why.find("'" + path + "'") != std::string::npos ? why : "cannot read '" + path + "': " + why);
  }

  // Point clouds take their own path before the checks below, which refuse
  // any non-finite point: scanners pad clouds with NaN points, which the
  // point-cloud path leaves out.
  if (vtkMRGIPointCloud::IsPointCloud(data))
  {
    return this->BuildPointCloud(path, vtkPointSet::SafeDownCast(data), renderer);
  }

  {
    std::string why;
    if (!vtkMRGIReaderOutput::ValidData(data, why))
    {
      return this->Fail("cannot draw '" + path + "': " + why);
    }
  }

  vtkNew<vtkCompositePolyDataMapper2> mapper;
  vtkIdType triangles = 0;
  vtkIdType points = 0;
  vtkSmartPointer<vtkDataObject> geometry;
  if (vtkPolyData::SafeDownCast(data))
  {
    geometry = data;
  }
  else if (this->Staging && vtkMRGIStaging::IsVolume(data))
  {
    // Staged volumes show an iso-surface, not their outer box.
    auto iso = vtkSmartPointer<vtkPolyData>::New();
    if (!this->Staging->MakeIsoSurface(vtkDataSet::SafeDownCast(data), iso))
    {
      return this->Fail("cannot draw '" + path + "': " + this->Staging->GetLastErrorMessage() +
        " (set the iso-value, or do not stage)");
    }
    geometry = iso;
  }
  else if (vtkCompositeDataSet::SafeDownCast(data) || vtkDataSet::SafeDownCast(data))
  {
    surface->SetInputData(data);
    surface->Update();
    geometry = surface->GetOutputDataObject(0);
    if (surfaceErrors.HasError() || !geometry)
    {
      return this->Fail("cannot draw '" + path + "': " +
        (surfaceErrors.HasError() ? surfaceErrors.GetMessage() : std::string("no surface")));
    }
  }
  else
  {
    return this->Fail("'" + path + "' holds a " + data->GetClassName() + ", which has no surface to draw");
  }
  if (vtkMRGIPointCloud::IsPointCloud(geometry))
  {
    // A data set of vertex cells only (a .vtu of points) has a cloud as
    // its surface.
    return this->BuildPointCloud(path, vtkPointSet::SafeDownCast(geometry), renderer);
  }
  if (auto* poly = vtkPolyData::SafeDownCast(geometry))
  {
    triangles = poly->GetNumberOfPolys() + poly->GetNumberOfStrips();
    points = poly->GetNumberOfPoints();
  }
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(geometry))
  {
    points = composite->GetNumberOfPoints();
    triangles = composite->GetNumberOfCells();
  }
  if (points == 0)
  {
    return this->Fail("'" + path + "' holds no geometry (0 points)");
  }

  mapper->SetInputDataObject(geometry);
  ColorByScalars(mapper, geometry, data);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.8, 0.8, 0.8);
  actor->GetProperty()->SetPointSize(2.0f);
  renderer->AddActor(actor);
  if (!this->Frame(path, renderer))
  {
    renderer->RemoveActor(actor);
    return false;
  }
  this->BuiltTriangleCount = triangles;
  return true;
}

//------------------------------------------------------------------------------
// Every point cloud, whatever its reader, is drawn here: the one place where
// normals, splat radii and surfels plug in.
bool vtkMRGISceneBuilder::BuildPointCloud(
  const std::string& path, vtkPointSet* cloud, vtkRenderer* renderer)
{
  const vtkIdType n = cloud ? cloud->GetNumberOfPoints() : 0;
  if (n > vtkMRGIReaderOutput::MaxPoints)
  {
    return this->Fail("cannot draw '" + path + "': it has " + std::to_string(n) +
      " points, more than MRGI draws (" + std::to_string(vtkMRGIReaderOutput::MaxPoints) + ")");
  }
  std::string why;
  auto* poly = vtkPolyData::SafeDownCast(cloud);
  if (!cloud || (poly && !vtkMRGIReaderOutput::CellsInRange(poly->GetVerts(), n, "vertex", why)))
  {
    return this->Fail("cannot draw '" + path + "': " + (cloud ? why : std::string("no points")));
  }
  vtkSmartPointer<vtkPolyData> drawable;
  drawable.TakeReference(vtkMRGIPointCloud::NewFiniteCloud(cloud));
  if (!drawable || drawable->GetNumberOfPoints() == 0)
  {
    return this->Fail("cannot draw '" + path + "': none of its " + std::to_string(n) +
      " points has finite coordinates (all NaN or infinite)");
  }
  // Points drawn as pixels give the G-buffer and the shadow maps no surface:
  // each point becomes an oriented surfel (vtkMRGISurfels), with normals
  // and splat radii estimated where the file has none (PCL when MRGI's PCL
  // module is loaded, the core otherwise). LAS clouds are georeferenced
  // with z up: their normals face up; PCD frames face their sensor.
  vtkNew<vtkMRGIPointCloudNormals> normals;
  normals->SetInputData(drawable);
  if (drawable->GetFieldData()->GetAbstractArray("LASVersion"))
  {
    normals->SetUp(0.0, 0.0, 1.0);
  }
  {
    ErrorCatcher normalsErrors(normals);
    normals->Update();
    if (normalsErrors.HasError())
    {
      return this->Fail("cannot draw the point cloud '" + path + "': " + normalsErrors.GetMessage());
    }
  }
  vtkNew<vtkMRGISurfels> surfels;
  surfels->SetInputConnection(normals->GetOutputPort());
  {
    // Points the surfels skip (a zero normal in the file) are reported by
    // VTK's warning; the others draw.
    ErrorCatcher surfelsErrors(surfels, false);
    surfels->Update();
    if (surfelsErrors.HasError() || surfels->GetOutput()->GetNumberOfPolys() == 0)
    {
      return this->Fail("cannot draw the point cloud '" + path + "': " +
        (surfelsErrors.HasError() ? surfelsErrors.GetMessage()
                                  : std::string("no point has a usable normal and radius")));
    }
  }
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(surfels->GetOutputPort());
  ColorByScalars(mapper, surfels->GetOutput(), drawable);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.8, 0.8, 0.8);
  renderer->AddActor(actor);
  if (!this->Frame(path, renderer))
  {
    renderer->RemoveActor(actor);
    return false;
  }
  // A cloud with many points per pixel looks the same with fewer, larger
  // surfels (every k-th point, radius x sqrt(k)) at a fraction of the
  // geometry cost: budget them from the framed view.
  const vtkIdType budget = vtkMRGISurfels::SuggestMaximumNumberOfSurfels(
    renderer, actor, this->SurfelsPerPixel);
  if (budget > 0 && budget < drawable->GetNumberOfPoints())
  {
    surfels->SetMaximumNumberOfSurfels(budget);
    surfels->Update();
  }
  this->BuiltTriangleCount = 0;
  this->BuiltPointCount = drawable->GetNumberOfPoints();
  return true;
}

//------------------------------------------------------------------------------
vtkMRGIAreaLight* vtkMRGISceneBuilder::GetAreaLight(int index) const
{
  return index >= 0 && index < this->GetNumberOfAreaLights() ? this->AreaLights[static_cast<size_t>(index)].Get()
                                                             : nullptr;
}

//------------------------------------------------------------------------------
bool vtkMRGISceneBuilder::Build(vtkRenderer* renderer)
{
  this->LastErrorMessage.clear();
  this->AreaLights.clear();
  this->BuiltTriangleCount = 0;
  this->BuiltPointCount = 0;
  if (!renderer)
  {
    return this->Fail("Build needs a renderer");
  }
  if (this->Scene.empty())
  {
    return this->Fail("no scene given: name a built-in scene (" +
      std::string(GetBuiltInSceneNames()) + ") or a data file");
  }
  if (!IsBuiltInScene(this->Scene.c_str()))
  {
    return this->BuildFile(this->Scene, renderer);
  }

  CoreScene core;
  mrgi_error err;
  mrgi_status status = MRGI_OK;
  if (this->Scene == "scaling")
  {
    status = mrgi_scene_scaling(this->ObjectCount, this->TriangleCount, this->Seed, &core.Scene, &err);
  }
  else if (this->Scene == "living-room")
  {
    status = mrgi_scene_living_room(&core.Scene, &err);
  }
  else
  {
    mrgi_cornell_variant variant = MRGI_CORNELL_POINT;
    status = mrgi_cornell_variant_parse(this->Scene.c_str(), &variant, &err);
    if (status == MRGI_OK)
    {
      status = mrgi_scene_cornell_box(variant, &core.Scene, &err);
    }
  }
  if (status != MRGI_OK)
  {
    return this->Fail("cannot build scene '" + this->Scene + "': " + err.message);
  }
  return this->BuildCoreScene(&core.Scene, renderer);
}

//------------------------------------------------------------------------------
void vtkMRGISceneBuilder::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Scene: " << this->Scene << "\n";
  os << indent << "TriangleCount: " << this->TriangleCount << "\n";
  os << indent << "ObjectCount: " << this->ObjectCount << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "SurfelsPerPixel: " << this->SurfelsPerPixel << "\n";
  os << indent << "BuiltTriangleCount: " << this->BuiltTriangleCount << "\n";
  os << indent << "BuiltPointCount: " << this->BuiltPointCount << "\n";
}
