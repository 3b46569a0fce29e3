#include "vtk_glew.h"

#include "vtkMRGIGBuffer.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIResourceStatistics.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkTextureObject.h"

//------------------------------------------------------------------------------
void vtkMRGIGBuffer::Prepare(vtkOpenGLRenderWindow* window, int w, int h, bool capture,
  bool specular, bool shadows, bool display)
{
  auto ensure = [&](vtkTextureObject*& t, int format) {
    if (!t)
    {
      t = vtkMRGIShaderUtilities::NewTexture(window, format, w, h);
    }
    else
    {
      vtkMRGIShaderUtilities::ResizeTexture(t, w, h);
    }
  };
  ensure(this->Color, GL_RGBA32F);
  if (!this->Depth)
  {
    this->Depth = vtkTextureObject::New();
    this->Depth->SetContext(window);
    this->Depth->SetMinificationFilter(vtkTextureObject::Nearest);
    this->Depth->SetMagnificationFilter(vtkTextureObject::Nearest);
    // The depth format of VTK's own framebuffers, chosen as
    // vtkOrderIndependentTranslucentPass chooses its depth texture (from the
    // framebuffer bound now: the window's, or an enclosing pass's): that pass
    // blits MRGI's depth into its texture, and a blit needs identical depth
    // formats (a float depth here left translucent props without depth test).
    if (window->GetStencilCapable())
    {
      this->Depth->AllocateDepthStencil(static_cast<unsigned int>(w), static_cast<unsigned int>(h));
    }
    else
    {
      this->Depth->AllocateDepth(static_cast<unsigned int>(w), static_cast<unsigned int>(h),
        window->GetDepthBufferSize() == 32 ? vtkTextureObject::Fixed32 : vtkTextureObject::Fixed24);
    }
    vtkMRGIResourceStatistics::RecordTextureAllocation(w, h, 4);
  }
  vtkMRGIShaderUtilities::ResizeTexture(this->Depth, w, h);
  if (capture)
  {
    ensure(this->Position, GL_RGBA32F);
    ensure(this->Normal, GL_RGBA16F);
    ensure(this->Albedo, GL_RGBA16F);
    ensure(this->Irradiance, GL_RGBA32F);
    ensure(this->Indirect, GL_RGBA32F);
    if (specular)
    {
      ensure(this->Specular, GL_RGBA16F);
      ensure(this->Shininess, GL_RGBA16F);
    }
    if (shadows)
    {
      // Terms in float, like the colour they are subtracted from: half
      // floats overflow above 65504 (bright lights would lose their
      // shadows) and leave 5e-4 of a removed term behind. Factors lie in
      // [0, 1]: half floats suffice.
      for (vtkTextureObject*& t : this->LightTerms)
      {
        ensure(t, GL_RGBA32F);
      }
      ensure(this->ShadowFactors, GL_RGBA16F);
      ensure(this->Shadowed, GL_RGBA32F);
    }
  }
  if (display)
  {
    // Display values: 16-bit float holds 8-bit precision and more.
    ensure(this->Display, GL_RGBA16F);
  }
  if (!this->FrameBuffer)
  {
    this->FrameBuffer = vtkOpenGLFramebufferObject::New();
    this->FrameBuffer->SetContext(window);
  }
}

//------------------------------------------------------------------------------
void vtkMRGIGBuffer::Release(vtkWindow* w)
{
  if (this->FrameBuffer)
  {
    if (w)
    {
      this->FrameBuffer->ReleaseGraphicsResources(w);
    }
    this->FrameBuffer->Delete();
    this->FrameBuffer = nullptr;
  }
  for (vtkTextureObject** t :
    { &this->Color, &this->Depth, &this->Position, &this->Normal, &this->Albedo, &this->Specular,
      &this->Shininess, &this->Irradiance, &this->Indirect, &this->Display,
      &this->ShadowFactors, &this->Shadowed })
  {
    vtkMRGIShaderUtilities::ReleaseTexture(*t, w);
  }
  for (vtkTextureObject*& t : this->LightTerms)
  {
    vtkMRGIShaderUtilities::ReleaseTexture(t, w);
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIGBuffer::HoldsResources() const
{
  return this->FrameBuffer || this->Color || this->Depth || this->Position;
}

//------------------------------------------------------------------------------
bool vtkMRGIGBuffer::ReadViewport(vtkOpenGLRenderWindow* window, vtkTextureObject* texture,
  const int viewport[4], int components, vtkImageData* image)
{
  if (!image || !texture || viewport[2] < 1 || viewport[3] < 1)
  {
    return false;
  }
  // Straight into the image, with no whole-texture copy beside it: a
  // read-back runs while every GL buffer is still allocated, i.e. at the
  // peak of a program's memory (llvmpipe keeps textures in host memory).
  image->SetDimensions(viewport[2], viewport[3], 1);
  image->AllocateScalars(VTK_FLOAT, components);
  float* out = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars())->GetPointer(0);
  if (components == 3 || components == 4)
  {
    return vtkMRGIShaderUtilities::ReadTextureRegion(
      window, texture, viewport[0], viewport[1], viewport[2], viewport[3], components, out);
  }
  std::vector<float> rgba; // other channel counts: through a whole RGBA copy
  if (!vtkMRGIShaderUtilities::ReadTextureRGBA(window, texture, rgba))
  {
    return false;
  }
  const int fullWidth = static_cast<int>(texture->GetWidth());
  const int x0 = viewport[0], y0 = viewport[1];
  const int w = viewport[2], h = viewport[3];
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const float* src = rgba.data() + 4 * (static_cast<size_t>(y + y0) * fullWidth + (x + x0));
      for (int c = 0; c < components; ++c)
      {
        out[(static_cast<size_t>(y) * w + x) * components + c] = src[c];
      }
    }
  }
  return true;
}
