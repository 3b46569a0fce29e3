#include "vtkMRGISceneBuilder.h"

#include "vtkMRGIAreaLight.h"
#include "vtkMRGIBuiltInScenes.h"
#include "vtkMRGIFileReaders.h"
#include "vtkMRGIPointCloud.h"
#include "vtkMRGIPointCloudNormals.h"
#include "vtkMRGIReaderErrors.h"
#include "vtkMRGIReaderOutput.h"
#include "vtkMRGIStaging.h"
#include "vtkMRGISurfels.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkCompositeDataSet.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkFieldData.h"
#include "vtkGLTFImporter.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "mrgi_error.h"
#include "mrgi_gltf_check.h"
#include "mrgi_input.h"
#include "mrgi_scene.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGISceneBuilder);

namespace
{
// Owns a core scene for the duration of a call.
struct CoreScene
{
  mrgi_scene Scene{};
  ~CoreScene() { mrgi_scene_destroy(&this->Scene); }
};

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
  return vtkMRGIBuiltInScenes::IsName(name);
}

//------------------------------------------------------------------------------
const char* vtkMRGISceneBuilder::GetBuiltInSceneNames()
{
  return vtkMRGIBuiltInScenes::NameList();
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
  return vtkMRGIBuiltInScenes::MeshToPolyData(mesh);
}

//------------------------------------------------------------------------------
bool vtkMRGISceneBuilder::BuildCoreScene(const mrgi_scene* scene, vtkRenderer* renderer)
{
  this->BuiltTriangleCount = vtkMRGIBuiltInScenes::AddToRenderer(scene, renderer, this->AreaLights);
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

  if (vtkMRGIFileReaders::IsGLTF(path))
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
    vtkMRGIReaderErrors errors(importer);
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

  std::string unreadable;
  vtkSmartPointer<vtkAlgorithm> reader = vtkMRGIFileReaders::MakeReader(path, unreadable);
  if (!reader)
  {
    return this->Fail(unreadable);
  }

  // Data sets that are not polygonal (and multiblocks of them) become their
  // outer surface, as ParaView's Surface representation shows them.
  vtkNew<vtkDataSetSurfaceFilter> surface;
  vtkMRGIReaderErrors readerErrors(reader);
  vtkMRGIReaderErrors surfaceErrors(surface);
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
    vtkMRGIReaderErrors normalsErrors(normals);
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
    vtkMRGIReaderErrors surfelsErrors(surfels, false);
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
  if (!vtkMRGIBuiltInScenes::Make(
        this->Scene, this->ObjectCount, this->TriangleCount, this->Seed, &core.Scene, &err))
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
