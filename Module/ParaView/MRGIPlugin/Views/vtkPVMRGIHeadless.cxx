#include "vtkPVMRGIHeadless.h"

#include "vtkLogger.h"
#include "vtkMRGIRenderWindowFactory.h"
#include "vtkMRGIEGLRenderWindow.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkMultiProcessController.h"
#include "vtkPVProcessWindow.h"
#include "vtkRemotingCoreConfiguration.h"
#include "vtkRenderWindow.h"
#include "vtkVersion.h"

#include <string>

namespace
{
// The backend chosen at load time; "x" until the plugin says otherwise.
std::string ChosenBackend = "x";

vtkObject* NewHeadlessRenderWindow()
{
  std::string why;
  vtkRenderWindow* window =
    vtkMRGIRenderWindowFactory::CreateRenderWindow(vtkMRGIRenderWindowFactory::Headless, &why);
  if (!window)
  {
    // ParaView aborts on a null window; say why first.
    vtkLogF(ERROR, "MRGI plugin: no headless render window: %s", why.c_str());
    return nullptr;
  }
  // ParaView's process window is never sized: it only holds the context
  // its views share (they draw into their own framebuffers), and MRGI's
  // windows refuse to render at 0 x 0.
  window->SetSize(1, 1);
  return window;
}

/**
 * Overrides vtkRenderWindow with MRGI's headless windows. Registered once,
 * by vtkPVMRGIInitializePlugin(), only where X cannot be had.
 */
class vtkPVMRGIHeadlessFactory : public vtkObjectFactory
{
public:
  static vtkPVMRGIHeadlessFactory* New()
  {
    auto* factory = new vtkPVMRGIHeadlessFactory;
    factory->InitializeObjectBase();
    return factory;
  }
  vtkTypeMacro(vtkPVMRGIHeadlessFactory, vtkObjectFactory);
  const char* GetVTKSourceVersion() override { return VTK_SOURCE_VERSION; }
  const char* GetDescription() override
  {
    return "MRGI: headless render windows (EGL, OSMesa) for ParaView without X";
  }

protected:
  vtkPVMRGIHeadlessFactory()
  {
    this->RegisterOverride("vtkRenderWindow", "vtkMRGIEGLRenderWindow",
      "MRGI headless render window (EGL, else OSMesa)", 1, NewHeadlessRenderWindow);
  }

private:
  vtkPVMRGIHeadlessFactory(const vtkPVMRGIHeadlessFactory&) = delete;
  void operator=(const vtkPVMRGIHeadlessFactory&) = delete;
};
}

namespace
{
// vtkOpenGLRenderWindow::Initialized is protected; a pointer to it formed in
// a derived class may be used on any vtkOpenGLRenderWindow (standard C++).
struct InitializedFlag : vtkOpenGLRenderWindow
{
  static constexpr bool vtkOpenGLRenderWindow::*Member = &InitializedFlag::Initialized;
};
}

//------------------------------------------------------------------------------
void vtkPVMRGIPrepareHeadlessView(vtkOpenGLRenderWindow* window)
{
  if (!window || ChosenBackend == "x" || window->*InitializedFlag::Member)
  {
    return;
  }
  // ParaView's batch views draw with the process window's context; make
  // sure it exists, then make it current through the view's window.
  vtkPVProcessWindow::PrepareForRendering();
  window->MakeCurrent();
  std::string why;
  if (!vtkMRGIEGLRenderWindow::LoadOpenGLFunctions(&why))
  {
    vtkLogF(ERROR, "MRGI plugin: %s", why.c_str());
    return;
  }
  // The GL state (vtkOpenGLState) is the process window's, which its own
  // initialisation set up; OpenGLInitState() here would query the colour
  // sizes of a default framebuffer that a surfaceless context does not have.
  window->*InitializedFlag::Member = true;
}

//------------------------------------------------------------------------------
void vtkPVMRGIInitializePlugin()
{
  static bool initialized = false;
  if (initialized)
  {
    return;
  }
  initialized = true;
  // "x" when MRGI_BACKEND says x, or says nothing and a display opens.
  const std::string backend =
    vtkMRGIRenderWindowFactory::GetWindowKindName(vtkMRGIRenderWindowFactory::Automatic);
  if (backend == "x" || backend == "none")
  {
    return;
  }
  vtkNew<vtkPVMRGIHeadlessFactory> factory;
  vtkObjectFactory::RegisterFactory(factory);
  // VTK asks the factories in registration order and RenderingOpenGL2's
  // (registered first) maps vtkRenderWindow to the X window: switch that
  // one off, so that ours answers.
  vtkObjectFactory::SetAllEnableFlags(0, "vtkRenderWindow", "vtkXOpenGLRenderWindow");
  ChosenBackend = backend;
  vtkLogF(INFO, "MRGI plugin: no X display; ParaView's render windows are MRGI's %s windows",
    backend.c_str());
  // ParaView's own rendering-capability test knows only X: on several MPI
  // ranks without a display it decides that they cannot render, and the
  // ranks then wait on each other in IceT forever (measured with mpirun -np
  // 2 pvbatch). Its switch is a command-line option the plugin cannot set:
  // say so before the hang, not after.
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  vtkRemotingCoreConfiguration* config = vtkRemotingCoreConfiguration::GetInstance();
  if (controller && controller->GetNumberOfProcesses() > 1 && config &&
    !config->GetDisableXDisplayTests())
  {
    vtkLogF(ERROR,
      "MRGI plugin: %d MPI ranks and no X display: ParaView's rendering-capability test knows "
      "only X and will decide that these ranks cannot render, and the ranks would then wait on "
      "each other forever. Start pvbatch (or pvserver) with --disable-xdisplay-test: MRGI's %s "
      "window renders without X.",
      controller->GetNumberOfProcesses(), backend.c_str());
  }
}

//------------------------------------------------------------------------------
const char* vtkPVMRGIHeadlessBackend()
{
  return ChosenBackend.c_str();
}
