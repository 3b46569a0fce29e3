#include "vtkMRGIStageResources.h"

#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"

//------------------------------------------------------------------------------
vtkMRGIStageResources::~vtkMRGIStageResources()
{
  this->Release(nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGIStageResources::Prepare(vtkOpenGLRenderWindow* window)
{
  if (!this->FrameBuffer)
  {
    this->FrameBuffer = vtkOpenGLFramebufferObject::New();
    this->FrameBuffer->SetContext(window);
  }
}

//------------------------------------------------------------------------------
void vtkMRGIStageResources::Release(vtkWindow* w)
{
  this->Programs.ReleaseGraphicsResources(w);
  if (this->FrameBuffer)
  {
    if (w)
    {
      this->FrameBuffer->ReleaseGraphicsResources(w);
    }
    this->FrameBuffer->Delete();
    this->FrameBuffer = nullptr;
  }
}
