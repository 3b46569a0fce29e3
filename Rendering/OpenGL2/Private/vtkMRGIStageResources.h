/**
 * @class   vtkMRGIStageResources
 * @brief   Internal: the GL objects every MRGI stage holds beside its
 *          textures: the framebuffer it draws through and its programs.
 *
 * One create/release routine for all stages: Prepare() on first use,
 * Release() from the stage's ReleaseGraphicsResources(); the destructor
 * frees what is left without a context. Not wrapped, not installed.
 */
#ifndef vtkMRGIStageResources_h
#define vtkMRGIStageResources_h

#include "vtkMRGIProgramCache.h" // For vtkMRGIProgramCache

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkWindow;

class vtkMRGIStageResources
{
public:
  vtkMRGIStageResources() = default;
  ~vtkMRGIStageResources();

  /** Create the framebuffer in `window`'s context when there is none yet. */
  void Prepare(vtkOpenGLRenderWindow* window);

  /** Free the framebuffer and every program (their GL objects too when `w` is given). */
  void Release(vtkWindow* w);

  vtkOpenGLFramebufferObject* FrameBuffer = nullptr;
  vtkMRGIProgramCache Programs;

private:
  vtkMRGIStageResources(const vtkMRGIStageResources&) = delete;
  void operator=(const vtkMRGIStageResources&) = delete;
};

#endif
