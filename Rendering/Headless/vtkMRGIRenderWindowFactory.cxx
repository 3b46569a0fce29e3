#include "vtkMRGIRenderWindowFactory.h"

#include "vtkMRGIEGLRenderWindow.h"
#include "vtkObjectFactory.h"
#include "vtkRenderWindow.h"
#include "vtkRenderingOpenGLConfigure.h" // VTK_OPENGL_HAS_OSMESA

#ifdef VTK_OPENGL_HAS_OSMESA
#include "vtkOSOpenGLRenderWindow.h"
#endif

#include <cstdlib>
#include <cstring>

vtkStandardNewMacro(vtkMRGIRenderWindowFactory);

namespace
{
enum class Choice
{
  X,
  OSMesa,
  EGL,
  None
};

Choice Choose(int kind, std::string& why)
{
  const char* forced = std::getenv("MRGI_WINDOW");
  const char* display = std::getenv("DISPLAY");
  const bool haveDisplay = display && display[0];
  if (forced && forced[0])
  {
    if (std::strcmp(forced, "x") == 0)
    {
      return Choice::X;
    }
    if (std::strcmp(forced, "egl") == 0)
    {
      return Choice::EGL;
    }
    if (std::strcmp(forced, "osmesa") == 0)
    {
#ifdef VTK_OPENGL_HAS_OSMESA
      return Choice::OSMesa;
#else
      why = "MRGI_WINDOW=osmesa, but this VTK was built without OSMesa";
      return Choice::None;
#endif
    }
    why = std::string("MRGI_WINDOW='") + forced + "' is not one of x, osmesa, egl";
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
#ifdef VTK_OPENGL_HAS_OSMESA
  return Choice::OSMesa;
#else
  return Choice::EGL;
#endif
}
}

//------------------------------------------------------------------------------
vtkRenderWindow* vtkMRGIRenderWindowFactory::CreateRenderWindow(int kind, std::string* why)
{
  std::string reason;
  vtkRenderWindow* window = nullptr;
  switch (Choose(kind, reason))
  {
    case Choice::X:
      window = vtkRenderWindow::New();
      break;
    case Choice::OSMesa:
#ifdef VTK_OPENGL_HAS_OSMESA
      window = vtkOSOpenGLRenderWindow::New();
#endif
      break;
    case Choice::EGL:
    {
      vtkMRGIEGLRenderWindow* egl = vtkMRGIEGLRenderWindow::New();
      if (!egl->InitializeHeadlessContext())
      {
        reason = egl->GetLastErrorMessage();
        egl->Delete();
      }
      else
      {
        window = egl;
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
  std::string why;
  vtkRenderWindow* window = CreateRenderWindow(kind, &why);
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
  switch (Choose(kind, why))
  {
    case Choice::X:
      return "x";
    case Choice::OSMesa:
      return "osmesa";
    case Choice::EGL:
      return "egl";
    case Choice::None:
      break;
  }
  return "none";
}

//------------------------------------------------------------------------------
void vtkMRGIRenderWindowFactory::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Headless window kind: " << GetWindowKindName(Headless) << "\n";
}
