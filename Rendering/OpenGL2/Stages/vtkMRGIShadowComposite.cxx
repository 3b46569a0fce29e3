#include "vtk_glew.h"

#include "vtkMRGIShadowComposite.h"

#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIShadowCompositeFS.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIStageResources.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

vtkStandardNewMacro(vtkMRGIShadowComposite);

struct vtkMRGIShadowComposite::Internals
{
  vtkMRGIStageResources GL; // framebuffer and program
};

//------------------------------------------------------------------------------
vtkMRGIShadowComposite::vtkMRGIShadowComposite()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkMRGIShadowComposite::~vtkMRGIShadowComposite()
{
  if (this->Internal->GL.FrameBuffer)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
}

//------------------------------------------------------------------------------
void vtkMRGIShadowComposite::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internal->GL.Release(w);
}

//------------------------------------------------------------------------------
bool vtkMRGIShadowComposite::Apply(const vtkMRGIFrameContext& frame, vtkTextureObject* colour,
  vtkTextureObject* const terms[MRGI_SHADOW_SLOTS], vtkTextureObject* factors,
  vtkTextureObject* target)
{
  vtkOpenGLRenderWindow* window = frame.Window;
  bool inputs = window && colour && factors && target && target != colour;
  for (int s = 0; inputs && s < MRGI_SHADOW_SLOTS; ++s)
  {
    inputs = terms[s] != nullptr;
  }
  if (!inputs)
  {
    vtkErrorMacro("applying shadows needs the colour, the light terms, the factors and a "
                  "separate target");
    return false;
  }
  Internals& in = *this->Internal;
  in.GL.Prepare(window);
  vtkOpenGLQuadHelper* quad = in.GL.Programs.Ready(window, "shadows.apply", "",
    [] { return vtkMRGIShadowCompositeFS; });
  if (!quad)
  {
    vtkErrorMacro("could not build the shadow composite shader");
    return false;
  }
  vtkShaderProgram* program = quad->Program;
  vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "shadows.apply");
  {
    vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
    window->GetShaderCache()->ReadyShaderProgram(program);
    steps.Target(target, nullptr, frame.Viewport[0], frame.Viewport[1], frame.Viewport[2],
      frame.Viewport[3]);
    static_assert(MRGI_SHADOW_SLOTS == 2, "bind one input per slot");
    vtkMRGIFullScreenStep::BindInputs(program, { colour, factors, terms[0], terms[1] });
    quad->Render();
    vtkMRGIFullScreenStep::UnbindInputs({ colour, factors, terms[0], terms[1] });
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIShadowComposite::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "HoldsResources: " << (this->Internal->GL.FrameBuffer ? "yes" : "no") << "\n";
}
