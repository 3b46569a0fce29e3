#include "vtkMRGIAreaLightSource.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMRGIAreaLight.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkMRGIAreaLightSource);

namespace
{
// The picture of an input image: T as float RGB, W x H texels, VTK order.
struct Picture
{
  int Width = 0;
  int Height = 0;
  vtkSmartPointer<vtkFloatArray> Texels;
};

// Reads T from `image` (class documentation: which array, which slice,
// which axes); false with `why` set when it cannot be a light's picture.
bool ReadPicture(vtkImageData* image, Picture& picture, std::string& why)
{
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars && image->GetPointData()->GetNumberOfArrays() > 0)
  {
    scalars = vtkDataArray::SafeDownCast(image->GetPointData()->GetAbstractArray(0));
  }
  if (!scalars || dims[0] < 1 || dims[1] < 1 || dims[2] < 1)
  {
    why = "the input image has no point scalars (a picture needs point data with 1 to 4 "
          "components)";
    return false;
  }
  const int components = scalars->GetNumberOfComponents();
  if (components < 1 || components > 4)
  {
    std::ostringstream s;
    s << "the input array '" << (scalars->GetName() ? scalars->GetName() : "") << "' has "
      << components << " components (1 grey, 2 grey-alpha, 3 RGB or 4 RGBA)";
    why = s.str();
    return false;
  }
  // The picture's axes: the first two of x, y, z with more than one point
  // (a slice in any axis-aligned plane); a 3D image gives its first z slice.
  int axes[2] = { 0, 1 };
  if (dims[2] > 1 && (dims[0] == 1 || dims[1] == 1))
  {
    axes[0] = dims[0] > 1 ? 0 : 1;
    axes[1] = 2;
  }
  const int width = dims[axes[0]];
  const int height = dims[axes[1]];
  const bool uchar = scalars->GetDataType() == VTK_UNSIGNED_CHAR;
  auto texels = vtkSmartPointer<vtkFloatArray>::New();
  texels->SetName("Texture");
  texels->SetNumberOfComponents(3);
  texels->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  const vtkIdType stride[3] = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const vtkIdType source = i * stride[axes[0]] + j * stride[axes[1]];
      double rgb[3];
      if (components <= 2)
      {
        rgb[0] = rgb[1] = rgb[2] = scalars->GetComponent(source, 0);
      }
      else
      {
        for (int c = 0; c < 3; ++c)
        {
          rgb[c] = scalars->GetComponent(source, c);
        }
      }
      for (int c = 0; c < 3; ++c)
      {
        if (uchar)
        {
          rgb[c] /= 255.0;
        }
        if (!std::isfinite(rgb[c]) || rgb[c] < 0.0)
        {
          std::ostringstream s;
          s << "the input image's texel (" << i << ", " << j << ") has the value " << rgb[c]
            << " (a picture needs finite values >= 0)";
          why = s.str();
          return false;
        }
      }
      const float texel[3] = { static_cast<float>(rgb[0]), static_cast<float>(rgb[1]),
        static_cast<float>(rgb[2]) };
      texels->SetTypedTuple(static_cast<vtkIdType>(j) * width + i, texel);
    }
  }
  picture.Width = width;
  picture.Height = height;
  picture.Texels = texels;
  return true;
}
}

//------------------------------------------------------------------------------
vtkMRGIAreaLightSource::vtkMRGIAreaLightSource()
{
  this->SetNumberOfInputPorts(1);
}

//------------------------------------------------------------------------------
vtkMRGIAreaLightSource::~vtkMRGIAreaLightSource() = default;

//------------------------------------------------------------------------------
int vtkMRGIAreaLightSource::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkMRGIAreaLightSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // Every piece is the whole light (class documentation).
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkMRGIAreaLightSource::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  if (this->GetNumberOfInputConnections(0) < 1)
  {
    return 1;
  }
  // The whole picture, whatever piece of the light is asked for.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  using SDDP = vtkStreamingDemandDrivenPipeline;
  inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
  if (inInfo->Has(SDDP::WHOLE_EXTENT()))
  {
    inInfo->Set(SDDP::UPDATE_EXTENT(), inInfo->Get(SDDP::WHOLE_EXTENT()), 6);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkMRGIAreaLightSource::Fail(const std::string& why)
{
  this->LastErrorMessage = why;
  vtkErrorMacro(<< (this->GetNumberOfInputConnections(0) > 0 ? "MRGI Textured Area Light: "
                                                             : "MRGI Area Light: ")
                << why);
  return 1; // an empty output: no light, but the pipeline goes on
}

//------------------------------------------------------------------------------
int vtkMRGIAreaLightSource::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->LastErrorMessage.clear();

  // The core's check of the parameters (the one vtkMRGIAreaLight applies):
  // a light the view would refuse gives no geometry either.
  std::string invalid;
  if (!vtkMRGIAreaLight::MakeCoreLight(this->Center, this->EdgeU, this->EdgeV, this->Color,
        this->Intensity, this->TwoSided, nullptr, &invalid))
  {
    return this->Fail("invalid parameters: " + invalid);
  }

  Picture picture;
  vtkImageData* image = vtkImageData::GetData(inputVector[0], 0);
  if (this->GetNumberOfInputConnections(0) > 0)
  {
    std::string why;
    if (!image || !ReadPicture(image, picture, why))
    {
      return this->Fail(image ? why : std::string("the input is not a vtkImageData"));
    }
  }

  const int w = picture.Texels ? picture.Width : 1;
  const int h = picture.Texels ? picture.Height : 1;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(w + 1) * (h + 1));
  for (int j = 0; j <= h; ++j)
  {
    const double t = static_cast<double>(j) / h - 0.5;
    for (int i = 0; i <= w; ++i)
    {
      const double s = static_cast<double>(i) / w - 0.5;
      double p[3];
      for (int c = 0; c < 3; ++c)
      {
        p[c] = this->Center[c] + s * this->EdgeU[c] + t * this->EdgeV[c];
      }
      points->SetPoint(static_cast<vtkIdType>(j) * (w + 1) + i, p);
    }
  }
  vtkNew<vtkCellArray> quads;
  quads->AllocateExact(static_cast<vtkIdType>(w) * h, 4 * static_cast<vtkIdType>(w) * h);
  vtkNew<vtkFloatArray> radiance;
  radiance->SetName("Radiance");
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      // Counter-clockwise seen from the emitting side (EdgeU right, EdgeV up).
      const vtkIdType a = static_cast<vtkIdType>(j) * (w + 1) + i;
      const vtkIdType quad[4] = { a, a + 1, a + 1 + (w + 1), a + (w + 1) };
      quads->InsertNextCell(4, quad);
      const vtkIdType cell = static_cast<vtkIdType>(j) * w + i;
      float rgb[3] = { 1.f, 1.f, 1.f };
      if (picture.Texels)
      {
        picture.Texels->GetTypedTuple(cell, rgb);
      }
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] = static_cast<float>(this->Intensity * this->Color[c] * rgb[c]);
      }
      radiance->SetTypedTuple(cell, rgb);
    }
  }

  // The display colours (8 bits: VTK converts float colours to bytes
  // without clamping, so a radiance of 17 would show as 17 * 255 mod 256).
  // vtkMRGIAreaLight's emitter rule: a uniform light shows its radiance
  // clamped (a bright light is white, as MRGI's HDR output clamps it); a
  // picture is divided by its peak P = max radiance when P > 1, so that a
  // bright picture stays a picture, not a white rectangle.
  double peak = 1.0;
  if (picture.Texels)
  {
    for (int c = 0; c < 3; ++c)
    {
      peak = std::max(peak, radiance->GetRange(c)[1]);
    }
  }
  vtkNew<vtkUnsignedCharArray> display;
  display->SetName("DisplayColors");
  display->SetNumberOfComponents(3);
  display->SetNumberOfTuples(radiance->GetNumberOfTuples());
  for (vtkIdType cell = 0; cell < radiance->GetNumberOfTuples(); ++cell)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double v = std::min(1.0, radiance->GetTypedComponent(cell, c) / peak);
      display->SetTypedComponent(cell, c, static_cast<unsigned char>(std::lround(255.0 * v)));
    }
  }
  output->SetPoints(points);
  output->SetPolys(quads);
  output->GetCellData()->AddArray(radiance);
  // Active scalars: ParaView's Show() colours by them.
  output->GetCellData()->SetScalars(display);
  if (picture.Texels)
  {
    output->GetCellData()->AddArray(picture.Texels);
  }

  vtkNew<vtkDoubleArray> mark;
  mark->SetName("MRGIAreaLight");
  mark->SetNumberOfComponents(VTK_MRGI_AREA_LIGHT_FIELD_SIZE);
  mark->SetNumberOfTuples(1);
  double values[VTK_MRGI_AREA_LIGHT_FIELD_SIZE];
  for (int c = 0; c < 3; ++c)
  {
    values[c] = this->Center[c];
    values[3 + c] = this->EdgeU[c];
    values[6 + c] = this->EdgeV[c];
    values[9 + c] = this->Color[c];
  }
  values[12] = this->Intensity;
  values[13] = this->TwoSided ? 1.0 : 0.0;
  values[14] = picture.Width;
  values[15] = picture.Height;
  mark->SetTypedTuple(0, values);
  output->GetFieldData()->AddArray(mark);
  return 1;
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLightSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Center: " << this->Center[0] << " " << this->Center[1] << " " << this->Center[2]
     << "\n";
  os << indent << "EdgeU: " << this->EdgeU[0] << " " << this->EdgeU[1] << " " << this->EdgeU[2]
     << "\n";
  os << indent << "EdgeV: " << this->EdgeV[0] << " " << this->EdgeV[1] << " " << this->EdgeV[2]
     << "\n";
  os << indent << "Color: " << this->Color[0] << " " << this->Color[1] << " " << this->Color[2]
     << "\n";
  os << indent << "Intensity: " << this->Intensity << "\n";
  os << indent << "TwoSided: " << this->TwoSided << "\n";
  os << indent << "LastErrorMessage: " << this->LastErrorMessage << "\n";
}
