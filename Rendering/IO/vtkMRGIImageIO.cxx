#include "vtkMRGIImageIO.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

#include "mrgi_error.h"
#include "mrgi_exr.h"
#include "mrgi_image.h"
#include "mrgi_png.h"

#include <cmath>
#include <cstring>
#include <strings.h>

vtkStandardNewMacro(vtkMRGIImageIO);

namespace
{
bool HasExtension(const char* path, const char* extension)
{
  const size_t n = std::strlen(path);
  const size_t e = std::strlen(extension);
  return n > e && strcasecmp(path + n - e, extension) == 0;
}

// Owns a core image for the duration of a call.
struct CoreImage
{
  mrgi_image Image{};
  ~CoreImage() { mrgi_image_destroy(&this->Image); }
};
}

//------------------------------------------------------------------------------
bool vtkMRGIImageIO::Fail(const std::string& why)
{
  this->LastErrorMessage = why;
  vtkErrorMacro(<< why);
  return false;
}

//------------------------------------------------------------------------------
bool vtkMRGIImageIO::ToCoreImage(vtkImageData* image, mrgi_image* out, std::string& why)
{
  if (!image || !out)
  {
    why = "no image given";
    return false;
  }
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars || dims[0] < 1 || dims[1] < 1 || image->GetNumberOfPoints() == 0)
  {
    why = "the image is empty (no points or no scalars)";
    return false;
  }
  if (dims[2] != 1)
  {
    why = "the image is 3D (" + std::to_string(dims[2]) + " slices); only 2D images are written";
    return false;
  }
  const int channels = scalars->GetNumberOfComponents();
  if (channels < 1 || channels > 4)
  {
    why = "the image has " + std::to_string(channels) + " components; 1 to 4 are supported";
    return false;
  }
  mrgi_error err;
  if (mrgi_image_create(out, dims[0], dims[1], channels, &err) != MRGI_OK)
  {
    why = err.message;
    return false;
  }
  const double scale = scalars->GetDataType() == VTK_UNSIGNED_CHAR ? 1.0 / 255.0 : 1.0;
  for (int y = 0; y < dims[1]; ++y)
  {
    // VTK rows run bottom-up, core images top-down.
    float* row = mrgi_image_at(out, 0, dims[1] - 1 - y);
    for (int x = 0; x < dims[0]; ++x)
    {
      const vtkIdType id = static_cast<vtkIdType>(y) * dims[0] + x;
      for (int c = 0; c < channels; ++c)
      {
        row[x * channels + c] = static_cast<float>(scalars->GetComponent(id, c) * scale);
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIImageIO::FromCoreImage(const mrgi_image* in, vtkImageData* image, std::string& why)
{
  mrgi_error err;
  if (!image || mrgi_image_validate(in, &err) != MRGI_OK)
  {
    why = image ? err.message : "no output image given";
    return false;
  }
  image->SetDimensions(in->width, in->height, 1);
  image->AllocateScalars(VTK_FLOAT, in->channels);
  float* dst = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars())->GetPointer(0);
  const size_t rowValues = static_cast<size_t>(in->width) * static_cast<size_t>(in->channels);
  for (int32_t y = 0; y < in->height; ++y)
  {
    std::memcpy(dst + static_cast<size_t>(y) * rowValues,
      mrgi_image_at(in, 0, in->height - 1 - y), rowValues * sizeof(float));
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIImageIO::Write(vtkImageData* image, const char* path)
{
  if (!path || !path[0])
  {
    return this->Fail("no output file name given");
  }
  if (HasExtension(path, ".exr"))
  {
    return this->WriteEXR(image, path);
  }
  if (HasExtension(path, ".png"))
  {
    return this->WritePNG(image, path);
  }
  return this->Fail(std::string("cannot tell the format of '") + path +
    "': the file name must end in .exr or .png");
}

//------------------------------------------------------------------------------
bool vtkMRGIImageIO::PrepareWrite(vtkImageData* image, const char* path, mrgi_image* core)
{
  this->LastErrorMessage.clear();
  if (!path || !path[0])
  {
    return this->Fail("no output file name given");
  }
  std::string why;
  if (!ToCoreImage(image, core, why))
  {
    return this->Fail("cannot write '" + std::string(path) + "': " + why);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIImageIO::WriteEXR(vtkImageData* image, const char* path)
{
  CoreImage core;
  mrgi_error err;
  if (!this->PrepareWrite(image, path, &core.Image))
  {
    return false;
  }
  if (mrgi_exr_write(path, &core.Image, nullptr, this->HalfFloat ? MRGI_EXR_HALF : MRGI_EXR_FLOAT,
        &err) != MRGI_OK)
  {
    return this->Fail(err.message);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIImageIO::WritePNG(vtkImageData* image, const char* path)
{
  CoreImage core;
  mrgi_error err;
  if (!this->PrepareWrite(image, path, &core.Image))
  {
    return false;
  }
  if (mrgi_png_write_image(path, &core.Image, 0, 1.0f, &err) != MRGI_OK)
  {
    return this->Fail(err.message);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIImageIO::Read(const char* path, vtkImageData* image)
{
  this->LastErrorMessage.clear();
  if (!path || !path[0] || !image)
  {
    return this->Fail("Read needs a file name and an output image");
  }
  CoreImage core;
  mrgi_error err;
  mrgi_status status = MRGI_ERR_UNSUPPORTED;
  if (HasExtension(path, ".exr"))
  {
    status = mrgi_exr_read(path, &core.Image, &err);
  }
  else if (HasExtension(path, ".png"))
  {
    status = mrgi_png_read(path, &core.Image, &err);
  }
  else
  {
    return this->Fail(std::string("cannot tell the format of '") + path +
      "': the file name must end in .exr or .png");
  }
  if (status != MRGI_OK)
  {
    return this->Fail(err.message);
  }
  std::string why;
  if (!FromCoreImage(&core.Image, image, why))
  {
    return this->Fail(why);
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIImageIO::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "HalfFloat: " << (this->HalfFloat ? "On" : "Off") << "\n";
  os << indent << "LastErrorMessage: "
     << (this->LastErrorMessage.empty() ? "(none)" : this->LastErrorMessage) << "\n";
}
