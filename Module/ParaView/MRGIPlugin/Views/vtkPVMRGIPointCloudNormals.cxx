#include "vtkPVMRGIPointCloudNormals.h"

#include "vtkPVMRGIInnerFilter.h"

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
  vtkNew<vtkMRGIPointCloudNormals> normals;
  normals->SetNumberOfNeighbors(this->NumberOfNeighbors);
  normals->SetRadiusScale(this->RadiusScale);
  normals->SetUp(this->Up);
  normals->SetComputeNormals(this->ComputeNormals);
  vtkPVMRGIInnerFilter::Run(normals, input, output);
  this->NumberOfDegeneratePoints = normals->GetNumberOfDegeneratePoints();
  this->NumberOfNonFinitePoints = normals->GetNumberOfNonFinitePoints();
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
