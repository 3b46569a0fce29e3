#include "vtkMRGIAreaLight.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIAreaLightEmitter.h"
#include "vtkMRGIAreaLightUtilities.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTexture.h"
#include "vtkTextureObject.h"
#include "vtkWeakPointer.h"

// The area-light GLSL libraries (embedded by vtk_encode_string).
#include "vtkMRGIShaderLibraries.h"
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

  // What draws the emitter (GetGeometryActor(); created on first request).
  vtkSmartPointer<vtkMRGIAreaLightEmitter> Emitter;

  ~vtkInternals()
  {
    mrgi_area_light_texture_pyramid_destroy(&this->Pyramid);
    mrgi_image_destroy(&this->Image);
  }
};

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
bool vtkMRGIAreaLight::MakeCoreLight(const double center[3], const double edgeU[3],
  const double edgeV[3], const double color[3], double intensity, bool twoSided,
  mrgi_area_light* light, std::string* why)
{
  mrgi_area_light core{};
  for (int c = 0; c < 3; ++c)
  {
    core.center[c] = center[c];
    core.edge_u[c] = edgeU[c];
    core.edge_v[c] = edgeV[c];
    core.color[c] = color[c];
  }
  core.intensity = intensity;
  core.texture = nullptr;
  core.two_sided = twoSided ? 1 : 0;
  mrgi_error err;
  if (mrgi_area_light_check(&core, &err) != MRGI_OK)
  {
    if (why)
    {
      *why = WithPropertyNames(err.message);
    }
    return false;
  }
  if (light)
  {
    *light = core;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLight::BuildCoreLight(mrgi_area_light* light, bool withTexture)
{
  // The texture was checked when it was converted and its pyramid built;
  // checking the rest without it keeps this O(1) per request.
  mrgi_area_light core;
  std::string why;
  if (!MakeCoreLight(this->Center, this->EdgeU, this->EdgeV, this->Color, this->Intensity,
        this->TwoSided, &core, &why))
  {
    return this->Fail("invalid area light: " + why);
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
  vtkMRGIAreaLightEmitter::MakeQuad(this->Center, this->EdgeU, this->EdgeV, quad);
  return true;
}

//------------------------------------------------------------------------------
vtkActor* vtkMRGIAreaLight::GetGeometryActor()
{
  vtkInternals& internals = *this->Internals;
  if (!internals.Emitter)
  {
    // The emitter asks for the quad and the picture at render time; it holds
    // the light weakly (a renderer may keep the actor after the light is gone).
    vtkWeakPointer<vtkMRGIAreaLight> self = this;
    auto quad = [self](vtkPolyData* output) { return self && self->MakeGeometry(output); };
    auto picture = [self]() {
      vtkMRGIAreaLightEmitter::Picture shown;
      if (self && self->UpdateTexture())
      {
        shown.Image = self->Internals->HasTexture ? &self->Internals->Image : nullptr;
        shown.Intensity = self->Intensity;
        std::copy(self->Color, self->Color + 3, shown.Color);
      }
      return shown;
    };
    internals.Emitter = vtkSmartPointer<vtkMRGIAreaLightEmitter>::New();
    internals.Emitter->SetLight(this, quad, picture);
    this->UpdateGeometryActor();
  }
  return internals.Emitter->GetActor();
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLight::UpdateGeometryActor()
{
  if (!this->Internals || !this->Internals->Emitter)
  {
    return;
  }
  vtkMRGIAreaLightEmitter::Look look;
  look.Visible = this->Visible;
  look.Textured = this->Texture || this->TextureData;
  look.TwoSided = this->TwoSided;
  look.Intensity = this->Intensity;
  std::copy(this->Color, this->Color + 3, look.Color);
  this->Internals->Emitter->UpdateActor(look);
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLight::ShareGeometryActor(vtkActor* actor)
{
  this->GetGeometryActor();
  this->Internals->Emitter->ShareActor(actor);
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
  // The diffuse library first: it ends with MRGI_AREA_LIGHT_DIFFUSE_DECLARED.
  return diffuse && specular
    ? vtkMRGIShaderLibraries::Compose({ "vtkMRGIAreaLightDiffuse", "vtkMRGIAreaLightSpecular" })
    : diffuse ? vtkMRGIShaderLibraries::Compose({ "vtkMRGIAreaLightDiffuse" })
    : specular ? vtkMRGIShaderLibraries::Compose({ "vtkMRGIAreaLightSpecular" })
               : std::string();
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
