#include "vtkMRGIRenderWindowFactory.h"

#include "vtkMRGIEGLRenderWindow.h"
#include "vtkMRGIOSMesaRenderWindow.h"
#include "vtkObjectFactory.h"
#include "vtkRenderWindow.h"

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>

vtkStandardNewMacro(vtkMRGIRenderWindowFactory);

namespace
{
enum class Choice
{
  X,
  EGL,
  OSMesa,
  HeadlessAuto, // EGL, else OSMesa
  None
};

// Whether an X display opens. libX11 is already loaded with VTK's X window;
// looked up at run time so that this module does not link it.
bool XDisplayWorks()
{
  void* x11 = dlopen("libX11.so.6", RTLD_NOW | RTLD_LOCAL);
  if (!x11)
  {
    return false;
  }
  using OpenDisplay = void* (*)(const char*);
  using CloseDisplay = int (*)(void*);
  auto openDisplay = reinterpret_cast<OpenDisplay>(dlsym(x11, "XOpenDisplay"));
  auto closeDisplay = reinterpret_cast<CloseDisplay>(dlsym(x11, "XCloseDisplay"));
  bool works = false;
  if (openDisplay && closeDisplay)
  {
    if (void* display = openDisplay(nullptr))
    {
      closeDisplay(display);
      works = true;
    }
  }
  dlclose(x11);
  return works;
}

// The backend to use for `kind`: from `backend`, else MRGI_BACKEND, else
// MRGI_WINDOW, else automatic. `source` names where a named backend came from.
Choice Choose(int kind, const char* backend, std::string& why)
{
  std::string source = "backend";
  const char* name = backend;
  if (!name || !name[0])
  {
    name = std::getenv("MRGI_BACKEND");
    source = "MRGI_BACKEND";
  }
  if (!name || !name[0])
  {
    name = std::getenv("MRGI_WINDOW");
    source = "MRGI_WINDOW";
  }
  const char* display = std::getenv("DISPLAY");
  const bool haveDisplay = display && display[0];
  if (name && name[0] && std::strcmp(name, "auto") != 0)
  {
    if (std::strcmp(name, "x") == 0)
    {
      if (!haveDisplay)
      {
        why = source + "=x, but DISPLAY is not set: the X backend needs an X display";
        return Choice::None;
      }
      if (!XDisplayWorks())
      {
        why = source + "=x, but the X display '" + display + "' cannot be opened";
        return Choice::None;
      }
      return Choice::X;
    }
    if (std::strcmp(name, "egl") == 0)
    {
      return Choice::EGL;
    }
    if (std::strcmp(name, "osmesa") == 0)
    {
      return Choice::OSMesa;
    }
    why = source + "='" + name + "' is not one of auto, egl, osmesa, x";
    return Choice::None;
  }
  if (kind == vtkMRGIRenderWindowFactory::Interactive)
  {
    if (!haveDisplay)
    {
      why = "an interactive window needs an X display, and DISPLAY is not set";
      return Choice::None;
    }
    return Choice::X;
  }
  if (kind == vtkMRGIRenderWindowFactory::Automatic && haveDisplay && XDisplayWorks())
  {
    return Choice::X;
  }
  return Choice::HeadlessAuto;
}

vtkRenderWindow* MakeEGL(std::string& why)
{
  vtkMRGIEGLRenderWindow* egl = vtkMRGIEGLRenderWindow::New();
  if (!egl->InitializeHeadlessContext())
  {
    why = std::string("EGL: ") + egl->GetLastErrorMessage();
    egl->Delete();
    return nullptr;
  }
  return egl;
}

vtkRenderWindow* MakeOSMesa(std::string& why)
{
  vtkMRGIOSMesaRenderWindow* osmesa = vtkMRGIOSMesaRenderWindow::New();
  if (!osmesa->InitializeHeadlessContext())
  {
    why = std::string("OSMesa: ") + osmesa->GetLastErrorMessage();
    osmesa->Delete();
    return nullptr;
  }
  return osmesa;
}
}

//------------------------------------------------------------------------------
vtkRenderWindow* vtkMRGIRenderWindowFactory::CreateRenderWindow(int kind, std::string* why)
{
  return CreateRenderWindow(kind, nullptr, why);
}

//------------------------------------------------------------------------------
vtkRenderWindow* vtkMRGIRenderWindowFactory::CreateRenderWindow(
  int kind, const char* backend, std::string* why)
{
  std::string reason;
  vtkRenderWindow* window = nullptr;
  switch (Choose(kind, backend, reason))
  {
    case Choice::X:
      window = vtkRenderWindow::New();
      break;
    case Choice::EGL:
      window = MakeEGL(reason);
      break;
    case Choice::OSMesa:
      window = MakeOSMesa(reason);
      break;
    case Choice::HeadlessAuto:
    {
      // Not asked for by name: OSMesa stands in when EGL has no context.
      std::string eglWhy;
      window = MakeEGL(eglWhy);
      if (!window)
      {
        std::string osmesaWhy;
        window = MakeOSMesa(osmesaWhy);
        reason = eglWhy + "; " + osmesaWhy;
      }
      break;
    }
    case Choice::None:
      break;
  }
  if (!window && why)
  {
    *why = reason;
  }
  return window;
}

//------------------------------------------------------------------------------
vtkRenderWindow* vtkMRGIRenderWindowFactory::NewRenderWindow(int kind)
{
  return NewRenderWindow(kind, nullptr);
}

//------------------------------------------------------------------------------
vtkRenderWindow* vtkMRGIRenderWindowFactory::NewRenderWindow(int kind, const char* backend)
{
  std::string why;
  vtkRenderWindow* window = CreateRenderWindow(kind, backend, &why);
  if (!window)
  {
    vtkGenericWarningMacro("no " << GetWindowKindName(kind) << " render window: " << why);
  }
  return window;
}

//------------------------------------------------------------------------------
vtkRenderWindow* vtkMRGIRenderWindowFactory::CreateHeadlessRenderWindow()
{
  return NewRenderWindow(Headless);
}

//------------------------------------------------------------------------------
const char* vtkMRGIRenderWindowFactory::GetWindowKindName(int kind)
{
  std::string why;
  switch (Choose(kind, nullptr, why))
  {
    case Choice::X:
      return "x";
    case Choice::EGL:
    case Choice::HeadlessAuto:
      return "egl";
    case Choice::OSMesa:
      return "osmesa";
    case Choice::None:
      break;
  }
  return "none";
}

//------------------------------------------------------------------------------
const char* vtkMRGIRenderWindowFactory::GetBackendName(vtkRenderWindow* window)
{
  if (!window)
  {
    return "none";
  }
  if (vtkMRGIEGLRenderWindow::SafeDownCast(window))
  {
    return "egl";
  }
  if (vtkMRGIOSMesaRenderWindow::SafeDownCast(window))
  {
    return "osmesa";
  }
  return "x";
}

//------------------------------------------------------------------------------
std::string vtkMRGIRenderWindowFactory::DescribeRenderWindow(vtkRenderWindow* window)
{
  std::string line = GetBackendName(window);
  const char* platform = nullptr;
  if (auto* egl = vtkMRGIEGLRenderWindow::SafeDownCast(window))
  {
    platform = egl->GetPlatformDescription();
  }
  else if (auto* osmesa = vtkMRGIOSMesaRenderWindow::SafeDownCast(window))
  {
    platform = osmesa->GetPlatformDescription();
  }
  else if (window)
  {
    platform = window->GetClassName();
  }
  if (platform && platform[0])
  {
    line += std::string(" (") + platform + ")";
  }
  return line;
}

//------------------------------------------------------------------------------
void vtkMRGIRenderWindowFactory::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Headless window kind: " << GetWindowKindName(Headless) << "\n";
}
