#include "vtkPVMRGILASReader.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMRGILASReader.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cctype>

vtkStandardNewMacro(vtkPVMRGILASReader);

//------------------------------------------------------------------------------
vtkPVMRGILASReader::vtkPVMRGILASReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
int vtkPVMRGILASReader::CanReadFile(const char* fileName)
{
  // The extension only: the reader itself names what is wrong with a file
  // that is not LAS (or is LAZ), which is more useful than ParaView's
  // "no reader" message.
  std::string name = fileName ? fileName : "";
  if (name.size() < 4)
  {
    return 0;
  }
  std::string extension = name.substr(name.size() - 4);
  std::transform(extension.begin(), extension.end(), extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".las" ? 1 : 0;
}

//------------------------------------------------------------------------------
int vtkPVMRGILASReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkPVMRGILASReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  // A fresh reader per run: the executive re-executes only when this
  // object changed, and a fresh one re-reads a file rewritten in place.
  vtkNew<vtkMRGILASReader> reader;
  reader->SetFileName(this->FileName.c_str());
  reader->SetColorBy(this->ColorBy);
  // The piece this rank was asked for (mpirun pvbatch): each rank reads
  // its share of the points instead of every rank drawing the whole cloud.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int piece = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    : 0;
  const int pieces = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    : 1;
  reader->UpdatePiece(piece, pieces, 0);
  this->SetErrorCode(reader->GetErrorCode());
  output->ShallowCopy(reader->GetOutput());
  return 1;
}

//------------------------------------------------------------------------------
void vtkPVMRGILASReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "ColorBy: " << this->ColorBy << "\n";
}
