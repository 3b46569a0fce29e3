#include "vtkMRGIAreaLightUtilities.h"

#include "vtkMRGIResourceStatistics.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "mrgi_area_light.h"
#include "mrgi_error.h"
#include "mrgi_image.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace
{
bool IsWordCharacter(char c)
{
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// Linear [0, 1] -> 8-bit sRGB, tabulated: the emission texture is encoded
// per texel per video frame, and powf per channel would dominate that.
unsigned char EncodeSRGB8(float linear)
{
  static const std::vector<unsigned char> table = [] {
    std::vector<unsigned char> t(65536);
    for (size_t i = 0; i < t.size(); ++i)
    {
      const float encoded = mrgi_srgb_encode(static_cast<float>(i) / 65535.0f);
      t[i] = static_cast<unsigned char>(std::lround(encoded * 255.0f));
    }
    return t;
  }();
  const float x = linear > 0.0f ? (linear < 1.0f ? linear : 1.0f) : 0.0f; // NaN -> 0
  return table[static_cast<size_t>(x * 65535.0f + 0.5f)];
}

// Copy the colour of a W x H image with `components` components of type T
// into the core's 3-channel float image (rows flipped: VTK's row 0 is the
// bottom, the core's the top). `lut` maps unsigned char values; float
// values are checked to be finite and >= 0.
template <typename T>
bool FillTexture(vtkDataArray* scalars, int width, int height, int components, const float* lut,
  mrgi_image* out, std::string& why)
{
  // Direct reads for the usual (array-of-structs) arrays; any other layout
  // goes through the generic, slower accessor.
  auto* aos = vtkArrayDownCast<vtkAOSDataArrayTemplate<T>>(scalars);
  const T* data = aos ? aos->GetPointer(0) : nullptr;
  // Gray (1 or 2 components) is replicated into RGB; alpha is ignored.
  const int colorComponents = components < 3 ? 1 : 3;
  for (int y = 0; y < height; ++y)
  {
    float* row = mrgi_image_at(out, 0, height - 1 - y);
    for (int x = 0; x < width; ++x)
    {
      const vtkIdType id = static_cast<vtkIdType>(y) * width + x;
      float rgb[3];
      for (int c = 0; c < colorComponents; ++c)
      {
        const double raw =
          data ? static_cast<double>(data[id * components + c]) : scalars->GetComponent(id, c);
        float value;
        if (lut)
        {
          value = lut[static_cast<unsigned char>(raw)];
        }
        else
        {
          value = static_cast<float>(raw);
          if (!(std::isfinite(value) && value >= 0.0f))
          {
            why = "texture pixel (" + std::to_string(x) + ", " + std::to_string(y) +
              ") component " + std::to_string(c) + " = " + std::to_string(raw) +
              " is not finite and >= 0 (float texels are radiances)";
            return false;
          }
        }
        rgb[c] = value;
      }
      if (colorComponents == 1)
      {
        rgb[1] = rgb[2] = rgb[0];
      }
      std::memcpy(row + 3 * x, rgb, sizeof(rgb));
    }
  }
  return true;
}
}

namespace vtkMRGIAreaLightUtilities
{
//------------------------------------------------------------------------------
// Core messages name the C fields; a VTK user knows the properties.
std::string WithPropertyNames(std::string message)
{
  static const char* const names[][2] = { { "center", "Center" }, { "edge_u", "EdgeU" },
    { "edge_v", "EdgeV" }, { "color", "Color" }, { "intensity", "Intensity" } };
  for (const auto& name : names)
  {
    const size_t length = std::strlen(name[0]);
    for (size_t at = message.find(name[0]); at != std::string::npos;
         at = message.find(name[0], at + length))
    {
      const size_t end = at + length;
      if ((at == 0 || !IsWordCharacter(message[at - 1])) &&
        (end == message.size() || !IsWordCharacter(message[end])))
      {
        message.replace(at, length, name[1]);
      }
    }
  }
  return message;
}

//------------------------------------------------------------------------------
// A value, or 0 when it is not finite and >= 0 (for display only: requests
// report such values as errors).
double Sanitized(double value)
{
  return std::isfinite(value) && value > 0.0 ? value : 0.0;
}

//------------------------------------------------------------------------------
// The core's float RGB image of a VTK texture image, or false with the reason.
bool ConvertTexture(vtkImageData* image, bool srgb, mrgi_image* out, std::string& why)
{
  int dims[3];
  image->GetDimensions(dims);
  if (image->GetNumberOfPoints() <= 0 || dims[0] < 1 || dims[1] < 1 || dims[2] < 1)
  {
    why = "the texture image is empty (no points)";
    return false;
  }
  if (dims[2] != 1)
  {
    why = "the texture image is 3D (" + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) +
      " x " + std::to_string(dims[2]) + "); a 2D image (W x H x 1) is needed";
    return false;
  }
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars)
  {
    why = "the texture image has no point scalars";
    return false;
  }
  const int type = scalars->GetDataType();
  if (type != VTK_UNSIGNED_CHAR && type != VTK_FLOAT)
  {
    why = std::string("the texture image has scalars of type ") + scalars->GetDataTypeAsString() +
      "; unsigned char or float is needed";
    return false;
  }
  const int components = scalars->GetNumberOfComponents();
  if (components < 1 || components > 4)
  {
    why = "the texture image has " + std::to_string(components) +
      " components; 1 (gray), 2 (gray + alpha), 3 (RGB) or 4 (RGBA) are accepted";
    return false;
  }
  const vtkIdType points = static_cast<vtkIdType>(dims[0]) * dims[1];
  if (scalars->GetNumberOfTuples() != points)
  {
    why = "the texture image has " + std::to_string(scalars->GetNumberOfTuples()) +
      " scalar tuples for its " + std::to_string(points) + " points";
    return false;
  }
  mrgi_error err;
  if (mrgi_image_create(out, dims[0], dims[1], 3, &err) != MRGI_OK)
  {
    why = std::string("texture: ") + err.message;
    return false;
  }
  bool ok;
  if (type == VTK_UNSIGNED_CHAR)
  {
    float lut[256];
    for (int v = 0; v < 256; ++v)
    {
      const float linear = static_cast<float>(v) / 255.0f;
      lut[v] = srgb ? mrgi_srgb_decode(linear) : linear;
    }
    ok = FillTexture<unsigned char>(scalars, dims[0], dims[1], components, lut, out, why);
  }
  else
  {
    ok = FillTexture<float>(scalars, dims[0], dims[1], components, nullptr, out, why);
  }
  if (!ok)
  {
    mrgi_image_destroy(out);
  }
  return ok;
}

//------------------------------------------------------------------------------
void EncodeDisplayPicture(
  const mrgi_image* picture, double intensity, const double color[3], unsigned char* rgb)
{
  const int width = picture->width;
  const int height = picture->height;
  // Display scale: the radiance scale Intensity * Color, divided by the
  // peak P = Intensity * max(Color) * max(1, max texel) when P > 1. The
  // max texel counts only above 1 (float HDR pictures): a picture in
  // [0, 1] keeps one scale from frame to frame (no exposure flicker).
  float maxTexel = 0.0f;
  const size_t values = static_cast<size_t>(width) * static_cast<size_t>(height) * 3;
  for (size_t i = 0; i < values; ++i)
  {
    maxTexel = std::max(maxTexel, picture->pixels[i]);
  }
  const double shown = Sanitized(intensity);
  double tint[3], maxColor = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    tint[c] = Sanitized(color[c]);
    maxColor = std::max(maxColor, tint[c]);
  }
  const double texturePeak = std::max(1.0, static_cast<double>(maxTexel));
  const double peak = shown * maxColor * texturePeak; // may be +inf: handled below
  float scale[3];
  for (int c = 0; c < 3; ++c)
  {
    // Above 1, Intensity * Color[c] / P, written without the product
    // (which can overflow for huge finite inputs).
    scale[c] = static_cast<float>(peak > 1.0 ? tint[c] / maxColor / texturePeak : shown * tint[c]);
  }
  unsigned char* dst = rgb;
  for (int y = 0; y < height; ++y)
  {
    const float* row = mrgi_image_at(picture, 0, height - 1 - y); // core rows run top-down
    for (int x = 0; x < width; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        *dst++ = EncodeSRGB8(scale[c] * row[3 * x + c]);
      }
    }
  }
}

//------------------------------------------------------------------------------
bool UploadPyramid(vtkTextureObject* texture, vtkOpenGLRenderWindow* window,
  const mrgi_area_light_texture_pyramid* pyramid)
{
  texture->SetContext(window);
  texture->SetInternalFormat(GL_RGB32F);
  texture->SetFormat(GL_RGB);
  texture->SetDataType(GL_FLOAT);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  texture->SetMinificationFilter(vtkTextureObject::LinearMipmapLinear);
  texture->SetMagnificationFilter(vtkTextureObject::Linear);
  texture->SetBaseLevel(0);
  texture->SetMaxLevel(pyramid->level_count - 1);
  texture->SetGenerateMipmap(false);
  // Level 0 through VTK (it creates and sizes the texture), the others as
  // GL mip levels of the same texture: the core's sizes are GL's chain.
  vtkMRGIResourceStatistics::RecordTextureAllocation(pyramid->width[0], pyramid->height[0], 12);
  if (!texture->Create2DFromRaw(static_cast<unsigned int>(pyramid->width[0]),
        static_cast<unsigned int>(pyramid->height[0]), 3, VTK_FLOAT,
        pyramid->texels + pyramid->offset[0]))
  {
    return false;
  }
  texture->Activate();
  vtkOpenGLState* state = window->GetState();
  state->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 4); // RGB32F rows are whole words
  for (int32_t k = 1; k < pyramid->level_count; ++k)
  {
    glTexImage2D(GL_TEXTURE_2D, k, GL_RGB32F, pyramid->width[k], pyramid->height[k], 0, GL_RGB,
      GL_FLOAT, pyramid->texels + pyramid->offset[k]);
  }
  texture->SendParameters(); // base/max level, filters, wrap
  texture->Deactivate();
  return true;
}

//------------------------------------------------------------------------------
bool UploadSamples(vtkTextureObject* texture, vtkOpenGLRenderWindow* window,
  const mrgi_area_light_sample* samples, int count)
{
  texture->SetContext(window);
  texture->SetInternalFormat(GL_RGBA32F);
  texture->SetFormat(GL_RGBA);
  texture->SetDataType(GL_FLOAT);
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  vtkMRGIResourceStatistics::RecordTextureAllocation(MRGI_AREA_LIGHT_SAMPLE_TEXELS, count, 16);
  return texture->Create2DFromRaw(MRGI_AREA_LIGHT_SAMPLE_TEXELS, static_cast<unsigned int>(count),
    4, VTK_FLOAT, const_cast<float*>(mrgi_area_light_sample_texture_data(samples)));
}
}
