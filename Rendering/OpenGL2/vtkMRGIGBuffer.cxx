#include "vtk_glew.h"

#include "vtkMRGIGBuffer.h"

#include "vtkMRGIShaderUtilities.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"

//------------------------------------------------------------------------------
void vtkMRGIGBuffer::Prepare(vtkOpenGLRenderWindow* window, int w, int h, bool capture, bool specular)
{
  auto ensure = [&](vtkTextureObject*& t, int format) {
    if (!t)
    {
      t = vtkMRGIShaderUtilities::NewTexture(window, format, w, h);
    }
    else
    {
      t->Resize(static_cast<unsigned int>(w), static_cast<unsigned int>(h));
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
  }
  this->Depth->Resize(static_cast<unsigned int>(w), static_cast<unsigned int>(h));
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
  for (vtkTextureObject** t : { &this->Color, &this->Depth, &this->Position, &this->Normal,
         &this->Albedo, &this->Specular, &this->Shininess, &this->Irradiance, &this->Indirect })
  {
    vtkMRGIShaderUtilities::ReleaseTexture(*t, w);
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIGBuffer::HoldsResources() const
{
  return this->FrameBuffer || this->Color || this->Depth || this->Position;
}
