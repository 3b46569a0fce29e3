#include "vtkPVMRGISurfels.h"

#include "vtkPVMRGIInnerFilter.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMRGISurfels.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

vtkStandardNewMacro(vtkPVMRGISurfels);

//------------------------------------------------------------------------------
vtkPVMRGISurfels::vtkPVMRGISurfels() = default;

//------------------------------------------------------------------------------
int vtkPVMRGISurfels::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!input || !output)
  {
    return 0;
  }
  vtkNew<vtkMRGISurfels> surfels;
  surfels->SetShape(this->Shape == 6 ? vtkMRGISurfels::Hexagon : vtkMRGISurfels::Square);
  surfels->SetNormalsArrayName(this->NormalsArrayName.c_str());
  surfels->SetRadiusArrayName(this->RadiusArrayName.c_str());
  surfels->SetRadius(this->Radius);
  surfels->SetRadiusScale(this->RadiusScale);
  surfels->SetMaximumNumberOfSurfels(this->MaximumNumberOfSurfels);
  vtkPVMRGIInnerFilter::Run(surfels, input, output);
  this->Stride = surfels->GetStride();
  this->NumberOfSkippedPoints = surfels->GetNumberOfSkippedPoints();
  return 1;
}

//------------------------------------------------------------------------------
void vtkPVMRGISurfels::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shape: " << this->Shape << "\n";
  os << indent << "NormalsArrayName: " << this->NormalsArrayName << "\n";
  os << indent << "RadiusArrayName: " << this->RadiusArrayName << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "RadiusScale: " << this->RadiusScale << "\n";
  os << indent << "MaximumNumberOfSurfels: " << this->MaximumNumberOfSurfels << "\n";
  os << indent << "Stride: " << this->Stride << "\n";
  os << indent << "NumberOfSkippedPoints: " << this->NumberOfSkippedPoints << "\n";
}
