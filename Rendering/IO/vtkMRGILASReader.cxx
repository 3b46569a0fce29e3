#include "vtkMRGILASReader.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include "mrgi_error.h"
#include "mrgi_input.h"
#include "mrgi_las.h"
#include "mrgi_las_colors.h"

#include <cstring>
#include <limits>

vtkStandardNewMacro(vtkMRGILASReader);

namespace
{
// Owns what the core allocated until the VTK arrays take it over.
struct CoreRead
{
  mrgi_input Input{};
  bool Mapped = false;
  mrgi_las_points Points{};
  ~CoreRead()
  {
    mrgi_las_points_destroy(&this->Points);
    if (this->Mapped)
    {
      mrgi_input_unmap(&this->Input);
    }
  }
};

// The core's messages start with "LAS: "; the reader names the file instead.
std::string Reason(const mrgi_error& err)
{
  std::string text = err.message;
  if (text.compare(0, 5, "LAS: ") == 0)
  {
    text.erase(0, 5);
  }
  return text;
}

// One vertex cell per point: offsets 0..n, connectivity 0..n-1, in 32 bits
// when they fit (half the memory of VTK's default 64-bit ids).
template <typename ArrayT>
void FillVertices(vtkCellArray* verts, vtkIdType n)
{
  using T = typename ArrayT::ValueType;
  vtkNew<ArrayT> offsets;
  vtkNew<ArrayT> connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(n);
  T* o = offsets->GetPointer(0);
  T* c = connectivity->GetPointer(0);
  for (vtkIdType i = 0; i < n; ++i)
  {
    o[i] = static_cast<T>(i);
    c[i] = static_cast<T>(i);
  }
  o[n] = static_cast<T>(n);
  verts->SetData(offsets, connectivity);
}

// Points [first, first + count) of `whole` (vertices, arrays, field data)
// into `out`, one vertex each.
void ExtractRange(vtkPolyData* whole, vtkIdType first, vtkIdType count, vtkPolyData* out)
{
  out->Initialize();
  vtkNew<vtkPoints> points;
  points->SetDataType(whole->GetPoints()->GetDataType());
  points->GetData()->InsertTuples(0, count, first, whole->GetPoints()->GetData());
  out->SetPoints(points);
  vtkPointData* from = whole->GetPointData();
  for (int a = 0; a < from->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* source = from->GetAbstractArray(a);
    vtkSmartPointer<vtkAbstractArray> part;
    part.TakeReference(source->NewInstance());
    part->SetName(source->GetName());
    part->SetNumberOfComponents(source->GetNumberOfComponents());
    part->InsertTuples(0, count, first, source);
    out->GetPointData()->AddArray(part);
    if (source == from->GetScalars())
    {
      out->GetPointData()->SetActiveScalars(part->GetName());
    }
  }
  vtkNew<vtkCellArray> verts;
  FillVertices<vtkTypeInt64Array>(verts, count);
  out->SetVerts(verts);
  out->GetFieldData()->ShallowCopy(whole->GetFieldData());
}
}

//------------------------------------------------------------------------------
vtkMRGILASReader::vtkMRGILASReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkLookupTable* vtkMRGILASReader::NewClassificationLookupTable()
{
  vtkLookupTable* table = vtkLookupTable::New();
  table->SetNumberOfTableValues(256);
  table->SetTableRange(0, 255);
  for (int c = 0; c < 256; ++c)
  {
    uint8_t rgb[3];
    mrgi_las_classification_color(c, rgb);
    table->SetTableValue(c, rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0, 1.0);
  }
  return table;
}

//------------------------------------------------------------------------------
int vtkMRGILASReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->Initialize();
  this->LastErrorMessage.clear();
  this->ColorByUsed = -1;
  this->SetErrorCode(vtkErrorCode::NoError);
  // A bad file is an error event and an empty output, not a failed request:
  // the executive would add a second, less useful error line.
  auto fail = [this](const std::string& why) {
    this->LastErrorMessage = why;
    this->SetErrorCode(vtkErrorCode::FileFormatError);
    vtkErrorMacro(<< why);
    return 1;
  };
  if (this->FileName.empty())
  {
    return fail("no FileName set");
  }
  const std::string& path = this->FileName;
  const std::string prefix = "cannot read LAS file '" + path + "': ";

  CoreRead read;
  mrgi_error err;
  if (mrgi_input_map(path.c_str(), &read.Input, &err) != MRGI_OK)
  {
    fail(prefix + err.message);
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    return 1;
  }
  read.Mapped = true;
  // The header alone first: the version for the field data, and the point
  // count against MaximumNumberOfPoints before anything is allocated.
  mrgi_las_header header;
  if (mrgi_las_read_header_buffer(read.Input.data, read.Input.size, &header, &err) != MRGI_OK ||
    mrgi_las_read_buffer(
      read.Input.data, read.Input.size, this->MaximumNumberOfPoints, &read.Points, &err) != MRGI_OK)
  {
    return fail(prefix + Reason(err));
  }
  mrgi_las_points& p = read.Points;
  if (p.count > static_cast<int64_t>(std::numeric_limits<vtkIdType>::max() / 3))
  {
    return fail(prefix + "too many points for this VTK's ids");
  }
  const vtkIdType n = static_cast<vtkIdType>(p.count);

  // Colours before anything is handed over (the core reads its own arrays).
  int mode = this->ColorBy;
  if (mode == COLOR_BY_RGB && !p.colors)
  {
    vtkWarningMacro(<< "'" << path << "': point format " << header.point_format
                    << " has no RGB; colouring as ColorBy Auto does");
    mode = COLOR_BY_AUTO;
  }
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(n);
  mrgi_las_color_mode used = MRGI_LAS_COLOR_AUTO;
  if (mrgi_las_colorize(
        &p, static_cast<mrgi_las_color_mode>(mode), colors->GetPointer(0), &used, &err) != MRGI_OK)
  {
    return fail(prefix + err.message);
  }

  // The file's RGB too when the display colours show something else.
  vtkSmartPointer<vtkUnsignedCharArray> rgb;
  if (p.colors && used != MRGI_LAS_COLOR_RGB)
  {
    rgb = vtkSmartPointer<vtkUnsignedCharArray>::New();
    rgb->SetName("RGB");
    rgb->SetNumberOfComponents(3);
    rgb->SetNumberOfTuples(n);
    if (mrgi_las_colorize(&p, MRGI_LAS_COLOR_RGB, rgb->GetPointer(0), nullptr, &err) != MRGI_OK)
    {
      return fail(prefix + err.message);
    }
  }

  // Points and attributes: the VTK arrays take over the core's malloc'd
  // buffers (no copy of 10^7 points); the core's pointers are cleared so
  // that mrgi_las_points_destroy() leaves them alone.
  vtkNew<vtkFloatArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetArray(p.positions, 3 * n, 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
  p.positions = nullptr;
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  output->SetPoints(points);

  vtkNew<vtkUnsignedShortArray> intensity;
  intensity->SetName("Intensity");
  intensity->SetArray(p.intensity, n, 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
  p.intensity = nullptr;
  vtkNew<vtkUnsignedCharArray> classification;
  classification->SetName("Classification");
  classification->SetArray(p.classification, n, 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
  p.classification = nullptr;
  vtkNew<vtkUnsignedCharArray> returnNumber;
  returnNumber->SetName("ReturnNumber");
  returnNumber->SetArray(p.return_number, n, 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
  p.return_number = nullptr;
  vtkNew<vtkUnsignedCharArray> numberOfReturns;
  numberOfReturns->SetName("NumberOfReturns");
  numberOfReturns->SetArray(p.number_of_returns, n, 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
  p.number_of_returns = nullptr;
  vtkPointData* pd = output->GetPointData();
  pd->AddArray(intensity);
  pd->AddArray(classification);
  pd->AddArray(returnNumber);
  pd->AddArray(numberOfReturns);
  if (used == MRGI_LAS_COLOR_RGB)
  {
    colors->SetName("RGB");
    pd->SetScalars(colors);
  }
  else
  {
    if (rgb)
    {
      pd->AddArray(rgb);
    }
    colors->SetName("Colors");
    pd->SetScalars(colors);
  }

  vtkNew<vtkCellArray> verts;
  if (n < vtkIdType(std::numeric_limits<vtkTypeInt32>::max()))
  {
    FillVertices<vtkTypeInt32Array>(verts, n);
  }
  else
  {
    FillVertices<vtkTypeInt64Array>(verts, n);
  }
  output->SetVerts(verts);

  vtkNew<vtkDoubleArray> origin;
  origin->SetName("Origin");
  origin->SetNumberOfComponents(3);
  origin->InsertNextTuple(p.origin);
  vtkNew<vtkStringArray> version;
  version->SetName("LASVersion");
  version->InsertNextValue(
    std::to_string(header.version_major) + "." + std::to_string(header.version_minor));
  vtkNew<vtkIntArray> format;
  format->SetName("LASPointFormat");
  format->InsertNextValue(header.point_format);
  output->GetFieldData()->AddArray(origin);
  output->GetFieldData()->AddArray(version);
  output->GetFieldData()->AddArray(format);

  switch (used)
  {
    case MRGI_LAS_COLOR_RGB:
      this->ColorByUsed = COLOR_BY_RGB;
      break;
    case MRGI_LAS_COLOR_CLASSIFICATION:
      this->ColorByUsed = COLOR_BY_CLASSIFICATION;
      break;
    default:
      this->ColorByUsed = COLOR_BY_INTENSITY;
      break;
  }

  // Pieces (ParaView under MPI asks each rank for one): an even share of
  // the file's points in file order, every share recentred on the same
  // origin, so that the ranks' pieces fit together.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int pieces = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    : 1;
  const int piece = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    : 0;
  if (pieces > 1 && piece >= 0 && piece < pieces)
  {
    const vtkIdType first = static_cast<vtkIdType>(static_cast<double>(n) * piece / pieces);
    const vtkIdType end = static_cast<vtkIdType>(static_cast<double>(n) * (piece + 1) / pieces);
    vtkNew<vtkPolyData> whole;
    whole->ShallowCopy(output);
    ExtractRange(whole, first, end - first, output);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkMRGILASReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // Any piece of the file can be read (RequestData), so ParaView's ranks
  // each draw their share instead of all drawing the whole cloud.
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

//------------------------------------------------------------------------------
void vtkMRGILASReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName.empty() ? "(none)" : this->FileName) << "\n";
  os << indent << "ColorBy: " << this->ColorBy << "\n";
  os << indent << "ColorByUsed: " << this->ColorByUsed << "\n";
  os << indent << "MaximumNumberOfPoints: " << this->MaximumNumberOfPoints << "\n";
  os << indent << "LastErrorMessage: " << this->LastErrorMessage << "\n";
}
