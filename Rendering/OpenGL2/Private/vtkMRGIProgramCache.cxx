#include "vtkMRGIProgramCache.h"

#include "vtkMRGIShaderUtilities.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkShaderProgram.h"

//------------------------------------------------------------------------------
vtkMRGIProgramCache::~vtkMRGIProgramCache()
{
  // Without a window the GL objects cannot be freed here; the owner's
  // ReleaseGraphicsResources() does that. The helpers themselves go.
  for (auto& entry : this->Quads)
  {
    delete entry.second;
  }
}

//------------------------------------------------------------------------------
vtkOpenGLQuadHelper* vtkMRGIProgramCache::Ready(vtkOpenGLRenderWindow* window,
  const std::string& stage, const std::string& defines, const std::function<std::string()>& source)
{
  vtkOpenGLQuadHelper*& quad = this->Quads[stage + '\n' + defines];
  if (!quad)
  {
    const std::string body = defines + source();
    quad = new vtkOpenGLQuadHelper(window,
      vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
      vtkMRGIShaderUtilities::FullScreenShader(body.c_str()).c_str(), "");
  }
  window->GetShaderCache()->ReadyShaderProgram(quad->Program);
  return (quad->Program && quad->Program->GetCompiled()) ? quad : nullptr;
}

//------------------------------------------------------------------------------
void vtkMRGIProgramCache::ReleaseGraphicsResources(vtkWindow* w)
{
  for (auto& entry : this->Quads)
  {
    if (entry.second && w)
    {
      entry.second->ReleaseGraphicsResources(w);
    }
    delete entry.second;
  }
  this->Quads.clear();
}
