/**
 * @class   vtkMRGIEGLRenderWindow
 * @brief   Headless OpenGL render window on an EGL context the window makes itself.
 *
 * Debian's VTK 9.1 and ParaView 5.11's VTK 9.2 are built for GLX only: neither
 * has vtkEGLRenderWindow, and vtkOSOpenGLRenderWindow is absent too. This
 * window makes its own EGL context and renders without any X server:
 *
 * - on a machine with a GPU it takes the first hardware EGL device
 *   (EGL_EXT_platform_device, e.g. the NVIDIA EGL device);
 * - otherwise it takes Mesa's surfaceless platform (EGL_MESA_platform_surfaceless),
 *   which is llvmpipe on a machine without a GPU.
 *
 * The environment variable `MRGI_EGL_DEVICE` (an index into the EGL device
 * list, or `surfaceless`) overrides the choice.
 *
 * The context is surfaceless: there is no default framebuffer, so the window
 * always renders into VTK's own offscreen framebuffers (OffScreenRendering is
 * forced on) and nothing is ever blitted to framebuffer 0. Pixels are read back
 * with the usual GetPixelData / GetRGBAPixelData / vtkWindowToImageFilter.
 *
 * GLEW in these VTK builds is the GLX flavour: glewInit() loads every core GL
 * entry point and then fails its GLX-only check with GLEW_ERROR_NO_GLX_DISPLAY.
 * OpenGLInitContext() accepts that result (and only that one) when an EGL
 * context is current.
 *
 * @sa vtkMRGIRenderWindowFactory, which picks this window, an X window or
 * VTK's OSMesa window as the build and environment allow.
 */
#ifndef vtkMRGIEGLRenderWindow_h
#define vtkMRGIEGLRenderWindow_h

#include "MRGIRenderingHeadlessModule.h" // For export macro
#include "vtkGenericOpenGLRenderWindow.h"

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class MRGIRENDERINGHEADLESS_EXPORT vtkMRGIEGLRenderWindow : public vtkGenericOpenGLRenderWindow
{
public:
  static vtkMRGIEGLRenderWindow* New();
  vtkTypeMacro(vtkMRGIEGLRenderWindow, vtkGenericOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Create the EGL display and context now (Render() does it on demand).
   * Returns false, with the reason in GetLastErrorMessage(), when no EGL
   * display or OpenGL 3.2 core context can be had.
   */
  bool InitializeHeadlessContext();

  /**
   * Whether an EGL OpenGL 3.2+ context can be created on this machine.
   * Creates and destroys a context; cheap enough for start-up checks.
   */
  static bool IsHeadlessRenderingAvailable();

  /**
   * Loads the OpenGL functions (glewInit) for the context current now,
   * accepting the one GLEW result that an EGL or OSMesa context gives
   * (no GLX display), and checks for OpenGL 3.2. For windows that draw with
   * this window's context without being one (ParaView's views in pvbatch
   * share their process window's context). False with the reason in `why`.
   */
#ifndef __VTK_WRAP__
  static bool LoadOpenGLFunctions(std::string* why);
#endif

  /** What EGL gave us: "device N (...)" or "surfaceless", empty before init. */
  const char* GetPlatformDescription() { return this->PlatformDescription.c_str(); }

  /** Why the last attempt to create a context failed; empty when it did not. */
  const char* GetLastErrorMessage() { return this->LastErrorMessage.c_str(); }

  ///@{
  /** vtkRenderWindow / vtkOpenGLRenderWindow API backed by EGL. */
  void Initialize() override;
  void Finalize() override;
  void Start() override;
  void Render() override;
  void Frame() override;
  void MakeCurrent() override;
  void ReleaseCurrent() override;
  bool IsCurrent() override;

  ///@{
  /**
   * Make this context current and restore the previous one afterwards, as
   * VTK does when it frees a resource of this window while another window
   * renders (e.g. a mapper shared by two windows).
   */
  void PushContext() override;
  void PopContext() override;
  ///@}
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

protected:
  vtkMRGIEGLRenderWindow();
  ~vtkMRGIEGLRenderWindow() override;

  void DestroyContext();

  ///@{
  /** Pixel reads fail cleanly, instead of calling unloaded GL, without a context. */
  int ReadPixels(
    const vtkRecti& rect, int front, int glFormat, int glType, void* data, int right) override;
  int GetZbufferData(int x1, int y1, int x2, int y2, float* z) override;
  ///@}
  bool CheckContextForRead();

  struct EGLState;
  std::unique_ptr<EGLState> EGL;
  std::string PlatformDescription;
  std::string LastErrorMessage;

private:
  vtkMRGIEGLRenderWindow(const vtkMRGIEGLRenderWindow&) = delete;
  void operator=(const vtkMRGIEGLRenderWindow&) = delete;
};

#endif
