#include "vtkPVMRGIPointCloudNormals.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMRGIPointCloudNormals.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

vtkStandardNewMacro(vtkPVMRGIPointCloudNormals);

//------------------------------------------------------------------------------
int vtkPVMRGIPointCloudNormals::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!input || !output)
  {
    return 0;
  }
  // The inner filter gets a shallow copy, so that it never holds (or
  // modifies) ParaView's pipeline object.
  vtkNew<vtkPolyData> cloud;
  cloud->ShallowCopy(input);
  vtkNew<vtkMRGIPointCloudNormals> normals;
  normals->SetInputData(cloud);
  normals->SetNumberOfNeighbors(this->NumberOfNeighbors);
  normals->SetRadiusScale(this->RadiusScale);
  normals->SetUp(this->Up);
  normals->SetComputeNormals(this->ComputeNormals);
  // On bad input the inner filter reports the problem itself; its
  // executive would add a second, generic error ("returned failure").
  // An observer takes that one: ParaView shows the useful message once.
  vtkNew<vtkCallbackCommand> quiet;
  normals->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, quiet);
  normals->Update();
  this->NumberOfDegeneratePoints = normals->GetNumberOfDegeneratePoints();
  this->NumberOfNonFinitePoints = normals->GetNumberOfNonFinitePoints();
  output->ShallowCopy(normals->GetOutput());
  return 1;
}

//------------------------------------------------------------------------------
void vtkPVMRGIPointCloudNormals::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfNeighbors: " << this->NumberOfNeighbors << "\n";
  os << indent << "RadiusScale: " << this->RadiusScale << "\n";
  os << indent << "Up: " << this->Up[0] << " " << this->Up[1] << " " << this->Up[2] << "\n";
  os << indent << "ComputeNormals: " << this->ComputeNormals << "\n";
  os << indent << "NumberOfDegeneratePoints: " << this->NumberOfDegeneratePoints << "\n";
  os << indent << "NumberOfNonFinitePoints: " << this->NumberOfNonFinitePoints << "\n";
}
