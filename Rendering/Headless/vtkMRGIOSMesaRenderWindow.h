/**
 * @class   vtkMRGIOSMesaRenderWindow
 * @brief   Headless OpenGL render window on Mesa's OSMesa (software, no X, no EGL).
 *
 * Debian's VTK 9.1 and ParaView 5.11's VTK 9.2 are built without
 * vtkOSOpenGLRenderWindow. This window makes its own OSMesa context with
 * Debian's libOSMesa (package libosmesa6): the highest OpenGL core profile
 * OSMesa offers, tried in the order 4.5, 3.3, 3.2. Like vtkMRGIEGLRenderWindow it
 * always renders into VTK's own offscreen framebuffers (OffScreenRendering is
 * forced on), which follow the window's size; OSMesa's own colour buffer
 * (framebuffer 0) is a single pixel without depth or stencil, which VTK
 * never draws into.
 *
 * **How GL calls reach OSMesa.** VTK calls OpenGL through libglvnd
 * (libOpenGL/libGL, whose entry points dispatch to the vendor of the current
 * context) and through GLEW's function pointers, which GLEW (GLX flavour)
 * loads with glXGetProcAddressARB, i.e. glvnd dispatch stubs as well. OSMesa
 * is not a glvnd vendor, so making an OSMesa context current alone leaves
 * every such call a no-op. The window therefore also makes a glvnd dispatch
 * table current whose entries come from OSMesaGetProcAddress
 * (libGLdispatch's ABI version 1, the one libGLX and libEGL use). Then
 * glewInit() loads every entry point and fails only its GLX check
 * (GLEW_ERROR_NO_GLX_DISPLAY), which OpenGLInitContext() accepts, as the EGL
 * window does.
 *
 * **Loading.** libOSMesa is opened with dlopen (RTLD_LOCAL) the first time an
 * OSMesa context is made, never before: programs and ParaView that use the EGL
 * or X window never load it, and MRGI has no link dependency on it. The
 * environment variable `MRGI_OSMESA_LIBRARY` names another file to open
 * (default libOSMesa.so.8, then libOSMesa.so.6).
 *
 * **Next to EGL and GLX.** libglvnd allows one window-system API current per
 * thread. MakeCurrent() first releases a current EGL context of the thread
 * (vtkMRGIEGLRenderWindow::MakeCurrent does the converse through
 * ReleaseCurrentOSMesaContext()), so EGL and OSMesa windows can alternate in
 * one process. A current GLX context is not released: MakeCurrent() reports
 * it as an error instead.
 *
 * @sa vtkMRGIRenderWindowFactory, which makes this window for
 * MRGI_BACKEND=osmesa (or when no EGL context can be had),
 * vtkMRGIEGLRenderWindow.
 */
#ifndef vtkMRGIOSMesaRenderWindow_h
#define vtkMRGIOSMesaRenderWindow_h

#include "MRGIRenderingHeadlessModule.h" // For export macro
#include "vtkGenericOpenGLRenderWindow.h"

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class MRGIRENDERINGHEADLESS_EXPORT vtkMRGIOSMesaRenderWindow : public vtkGenericOpenGLRenderWindow
{
public:
  static vtkMRGIOSMesaRenderWindow* New();
  vtkTypeMacro(vtkMRGIOSMesaRenderWindow, vtkGenericOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Load libOSMesa if needed and create the context now (Render() does it on
   * demand). Returns false, with the reason in GetLastErrorMessage(), when
   * libOSMesa cannot be loaded, libglvnd's dispatch cannot be reached, or no
   * OpenGL 3.2+ core context can be made.
   */
  bool InitializeHeadlessContext();

  /**
   * Whether an OSMesa OpenGL 3.2+ core context can be created here.
   * Loads libOSMesa (once per process) and creates and destroys a context.
   */
  static bool IsHeadlessRenderingAvailable();

  /**
   * Make no OSMesa context current on this thread, if one of these windows
   * has one current. Does nothing (and loads nothing) when libOSMesa was never
   * loaded. Other window systems call it before making their own context
   * current: libglvnd refuses to switch APIs while one is current.
   */
  static void ReleaseCurrentOSMesaContext();

  /** What was made: "OSMesa, OpenGL 4.5 core, <GL_RENDERER>"; empty before init. */
  const char* GetPlatformDescription() { return this->PlatformDescription.c_str(); }

  /** Why the last attempt to create or make current a context failed; empty when none did. */
  const char* GetLastErrorMessage() { return this->LastErrorMessage.c_str(); }

  /** The OpenGL version of the context as major * 10 + minor (45 for 4.5); 0 before init. */
  vtkGetMacro(ContextVersion, int);

  ///@{
  /** vtkRenderWindow / vtkOpenGLRenderWindow API backed by OSMesa. */
  void Initialize() override;
  void Finalize() override;
  void Start() override;
  void Render() override;
  void MakeCurrent() override;
  void ReleaseCurrent() override;
  bool IsCurrent() override;
  int SupportsOpenGL() override;
  void OpenGLInitContext() override;
  void* GetGenericContext() override;
  void* GetGenericDisplayId() override;
  int GetColorBufferSizes(int* rgba) override;
  /**
   * Depth bits of the framebuffer VTK renders into (vtkMRGIHeadlessDepth.h):
   * vtkRenderer picks its near plane from them, as in a desktop window.
   */
  int GetDepthBufferSize() override;
  using Superclass::GetZbufferData;
  ///@}

  ///@{
  /**
   * Make this context current and restore the previous one (OSMesa or EGL)
   * afterwards, as VTK does when it frees a resource of this window while
   * another window renders (e.g. a mapper shared by two windows).
   */
  void PushContext() override;
  void PopContext() override;
  ///@}

protected:
  vtkMRGIOSMesaRenderWindow();
  ~vtkMRGIOSMesaRenderWindow() override;

  void DestroyContext();

  ///@{
  /** Pixel reads fail cleanly, instead of calling unloaded GL, without a context. */
  int ReadPixels(
    const vtkRecti& rect, int front, int glFormat, int glType, void* data, int right) override;
  int GetZbufferData(int x1, int y1, int x2, int y2, float* z) override;
  ///@}
  bool CheckContextForRead();

  struct OSMesaState;
  std::unique_ptr<OSMesaState> OSMesa;
  std::string PlatformDescription;
  std::string LastErrorMessage;
  int ContextVersion = 0;

private:
  vtkMRGIOSMesaRenderWindow(const vtkMRGIOSMesaRenderWindow&) = delete;
  void operator=(const vtkMRGIOSMesaRenderWindow&) = delete;
};

#endif
