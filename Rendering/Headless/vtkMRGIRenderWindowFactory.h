/**
 * @class   vtkMRGIRenderWindowFactory
 * @brief   Makes the render window that works where the program runs.
 *
 * - Interactive, with DISPLAY set: VTK's own window (an X window here).
 * - Otherwise, when VTK was built with OSMesa: VTK's OSMesa window.
 * - Otherwise: vtkMRGIEGLRenderWindow (EGL device or Mesa surfaceless),
 *   which needs neither X nor a GPU.
 *
 * The environment variable MRGI_WINDOW (x, osmesa, egl) forces a kind.
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
   * interactive window without DISPLAY, or no EGL context.
   */
  static vtkRenderWindow* CreateRenderWindow(int kind, std::string* why = nullptr);

  /** Python-friendly forms: a window of `kind` (or a headless one), or nullptr with a warning. */
  VTK_NEWINSTANCE static vtkRenderWindow* NewRenderWindow(int kind);
  VTK_NEWINSTANCE static vtkRenderWindow* CreateHeadlessRenderWindow();

  /** The name of the window kind CreateRenderWindow(kind) would pick. */
  static const char* GetWindowKindName(int kind);

protected:
  vtkMRGIRenderWindowFactory() = default;
  ~vtkMRGIRenderWindowFactory() override = default;

private:
  vtkMRGIRenderWindowFactory(const vtkMRGIRenderWindowFactory&) = delete;
  void operator=(const vtkMRGIRenderWindowFactory&) = delete;
};

#endif
