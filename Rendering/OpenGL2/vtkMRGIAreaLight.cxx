#include "vtkMRGIAreaLight.h"

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkImageAlgorithm.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMRGIAreaLightUtilities.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataAlgorithm.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTexture.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWeakPointer.h"

// The area-light GLSL libraries (embedded by vtk_encode_string).
#include "vtkMRGIAreaLightDiffuse.h"
#include "vtkMRGIAreaLightSpecular.h"

#include "mrgi_area_light.h"
#include "mrgi_error.h"
#include "mrgi_image.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

// The clamp range and default of NumberOfSamples are the core's (the header
// spells them out so that it needs no C header).
static_assert(MRGI_AREA_LIGHT_MIN_SAMPLES == 1, "NumberOfSamples clamp range");
static_assert(MRGI_AREA_LIGHT_MAX_SAMPLES == 4096, "NumberOfSamples clamp range");
static_assert(MRGI_AREA_LIGHT_DEFAULT_SAMPLES == 256, "NumberOfSamples default");
static_assert(sizeof(mrgi_area_light_sample) == MRGI_AREA_LIGHT_SAMPLE_FLOATS * sizeof(float),
  "a sample record is its texels");

namespace
{
// Everything a sample set depends on, compared bit for bit: a request with
// the same values reuses the samples (setting a property to its current
// value, or changing one the samples ignore such as Visible, rebuilds
// nothing).
struct SampleKey
{
  double Values[13];
  vtkTypeUInt64 Seed;
  vtkTypeUInt64 TextureGeneration;
  int NumberOfSamples;
  int Flags;
};
}

using vtkMRGIAreaLightUtilities::Sanitized;
using vtkMRGIAreaLightUtilities::WithPropertyNames;

//------------------------------------------------------------------------------
struct vtkMRGIAreaLight::vtkInternals
{
  // Texture cache: the converted image and its pyramid, for the image
  // (pointer, MTime, sRGB reading) they were built from.
  mrgi_image Image{};
  mrgi_area_light_texture_pyramid Pyramid{};
  bool HasTexture = false; // Image and Pyramid hold a texture
  bool TextureKeyValid = false;
  vtkImageData* TextureKeyImage = nullptr; // compared, never dereferenced
  vtkMTimeType TextureKeyMTime = 0;
  bool TextureKeySRGB = false;
  bool TextureOK = false;
  std::string TextureError;
  vtkTypeUInt64 TextureGeneration = 0;

  // Sample cache.
  bool SampleKeyValid = false;
  SampleKey Key{};
  bool SamplesOK = false;
  std::string SampleError;
  std::vector<mrgi_area_light_sample> Samples;
  int SampleCount = 0;

  // GPU copies (GetPyramidTexture(), GetSampleTexture()) in GLWindow's
  // context, with the generation of what they hold.
  vtkWeakPointer<vtkOpenGLRenderWindow> GLWindow;
  bool HadGLWindow = false; // GLWindow was set (a null GLWindow is then a dead one)
  vtkSmartPointer<vtkTextureObject> PyramidTexture;
  vtkTypeUInt64 PyramidTextureGeneration = 0;
  vtkSmartPointer<vtkTextureObject> SampleTexture;
  int SampleTextureBuild = -1; // NumberOfSampleBuilds at upload
  bool TexturesActive = false;

  // The emitter's actor and what feeds it (created on first request).
  vtkSmartPointer<vtkActor> Actor;
  vtkSmartPointer<vtkTexture> EmissionTexture;
  vtkSmartPointer<vtkProperty> BackProperty;
  // Actors given to ShareGeometryActor(): kept in step with Actor's look.
  std::vector<vtkWeakPointer<vtkActor>> Views;

  ~vtkInternals()
  {
    mrgi_area_light_texture_pyramid_destroy(&this->Pyramid);
    mrgi_image_destroy(&this->Image);
  }
};

//------------------------------------------------------------------------------
// The emitter quad, regenerated whenever the light's own properties change
// (not when only its texture image does).
class vtkMRGIAreaLightGeometrySource : public vtkPolyDataAlgorithm
{
public:
  static vtkMRGIAreaLightGeometrySource* New();
  vtkTypeMacro(vtkMRGIAreaLightGeometrySource, vtkPolyDataAlgorithm);

  // Weak: the light owns this source (through its actor), while a renderer
  // may keep the actor after the light is gone.
  vtkWeakPointer<vtkMRGIAreaLight> Light;
  // Set for the sources of ShareGeometryActor()'s views only: they keep the
  // light alive (it holds them weakly, so there is no cycle).
  vtkSmartPointer<vtkMRGIAreaLight> Owner;

  vtkMTimeType GetMTime() override
  {
    vtkMTimeType mtime = this->Superclass::GetMTime();
    if (this->Light)
    {
      mtime = std::max(mtime, this->Light->vtkObject::GetMTime());
    }
    return mtime;
  }

protected:
  vtkMRGIAreaLightGeometrySource() { this->SetNumberOfInputPorts(0); }

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    vtkPolyData* output = vtkPolyData::GetData(out);
    if (!this->Light || !this->Light->MakeGeometry(output))
    {
      output->Initialize(); // an invalid light draws nothing
    }
    return 1;
  }

private:
  vtkMRGIAreaLightGeometrySource(const vtkMRGIAreaLightGeometrySource&) = delete;
  void operator=(const vtkMRGIAreaLightGeometrySource&) = delete;
};
vtkStandardNewMacro(vtkMRGIAreaLightGeometrySource);

//------------------------------------------------------------------------------
// The emitter's picture: Intensity * Color * T scaled for display
// (vtkMRGIAreaLightUtilities::EncodeDisplayPicture()) as 8-bit sRGB RGB,
// the input of the actor's texture; regenerated when the light or its
// texture image changes (the next video frame).
class vtkMRGIAreaLightEmissionSource : public vtkImageAlgorithm
{
public:
  static vtkMRGIAreaLightEmissionSource* New();
  vtkTypeMacro(vtkMRGIAreaLightEmissionSource, vtkImageAlgorithm);

  vtkWeakPointer<vtkMRGIAreaLight> Light;

  vtkMTimeType GetMTime() override
  {
    vtkMTimeType mtime = this->Superclass::GetMTime();
    if (this->Light)
    {
      mtime = std::max(mtime, this->Light->GetMTime());
    }
    return mtime;
  }

protected:
  vtkMRGIAreaLightEmissionSource() { this->SetNumberOfInputPorts(0); }

  // The picture of the cached texture, or nullptr (then 1 x 1 black).
  const mrgi_image* Picture()
  {
    if (!this->Light || !this->Light->UpdateTexture())
    {
      return nullptr;
    }
    const auto& internals = *this->Light->Internals;
    return internals.HasTexture ? &internals.Image : nullptr;
  }

  int RequestInformation(
    vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    const mrgi_image* picture = this->Picture();
    const int width = picture ? picture->width : 1;
    const int height = picture ? picture->height : 1;
    vtkInformation* info = out->GetInformationObject(0);
    int extent[6] = { 0, width - 1, 0, height - 1, 0, 0 };
    info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
    vtkDataObject::SetPointDataActiveScalarInfo(info, VTK_UNSIGNED_CHAR, 3);
    return 1;
  }

  void ExecuteDataWithInformation(vtkDataObject* data, vtkInformation* info) override
  {
    vtkImageData* image = this->AllocateOutputData(data, info);
    auto* rgb = vtkArrayDownCast<vtkUnsignedCharArray>(image->GetPointData()->GetScalars());
    const mrgi_image* picture = this->Picture();
    int dims[3];
    image->GetDimensions(dims);
    if (!rgb || !picture || picture->width != dims[0] || picture->height != dims[1])
    {
      if (rgb)
      {
        rgb->FillValue(0);
      }
      return;
    }
    double color[3];
    this->Light->GetColor(color);
    vtkMRGIAreaLightUtilities::EncodeDisplayPicture(
      picture, this->Light->GetIntensity(), color, rgb->GetPointer(0));
  }

private:
  vtkMRGIAreaLightEmissionSource(const vtkMRGIAreaLightEmissionSource&) = delete;
  void operator=(const vtkMRGIAreaLightEmissionSource&) = delete;
};
vtkStandardNewMacro(vtkMRGIAreaLightEmissionSource);

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkMRGIAreaLight);

//------------------------------------------------------------------------------
vtkMRGIAreaLight::vtkMRGIAreaLight()
  : Internals(new vtkInternals)
{
}

//------------------------------------------------------------------------------
vtkMRGIAreaLight::~vtkMRGIAreaLight()
{
  if (this->Texture)
  {
    this->Texture->UnRegister(this);
  }
  if (this->TextureData)
  {
    this->TextureData->UnRegister(this);
  }
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLight::SetTexture(vtkTexture* texture)
{
  if (texture == this->Texture)
  {
    return;
  }
  vtkTexture* old = this->Texture;
  this->Texture = texture;
  if (texture)
  {
    texture->Register(this);
    this->SetTextureData(nullptr); // the last one set wins
  }
  if (old)
  {
    old->UnRegister(this);
  }
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLight::SetTextureData(vtkImageData* image)
{
  if (image == this->TextureData)
  {
    return;
  }
  vtkImageData* old = this->TextureData;
  this->TextureData = image;
  if (image)
  {
    image->Register(this);
    this->SetTexture(nullptr);
  }
  if (old)
  {
    old->UnRegister(this);
  }
  this->Modified();
}

//------------------------------------------------------------------------------
vtkMTimeType vtkMRGIAreaLight::GetMTime()
{
  vtkMTimeType mtime = this->Superclass::GetMTime();
  if (this->Texture)
  {
    mtime = std::max(mtime, this->Texture->GetMTime());
    if (vtkImageData* input = this->Texture->GetInput())
    {
      mtime = std::max(mtime, input->GetMTime());
    }
  }
  if (this->TextureData)
  {
    mtime = std::max(mtime, this->TextureData->GetMTime());
  }
  return mtime;
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLight::Modified()
{
  this->Superclass::Modified();
  this->UpdateGeometryActor();
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLight::Fail(const std::string& why)
{
  this->LastErrorMessage = why;
  vtkErrorMacro(<< why);
  return false;
}

//------------------------------------------------------------------------------
vtkImageData* vtkMRGIAreaLight::ResolveTextureImage(bool updatePipeline)
{
  if (this->TextureData)
  {
    return this->TextureData;
  }
  if (!this->Texture)
  {
    return nullptr;
  }
  // A texture fed by a pipeline (a reader, a video source) is brought up to
  // date here, as vtkTexture::Render() does before it loads.
  if (updatePipeline && this->Texture->GetNumberOfInputConnections(0) > 0)
  {
    if (vtkAlgorithm* source = this->Texture->GetInputAlgorithm())
    {
      source->Update();
    }
  }
  return this->Texture->GetInput();
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLight::UpdateTexture()
{
  vtkInternals& internals = *this->Internals;
  vtkImageData* image = this->ResolveTextureImage(true);
  if ((this->Texture || this->TextureData) && !image)
  {
    return this->Fail("the area light's vtkTexture has no input image");
  }
  const bool srgb = image && this->Texture && this->Texture->GetUseSRGBColorSpace();
  const vtkMTimeType mtime = image ? image->GetMTime() : 0;
  if (internals.TextureKeyValid && internals.TextureKeyImage == image &&
    internals.TextureKeyMTime == mtime && internals.TextureKeySRGB == srgb)
  {
    return internals.TextureOK ? true : this->Fail(internals.TextureError);
  }
  internals.TextureKeyValid = true;
  internals.TextureKeyImage = image;
  internals.TextureKeyMTime = mtime;
  internals.TextureKeySRGB = srgb;
  ++internals.TextureGeneration;
  if (!image)
  {
    mrgi_area_light_texture_pyramid_destroy(&internals.Pyramid);
    mrgi_image_destroy(&internals.Image);
    internals.HasTexture = false;
    internals.TextureOK = true;
    return true;
  }
  // Build into temporaries: a bad image leaves the last good pyramid alone.
  mrgi_image converted{};
  mrgi_area_light_texture_pyramid pyramid{};
  std::string why;
  mrgi_error err;
  bool ok = vtkMRGIAreaLightUtilities::ConvertTexture(image, srgb, &converted, why);
  if (ok && mrgi_area_light_texture_pyramid_create(&pyramid, &converted, &err) != MRGI_OK)
  {
    why = std::string("texture: ") + err.message;
    mrgi_image_destroy(&converted);
    ok = false;
  }
  if (!ok)
  {
    internals.TextureOK = false;
    internals.TextureError = "bad area light texture: " + why;
    return this->Fail(internals.TextureError);
  }
  mrgi_area_light_texture_pyramid_destroy(&internals.Pyramid);
  mrgi_image_destroy(&internals.Image);
  internals.Image = converted;
  internals.Pyramid = pyramid;
  internals.HasTexture = true;
  internals.TextureOK = true;
  ++this->NumberOfTextureBuilds;
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLight::BuildCoreLight(mrgi_area_light* light, bool withTexture)
{
  mrgi_area_light core{};
  for (int c = 0; c < 3; ++c)
  {
    core.center[c] = this->Center[c];
    core.edge_u[c] = this->EdgeU[c];
    core.edge_v[c] = this->EdgeV[c];
    core.color[c] = this->Color[c];
  }
  core.intensity = this->Intensity;
  core.two_sided = this->TwoSided ? 1 : 0;
  // The texture was checked when it was converted and its pyramid built;
  // checking the rest without it keeps this O(1) per request.
  mrgi_error err;
  if (mrgi_area_light_check(&core, &err) != MRGI_OK)
  {
    return this->Fail("invalid area light: " + WithPropertyNames(err.message));
  }
  if (withTexture && this->Internals->HasTexture)
  {
    core.texture = &this->Internals->Image;
  }
  *light = core;
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLight::UpdateSamples()
{
  if (!this->UpdateTexture())
  {
    return false;
  }
  vtkInternals& internals = *this->Internals;
  SampleKey key;
  std::memset(&key, 0, sizeof(key)); // padding too: keys are compared with memcmp
  for (int c = 0; c < 3; ++c)
  {
    key.Values[c] = this->Center[c];
    key.Values[3 + c] = this->EdgeU[c];
    key.Values[6 + c] = this->EdgeV[c];
    key.Values[9 + c] = this->Color[c];
  }
  key.Values[12] = this->Intensity;
  key.Seed = this->Seed;
  key.TextureGeneration = internals.TextureGeneration;
  key.NumberOfSamples = this->NumberOfSamples;
  key.Flags = (this->TwoSided ? 1 : 0) | (this->Jitter ? 2 : 0);
  if (internals.SampleKeyValid && std::memcmp(&key, &internals.Key, sizeof(key)) == 0)
  {
    return internals.SamplesOK ? true : this->Fail(internals.SampleError);
  }
  internals.SampleKeyValid = true;
  internals.Key = key;
  internals.SamplesOK = false;

  mrgi_area_light light;
  if (!this->BuildCoreLight(&light, true))
  {
    internals.SampleError = this->LastErrorMessage;
    return false;
  }
  const mrgi_area_light_texture_pyramid* pyramid =
    internals.HasTexture ? &internals.Pyramid : nullptr;
  mrgi_error err;
  int32_t count = 0;
  if (mrgi_area_light_sample_layout(&light, this->NumberOfSamples, nullptr, nullptr, &count,
        &err) != MRGI_OK)
  {
    internals.SampleError = "area light samples: " + WithPropertyNames(err.message);
    return this->Fail(internals.SampleError);
  }
  std::vector<mrgi_area_light_sample> samples(static_cast<size_t>(count));
  if (mrgi_area_light_make_samples(&light, pyramid, this->NumberOfSamples, this->Jitter ? 1 : 0,
        this->Seed, samples.data(), count, &count, &err) != MRGI_OK)
  {
    internals.SampleError = "area light samples: " + WithPropertyNames(err.message);
    return this->Fail(internals.SampleError);
  }
  // Finite inputs can still overflow: a float texel near FLT_MAX times a
  // large Intensity * Color. Never hand out an infinite radiance.
  for (const mrgi_area_light_sample& sample : samples)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (!std::isfinite(sample.radiance[c]))
      {
        internals.SampleError = "area light radiance Intensity * Color * texture exceeds the "
                                "float range";
        return this->Fail(internals.SampleError);
      }
    }
  }
  internals.Samples.swap(samples);
  internals.SampleCount = count;
  internals.SamplesOK = true;
  ++this->NumberOfSampleBuilds;
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLight::GetSamples(vtkFloatArray* samples)
{
  if (!samples)
  {
    return this->Fail("GetSamples: no output array given");
  }
  if (!this->UpdateSamples())
  {
    return false;
  }
  const vtkInternals& internals = *this->Internals;
  samples->SetNumberOfComponents(4);
  samples->SetNumberOfTuples(
    static_cast<vtkIdType>(internals.SampleCount) * MRGI_AREA_LIGHT_SAMPLE_TEXELS);
  std::memcpy(samples->GetPointer(0), mrgi_area_light_sample_texture_data(internals.Samples.data()),
    sizeof(mrgi_area_light_sample) * static_cast<size_t>(internals.SampleCount));
  samples->Modified();
  this->LastErrorMessage.clear();
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLight::GetCoreLight(mrgi_area_light* light)
{
  if (!light)
  {
    return this->Fail("GetCoreLight: no output given");
  }
  mrgi_area_light core;
  if (!this->UpdateTexture() || !this->BuildCoreLight(&core, true))
  {
    return false;
  }
  *light = core;
  this->LastErrorMessage.clear();
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLight::GetCoreUniforms(mrgi_area_light_uniforms* uniforms)
{
  if (!uniforms)
  {
    return this->Fail("GetCoreUniforms: no output given");
  }
  mrgi_area_light core;
  if (!this->UpdateTexture() || !this->BuildCoreLight(&core, true))
  {
    return false;
  }
  mrgi_area_light_uniforms out;
  mrgi_error err;
  if (mrgi_area_light_uniforms_init(&core,
        this->Internals->HasTexture ? &this->Internals->Pyramid : nullptr, &out,
        &err) != MRGI_OK)
  {
    return this->Fail("area light uniforms: " + WithPropertyNames(err.message));
  }
  *uniforms = out;
  this->LastErrorMessage.clear();
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLight::GetCorePyramid(const mrgi_area_light_texture_pyramid** pyramid)
{
  if (!pyramid)
  {
    return this->Fail("GetCorePyramid: no output given");
  }
  if (!this->UpdateTexture())
  {
    return false;
  }
  *pyramid = this->Internals->HasTexture ? &this->Internals->Pyramid : nullptr;
  this->LastErrorMessage.clear();
  return true;
}

//------------------------------------------------------------------------------
const mrgi_area_light_sample* vtkMRGIAreaLight::GetCoreSamples(int* count)
{
  if (!this->UpdateSamples())
  {
    if (count)
    {
      *count = 0;
    }
    return nullptr;
  }
  if (count)
  {
    *count = this->Internals->SampleCount;
  }
  this->LastErrorMessage.clear();
  return this->Internals->Samples.data();
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLight::MakeGeometry(vtkPolyData* quad)
{
  if (!quad)
  {
    return this->Fail("MakeGeometry: no output given");
  }
  // The geometry needs no texture: check the light without it.
  mrgi_area_light light;
  if (!this->BuildCoreLight(&light, false))
  {
    return false;
  }
  // Corners in the order of mrgi_area_light_uniforms::corners (counter-
  // clockwise seen from the emitting side, so VTK's front face is the
  // emitting one), with texture coordinates (s, t) of the core's mapping.
  static const double signs[4][2] = { { -0.5, -0.5 }, { 0.5, -0.5 }, { 0.5, 0.5 }, { -0.5, 0.5 } };
  double normal[3];
  vtkMath::Cross(this->EdgeU, this->EdgeV, normal);
  vtkMath::Normalize(normal);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> tcoords;
  tcoords->SetName("TCoords");
  tcoords->SetNumberOfComponents(2);
  for (const auto& sign : signs)
  {
    double corner[3];
    for (int c = 0; c < 3; ++c)
    {
      corner[c] = this->Center[c] + sign[0] * this->EdgeU[c] + sign[1] * this->EdgeV[c];
    }
    points->InsertNextPoint(corner);
    normals->InsertNextTuple(normal);
    const double st[2] = { sign[0] + 0.5, sign[1] + 0.5 };
    tcoords->InsertNextTuple(st);
  }
  vtkNew<vtkCellArray> polys;
  const vtkIdType ids[4] = { 0, 1, 2, 3 };
  polys->InsertNextCell(4, ids);
  quad->Initialize();
  quad->SetPoints(points);
  quad->SetPolys(polys);
  quad->GetPointData()->SetNormals(normals);
  quad->GetPointData()->SetTCoords(tcoords);
  return true;
}

//------------------------------------------------------------------------------
vtkActor* vtkMRGIAreaLight::GetGeometryActor()
{
  vtkInternals& internals = *this->Internals;
  if (!internals.Actor)
  {
    vtkNew<vtkMRGIAreaLightGeometrySource> geometry;
    geometry->Light = this;
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(geometry->GetOutputPort());
    mapper->ScalarVisibilityOff();
    internals.Actor = vtkSmartPointer<vtkActor>::New();
    internals.Actor->SetMapper(mapper);

    vtkNew<vtkMRGIAreaLightEmissionSource> emission;
    emission->Light = this;
    internals.EmissionTexture = vtkSmartPointer<vtkTexture>::New();
    internals.EmissionTexture->SetInputConnection(emission->GetOutputPort());
    // 8 bits sRGB-encoded keep dark radiances; GL decodes back to linear.
    internals.EmissionTexture->UseSRGBColorSpaceOn();
    internals.EmissionTexture->InterpolateOn();
    internals.EmissionTexture->MipmapOn(); // a video frame seen small must not alias
    // Mesa llvmpipe's anisotropic filtering (VTK's default 4x) blends coarser
    // levels in even where the texture is magnified (measured: a 2 x 2
    // picture drawn 64 pixels wide mixed all four texels where bilinear
    // filtering gives one texel's colour): plain trilinear filtering.
    internals.EmissionTexture->SetMaximumAnisotropicFiltering(1.0f);
    internals.EmissionTexture->RepeatOff();
    internals.EmissionTexture->EdgeClampOn();

    // The back of a one-sided emitter emits nothing: black, not see-through.
    internals.BackProperty = vtkSmartPointer<vtkProperty>::New();
    internals.BackProperty->LightingOff();
    internals.BackProperty->SetAmbient(1.0);
    internals.BackProperty->SetDiffuse(0.0);
    internals.BackProperty->SetSpecular(0.0);
    this->UpdateGeometryActor();
  }
  return internals.Actor;
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLight::UpdateGeometryActor()
{
  if (!this->Internals || !this->Internals->Actor)
  {
    return;
  }
  vtkInternals& internals = *this->Internals;
  vtkActor* actor = internals.Actor;
  actor->SetVisibility(this->Visible ? 1 : 0);
  vtkProperty* property = actor->GetProperty();
  // An emitter shows its radiance whatever the lights (as the emitters of
  // vtkMRGISceneBuilder): VTK's ambient term only.
  property->LightingOff();
  property->SetAmbient(1.0);
  property->SetDiffuse(0.0);
  property->SetSpecular(0.0);
  const bool textured = this->Texture || this->TextureData;
  double front[3] = { 1.0, 1.0, 1.0 };
  if (!textured)
  {
    for (int c = 0; c < 3; ++c)
    {
      front[c] = Sanitized(this->Intensity) * Sanitized(this->Color[c]);
    }
  }
  vtkTexture* texture = textured ? internals.EmissionTexture.Get() : nullptr;
  actor->SetTexture(texture);
  // With a texture, VTK clamps the colour to [0, 1] before it modulates
  // the texture: the radiance scale is in the emission picture and the
  // colour is white. Without one, the colour is the radiance.
  property->SetAmbientColor(front);
  property->SetColor(front);
  // The backface property stays set (VTK 9.1's mapper keeps reading it
  // once its shader was built with it, even after it is removed): black
  // for a one-sided light, the front's look for a two-sided one.
  double back[3];
  for (int c = 0; c < 3; ++c)
  {
    back[c] = this->TwoSided ? front[c] : 0.0;
  }
  internals.BackProperty->SetAmbientColor(back);
  internals.BackProperty->SetColor(back);
  actor->SetBackfaceProperty(internals.BackProperty);
  // The shared views follow the texture switch (everything else they share).
  for (const vtkWeakPointer<vtkActor>& view : internals.Views)
  {
    if (view)
    {
      view->SetTexture(texture);
    }
  }
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLight::ShareGeometryActor(vtkActor* actor)
{
  vtkActor* own = this->GetGeometryActor();
  if (!actor || actor == own)
  {
    return;
  }
  // Forget views that are gone; add this one once.
  auto& views = this->Internals->Views;
  views.erase(std::remove_if(views.begin(), views.end(),
                [](const vtkWeakPointer<vtkActor>& view) { return !view; }),
    views.end());
  if (std::none_of(views.begin(), views.end(),
        [actor](const vtkWeakPointer<vtkActor>& view) { return view.Get() == actor; }))
  {
    views.emplace_back(actor);
  }
  // Its own quad source (the same quad), which keeps the light alive: the
  // view may outlive whoever made it (a scene builder).
  vtkNew<vtkMRGIAreaLightGeometrySource> geometry;
  geometry->Light = this;
  geometry->Owner = this;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(geometry->GetOutputPort());
  mapper->ScalarVisibilityOff();
  actor->SetMapper(mapper);
  actor->SetProperty(own->GetProperty());
  actor->SetBackfaceProperty(own->GetBackfaceProperty());
  actor->SetTexture(own->GetTexture());
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLight::ReleaseGraphicsResources(vtkWindow* window)
{
  vtkInternals& internals = *this->Internals;
  for (vtkSmartPointer<vtkTextureObject>* texture :
    { &internals.PyramidTexture, &internals.SampleTexture })
  {
    if (*texture && window)
    {
      (*texture)->ReleaseGraphicsResources(window);
    }
    *texture = nullptr;
  }
  internals.TexturesActive = false;
  internals.GLWindow = nullptr;
  internals.HadGLWindow = false;
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLight::UseGraphicsWindow(vtkOpenGLRenderWindow* window)
{
  vtkInternals& internals = *this->Internals;
  if (internals.HadGLWindow && internals.GLWindow.Get() != window)
  {
    // Textures live in one context: free them in the old window (or forget
    // them when that window, and its context, is gone).
    vtkOpenGLRenderWindow* old = internals.GLWindow;
    if (old)
    {
      old->MakeCurrent();
    }
    this->ReleaseGraphicsResources(old);
  }
  internals.GLWindow = window;
  internals.HadGLWindow = true;
  window->MakeCurrent();
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIAreaLight::GetPyramidTexture(vtkOpenGLRenderWindow* window)
{
  if (!window)
  {
    this->Fail("GetPyramidTexture: no window given");
    return nullptr;
  }
  if (!this->UpdateTexture())
  {
    return nullptr;
  }
  this->UseGraphicsWindow(window);
  vtkInternals& internals = *this->Internals;
  if (internals.PyramidTexture &&
    internals.PyramidTextureGeneration == internals.TextureGeneration)
  {
    this->LastErrorMessage.clear();
    return internals.PyramidTexture;
  }
  // An untextured light: the core's 1 x 1 white pyramid.
  mrgi_area_light_texture_pyramid white{};
  float whiteTexel[3];
  mrgi_error err;
  const mrgi_area_light_texture_pyramid* pyramid = &internals.Pyramid;
  if (!internals.HasTexture)
  {
    if (mrgi_area_light_texture_pyramid_init(&white, nullptr, whiteTexel, 3, &err) != MRGI_OK)
    {
      this->Fail(std::string("area light pyramid: ") + err.message);
      return nullptr;
    }
    pyramid = &white;
  }
  if (!internals.PyramidTexture)
  {
    internals.PyramidTexture = vtkSmartPointer<vtkTextureObject>::New();
  }
  vtkTextureObject* texture = internals.PyramidTexture;
  if (!vtkMRGIAreaLightUtilities::UploadPyramid(texture, window, pyramid))
  {
    this->Fail("GetPyramidTexture: could not create the GL texture");
    return nullptr;
  }
  internals.PyramidTextureGeneration = internals.TextureGeneration;
  ++this->NumberOfPyramidUploads;
  this->LastErrorMessage.clear();
  return texture;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIAreaLight::GetSampleTexture(vtkOpenGLRenderWindow* window, int* count)
{
  if (count)
  {
    *count = 0;
  }
  if (!window)
  {
    this->Fail("GetSampleTexture: no window given");
    return nullptr;
  }
  if (!this->UpdateSamples())
  {
    return nullptr;
  }
  this->UseGraphicsWindow(window);
  vtkInternals& internals = *this->Internals;
  if (!internals.SampleTexture || internals.SampleTextureBuild != this->NumberOfSampleBuilds)
  {
    if (!internals.SampleTexture)
    {
      internals.SampleTexture = vtkSmartPointer<vtkTextureObject>::New();
    }
    if (!vtkMRGIAreaLightUtilities::UploadSamples(
          internals.SampleTexture, window, internals.Samples.data(), internals.SampleCount))
    {
      this->Fail("GetSampleTexture: could not create the GL texture");
      return nullptr;
    }
    internals.SampleTextureBuild = this->NumberOfSampleBuilds;
    ++this->NumberOfSampleUploads;
  }
  if (count)
  {
    *count = internals.SampleCount;
  }
  this->LastErrorMessage.clear();
  return internals.SampleTexture;
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLight::SetShaderUniforms(vtkShaderProgram* program, vtkOpenGLRenderWindow* window)
{
  if (!program)
  {
    return this->Fail("SetShaderUniforms: no shader program given");
  }
  if (!window)
  {
    return this->Fail("SetShaderUniforms: no window given");
  }
  mrgi_area_light_uniforms light;
  int count = 0;
  if (!this->GetCoreUniforms(&light))
  {
    return false;
  }
  vtkTextureObject* samples = this->GetSampleTexture(window, &count);
  vtkTextureObject* pyramid = samples ? this->GetPyramidTexture(window) : nullptr;
  if (!samples || !pyramid)
  {
    return false;
  }
  auto used = [program](const char* name) { return program->IsUniformUsed(name); };
  if (used("mrgiAreaSamples"))
  {
    samples->Activate();
    program->SetUniformi("mrgiAreaSamples", samples->GetTextureUnit());
    this->Internals->TexturesActive = true;
  }
  if (used("mrgiAreaPyramid"))
  {
    pyramid->Activate();
    program->SetUniformi("mrgiAreaPyramid", pyramid->GetTextureUnit());
    this->Internals->TexturesActive = true;
  }
  const int textureSize[2] = { light.texture_width, light.texture_height };
  if (used("mrgiAreaSampleFirst"))
  {
    program->SetUniformi("mrgiAreaSampleFirst", 0);
  }
  if (used("mrgiAreaSampleCount"))
  {
    program->SetUniformi("mrgiAreaSampleCount", count);
  }
  const struct
  {
    const char* Name;
    const float* Value;
  } vectors[] = { { "mrgiAreaCenter", light.center }, { "mrgiAreaNormal", light.normal },
    { "mrgiAreaAxisU", light.axis_u }, { "mrgiAreaAxisV", light.axis_v },
    { "mrgiAreaScale", light.scale } };
  for (const auto& vector : vectors)
  {
    if (used(vector.Name))
    {
      program->SetUniform3f(vector.Name, vector.Value);
    }
  }
  if (used("mrgiAreaCorners"))
  {
    program->SetUniform3fv("mrgiAreaCorners", 4, light.corners);
  }
  if (used("mrgiAreaTwoSided"))
  {
    program->SetUniformi("mrgiAreaTwoSided", light.two_sided);
  }
  if (used("mrgiAreaHalfU"))
  {
    program->SetUniformf("mrgiAreaHalfU", light.half_u);
  }
  if (used("mrgiAreaHalfV"))
  {
    program->SetUniformf("mrgiAreaHalfV", light.half_v);
  }
  if (used("mrgiAreaTextureSize"))
  {
    program->SetUniform2i("mrgiAreaTextureSize", textureSize);
  }
  if (used("mrgiAreaTextureLevels"))
  {
    program->SetUniformi("mrgiAreaTextureLevels", light.texture_levels);
  }
  if (used("mrgiAreaTextured"))
  {
    program->SetUniformi("mrgiAreaTextured", this->Internals->HasTexture ? 1 : 0);
  }
  this->LastErrorMessage.clear();
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLight::DeactivateTextures()
{
  vtkInternals& internals = *this->Internals;
  if (!internals.TexturesActive)
  {
    return;
  }
  for (vtkTextureObject* texture : { internals.SampleTexture.Get(), internals.PyramidTexture.Get() })
  {
    if (texture)
    {
      texture->Deactivate();
    }
  }
  internals.TexturesActive = false;
}

//------------------------------------------------------------------------------
const char* vtkMRGIAreaLight::GetSpecularShaderSource()
{
  return vtkMRGIAreaLightSpecular;
}

//------------------------------------------------------------------------------
std::string vtkMRGIAreaLight::GetShaderSource(bool diffuse, bool specular)
{
  std::string source;
  if (diffuse)
  {
    source += vtkMRGIAreaLightDiffuse;
  }
  if (diffuse && specular)
  {
    source += "\n#define MRGI_AREA_LIGHT_DIFFUSE_DECLARED\n";
  }
  if (specular)
  {
    source += vtkMRGIAreaLightSpecular;
  }
  return source;
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLight::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Center: (" << this->Center[0] << ", " << this->Center[1] << ", "
     << this->Center[2] << ")\n";
  os << indent << "EdgeU: (" << this->EdgeU[0] << ", " << this->EdgeU[1] << ", "
     << this->EdgeU[2] << ")\n";
  os << indent << "EdgeV: (" << this->EdgeV[0] << ", " << this->EdgeV[1] << ", "
     << this->EdgeV[2] << ")\n";
  os << indent << "Color: (" << this->Color[0] << ", " << this->Color[1] << ", "
     << this->Color[2] << ")\n";
  os << indent << "Intensity: " << this->Intensity << "\n";
  os << indent << "TwoSided: " << (this->TwoSided ? "On" : "Off") << "\n";
  os << indent << "NumberOfSamples: " << this->NumberOfSamples << "\n";
  os << indent << "Jitter: " << (this->Jitter ? "On" : "Off") << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Visible: " << (this->Visible ? "On" : "Off") << "\n";
  os << indent << "Texture: " << static_cast<void*>(this->Texture) << "\n";
  os << indent << "TextureData: " << static_cast<void*>(this->TextureData) << "\n";
  os << indent << "NumberOfTextureBuilds: " << this->NumberOfTextureBuilds << "\n";
  os << indent << "NumberOfSampleBuilds: " << this->NumberOfSampleBuilds << "\n";
  os << indent << "NumberOfPyramidUploads: " << this->NumberOfPyramidUploads << "\n";
  os << indent << "NumberOfSampleUploads: " << this->NumberOfSampleUploads << "\n";
  os << indent << "LastErrorMessage: "
     << (this->LastErrorMessage.empty() ? "(none)" : this->LastErrorMessage) << "\n";
}
