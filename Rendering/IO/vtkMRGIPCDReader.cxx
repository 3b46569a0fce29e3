#include "vtkMRGIPCDReader.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

// The factory's override (MRGI::RenderingPCL) when it is registered.
vtkObjectFactoryNewMacro(vtkMRGIPCDReader);

vtkMRGIPCDReader::vtkMRGIPCDReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkMRGIPCDReader::~vtkMRGIPCDReader()
{
  this->SetFileName(nullptr);
}

int vtkMRGIPCDReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (output)
  {
    output->Initialize();
  }
  vtkErrorMacro(<< "'" << (this->FileName ? this->FileName : "(no file name)")
                << "': reading PCD needs MRGI's PCL module (MRGI::RenderingPCL), which this "
                   "build lacks");
  return 0;
}

void vtkMRGIPCDReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}
