#include "vtkMRGISceneSource.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMapper.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <vector>

vtkStandardNewMacro(vtkMRGISceneSource);

namespace
{
// One mesh of the built scene: its geometry and material as the scene
// builder gave them to the renderer.
struct SceneMesh
{
  vtkPolyData* Geometry;
  double Albedo[3];
  double Emission[3];
};

std::vector<SceneMesh> MeshesOf(vtkRenderer* renderer)
{
  std::vector<SceneMesh> meshes;
  vtkActorCollection* actors = renderer->GetActors();
  vtkCollectionSimpleIterator it;
  actors->InitTraversal(it);
  while (vtkActor* actor = actors->GetNextActor(it))
  {
    vtkPolyData* poly =
      actor->GetMapper() ? vtkPolyData::SafeDownCast(actor->GetMapper()->GetInput()) : nullptr;
    if (!poly)
    {
      continue;
    }
    SceneMesh mesh{ poly, { 0, 0, 0 }, { 0, 0, 0 } };
    vtkProperty* property = actor->GetProperty();
    // The builder draws emitters with the ambient term (ambient 1, diffuse
    // 0, the radiance as colour) and everything else diffuse.
    if (property->GetAmbient() > 0.0 && property->GetDiffuse() == 0.0)
    {
      property->GetAmbientColor(mesh.Emission);
    }
    else
    {
      property->GetDiffuseColor(mesh.Albedo);
    }
    meshes.push_back(mesh);
  }
  return meshes;
}

vtkSmartPointer<vtkFloatArray> Constant(const char* name, const double rgb[3], vtkIdType n)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(n);
  for (int c = 0; c < 3; ++c)
  {
    array->FillComponent(c, rgb[c]);
  }
  return array;
}
}

//------------------------------------------------------------------------------
vtkMRGISceneSource::vtkMRGISceneSource()
{
  this->SetNumberOfInputPorts(0);
  this->Lights = vtkSmartPointer<vtkDoubleArray>::New();
  this->Lights->SetName("LightParameters");
  this->Lights->SetNumberOfComponents(13);
  this->AreaLights = vtkSmartPointer<vtkDoubleArray>::New();
  this->AreaLights->SetName("AreaLightParameters");
  this->AreaLights->SetNumberOfComponents(14);
}

//------------------------------------------------------------------------------
vtkMRGISceneSource::~vtkMRGISceneSource() = default;

//------------------------------------------------------------------------------
bool vtkMRGISceneSource::BuildScene()
{
  if (this->Renderer && this->BuiltScene == this->Scene)
  {
    return true;
  }
  this->Renderer = nullptr;
  this->BuiltScene.clear();
  this->Lights->SetNumberOfTuples(0);
  this->AreaLights->SetNumberOfTuples(0);
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene(this->Scene.c_str());
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  if (!builder->Build(renderer))
  {
    this->LastErrorMessage = builder->GetLastErrorMessage();
    vtkErrorMacro("MRGI scene '" << this->Scene << "': " << this->LastErrorMessage);
    return false;
  }
  this->LastErrorMessage.clear();
  this->Renderer = renderer;
  this->BuiltScene = this->Scene;

  vtkCamera* camera = renderer->GetActiveCamera();
  camera->GetPosition(this->CameraPosition);
  camera->GetFocalPoint(this->CameraFocalPoint);
  camera->GetViewUp(this->CameraViewUp);
  this->CameraViewAngle = camera->GetViewAngle();

  vtkLightCollection* lights = renderer->GetLights();
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* light = lights->GetNextLight(it))
  {
    double tuple[13];
    tuple[0] = light->GetPositional() ? 1.0 : 0.0;
    light->GetPosition(tuple + 1);
    light->GetFocalPoint(tuple + 4);
    light->GetDiffuseColor(tuple + 7);
    tuple[10] = light->GetIntensity();
    tuple[11] = light->GetConeAngle();
    tuple[12] = light->GetExponent();
    this->Lights->InsertNextTuple(tuple);
  }
  for (int l = 0; l < builder->GetNumberOfAreaLights(); ++l)
  {
    vtkMRGIAreaLight* area = builder->GetAreaLight(l);
    double tuple[14];
    area->GetCenter(tuple);
    area->GetEdgeU(tuple + 3);
    area->GetEdgeV(tuple + 6);
    area->GetColor(tuple + 9);
    tuple[12] = area->GetIntensity();
    tuple[13] = area->GetTwoSided() ? 1.0 : 0.0;
    this->AreaLights->InsertNextTuple(tuple);
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkMRGISceneSource::GetNumberOfMeshes()
{
  return this->BuildScene() ? static_cast<int>(MeshesOf(this->Renderer).size()) : 0;
}

//------------------------------------------------------------------------------
double* vtkMRGISceneSource::GetCameraPosition()
{
  this->BuildScene();
  return this->CameraPosition;
}

//------------------------------------------------------------------------------
double* vtkMRGISceneSource::GetCameraFocalPoint()
{
  this->BuildScene();
  return this->CameraFocalPoint;
}

//------------------------------------------------------------------------------
double* vtkMRGISceneSource::GetCameraViewUp()
{
  this->BuildScene();
  return this->CameraViewUp;
}

//------------------------------------------------------------------------------
double vtkMRGISceneSource::GetCameraViewAngle()
{
  this->BuildScene();
  return this->CameraViewAngle;
}

//------------------------------------------------------------------------------
vtkDoubleArray* vtkMRGISceneSource::GetLightParameters()
{
  this->BuildScene();
  return this->Lights;
}

//------------------------------------------------------------------------------
vtkDoubleArray* vtkMRGISceneSource::GetAreaLightParameters()
{
  this->BuildScene();
  return this->AreaLights;
}

//------------------------------------------------------------------------------
int vtkMRGISceneSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // Whole meshes go to pieces: any number of pieces can be asked for.
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkMRGISceneSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outInfo);
  if (!this->BuildScene())
  {
    return 1; // empty output; the error is reported
  }
  int piece = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
  int pieces = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES());
  if (pieces < 1)
  {
    pieces = 1;
    piece = 0;
  }
  const std::vector<SceneMesh> meshes = MeshesOf(this->Renderer);
  if (this->MeshIndex >= static_cast<int>(meshes.size()))
  {
    vtkErrorMacro("MeshIndex " << this->MeshIndex << " is past the " << meshes.size()
                               << " meshes of scene '" << this->Scene << "'");
    return 1;
  }

  if (this->MeshIndex >= 0)
  {
    if (this->MeshIndex % pieces != piece)
    {
      return 1;
    }
    const SceneMesh& mesh = meshes[this->MeshIndex];
    output->ShallowCopy(mesh.Geometry);
    output->GetFieldData()->AddArray(Constant("Albedo", mesh.Albedo, 1));
    output->GetFieldData()->AddArray(Constant("Emission", mesh.Emission, 1));
    return 1;
  }

  vtkNew<vtkAppendPolyData> append;
  int appended = 0;
  for (size_t m = 0; m < meshes.size(); ++m)
  {
    if (static_cast<int>(m % static_cast<size_t>(pieces)) != piece)
    {
      continue;
    }
    const SceneMesh& mesh = meshes[m];
    vtkNew<vtkPolyData> copy;
    copy->ShallowCopy(mesh.Geometry);
    const vtkIdType cells = copy->GetNumberOfCells();
    copy->GetCellData()->AddArray(Constant("Albedo", mesh.Albedo, cells));
    copy->GetCellData()->AddArray(Constant("Emission", mesh.Emission, cells));
    append->AddInputData(copy);
    ++appended;
  }
  if (appended > 0)
  {
    append->Update();
    output->ShallowCopy(append->GetOutput());
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkMRGISceneSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Scene: " << this->Scene << "\n";
  os << indent << "MeshIndex: " << this->MeshIndex << "\n";
  os << indent << "LastErrorMessage: " << this->LastErrorMessage << "\n";
}
