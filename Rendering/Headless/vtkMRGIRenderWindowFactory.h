/**
 * @class   vtkMRGIRenderWindowFactory
 * @brief   Makes the render window that works where the program runs.
 *
 * A window is made on one of three backends:
 *
 * - `x`: VTK's own window (an X window here); needs DISPLAY.
 * - `egl`: vtkMRGIEGLRenderWindow (EGL device or Mesa surfaceless).
 * - `osmesa`: vtkMRGIOSMesaRenderWindow (Mesa's OSMesa, loaded on demand).
 *
 * The backend comes from, in this order: the `backend` argument, the
 * environment variable `MRGI_BACKEND`, the older `MRGI_WINDOW`; `auto` (or
 * none of them) lets the kind decide:
 *
 * - Interactive: X (an error without DISPLAY);
 * - Automatic: X when DISPLAY is set and the display opens, else as Headless;
 * - Headless: EGL, else OSMesa when no EGL context can be made.
 *
 * A backend that was asked for by name and cannot be had is an error, with
 * the reason; it never falls back to another one. An unknown name is an
 * error too.
 */
#ifndef vtkMRGIRenderWindowFactory_h
#define vtkMRGIRenderWindowFactory_h

#include "MRGIRenderingHeadlessModule.h" // For export macro
#include "vtkObject.h"
#include "vtkWrappingHints.h" // For VTK_NEWINSTANCE

#include <string> // For std::string

class vtkRenderWindow;

class MRGIRENDERINGHEADLESS_EXPORT vtkMRGIRenderWindowFactory : public vtkObject
{
public:
  static vtkMRGIRenderWindowFactory* New();
  vtkTypeMacro(vtkMRGIRenderWindowFactory, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum WindowKind
  {
    Automatic = 0,
    Headless = 1,
    Interactive = 2
  };

  /**
   * A new render window of the kind asked for (the caller owns the reference),
   * or nullptr with the reason in `why` when none can be made: e.g. an
   * interactive window without DISPLAY, an unknown MRGI_BACKEND, or a backend
   * asked for that cannot make a context. The backend comes from the
   * environment (see the class documentation).
   */
  static vtkRenderWindow* CreateRenderWindow(int kind, std::string* why = nullptr);

  /**
   * The same, on the backend named by `backend` ("x", "egl", "osmesa", or
   * "auto"); nullptr or "" means: from the environment.
   */
  static vtkRenderWindow* CreateRenderWindow(int kind, const char* backend, std::string* why);

  /** Python-friendly forms: a window of `kind` (or a headless one), or nullptr with a warning. */
  VTK_NEWINSTANCE static vtkRenderWindow* NewRenderWindow(int kind);
  VTK_NEWINSTANCE static vtkRenderWindow* NewRenderWindow(int kind, const char* backend);
  VTK_NEWINSTANCE static vtkRenderWindow* CreateHeadlessRenderWindow();

  /**
   * The name of the backend CreateRenderWindow(kind) tries first ("x", "egl",
   * "osmesa"), or "none" when the request is an error.
   */
  static const char* GetWindowKindName(int kind);

  /** The backend of a window this factory made: "x", "egl", "osmesa"; "none" for nullptr. */
  static const char* GetBackendName(vtkRenderWindow* window);

  /**
   * One line for logs: the backend, and for the headless windows the platform
   * and GL renderer, e.g. "egl (EGL surfaceless (Mesa), llvmpipe (...))".
   */
  static std::string DescribeRenderWindow(vtkRenderWindow* window);

protected:
  vtkMRGIRenderWindowFactory() = default;
  ~vtkMRGIRenderWindowFactory() override = default;

private:
  vtkMRGIRenderWindowFactory(const vtkMRGIRenderWindowFactory&) = delete;
  void operator=(const vtkMRGIRenderWindowFactory&) = delete;
};

#endif
