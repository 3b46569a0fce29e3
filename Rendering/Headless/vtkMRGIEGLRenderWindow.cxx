#include "vtk_glew.h" // first: GLEW must precede every other GL header

#include "vtkMRGIEGLRenderWindow.h"

#include "vtkMRGIHeadlessDepth.h"

#include "vtkMRGIOSMesaRenderWindow.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLState.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <cstring>
#include <sstream>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkMRGIEGLRenderWindow);

struct vtkMRGIEGLRenderWindow::EGLState
{
  EGLDisplay Display = EGL_NO_DISPLAY;
  EGLContext Context = EGL_NO_CONTEXT;
  // What PushContext() found current, for PopContext() to restore.
  std::vector<std::pair<EGLDisplay, EGLContext>> ContextStack;
};

namespace
{
// Whole-token search in a space-separated EGL extension string.
bool HasExtension(const char* list, const char* name)
{
  if (!list || !name)
  {
    return false;
  }
  const size_t len = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + 1, name))
  {
    const bool startOk = (p == list) || p[-1] == ' ';
    const bool endOk = p[len] == '\0' || p[len] == ' ';
    if (startOk && endOk)
    {
      return true;
    }
  }
  return false;
}

// Initialize `display` and make an OpenGL 3.2 core context current on it
// without a surface. Leaves `out` untouched and explains in `why` on failure.
bool CreateSurfacelessContext(EGLDisplay display, EGLDisplay& outDisplay,
  EGLContext& outContext, std::string& why)
{
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor))
  {
    why = "eglInitialize failed";
    return false;
  }
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  if (!HasExtension(extensions, "EGL_KHR_surfaceless_context"))
  {
    why = "the EGL display lacks EGL_KHR_surfaceless_context";
    return false;
  }
  if (!eglBindAPI(EGL_OPENGL_API))
  {
    why = "the EGL display does not offer desktop OpenGL";
    return false;
  }
  // eglChooseConfig defaults EGL_SURFACE_TYPE to windows, which surfaceless
  // and device displays lack: ask for pbuffer-capable configs instead.
  const EGLint configAttributes[] = { EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
    EGL_OPENGL_BIT, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_NONE };
  EGLConfig config = nullptr;
  EGLint configCount = 0;
  if (!eglChooseConfig(display, configAttributes, &config, 1, &configCount) || configCount < 1)
  {
    why = "no EGL config renders desktop OpenGL";
    return false;
  }
  // VTK needs OpenGL 3.2 core; drivers return the newest compatible version.
  const EGLint contextAttributes[] = { EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 2,
    EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE };
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
  if (context == EGL_NO_CONTEXT)
  {
    why = "eglCreateContext could not make an OpenGL 3.2 core context";
    return false;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
  {
    eglDestroyContext(display, context);
    why = "eglMakeCurrent failed for a surfaceless context";
    return false;
  }
  outDisplay = display;
  outContext = context;
  return true;
}
}

//------------------------------------------------------------------------------
vtkMRGIEGLRenderWindow::vtkMRGIEGLRenderWindow()
  : EGL(new EGLState)
{
  // No default framebuffer exists on a surfaceless context: render into VTK's
  // own framebuffers, never blit to framebuffer 0.
  this->ShowWindow = false;
  this->UseOffScreenBuffers = true;
  this->SetReadyForRendering(true);
  this->SetIsDirect(1);
  this->SetSupportsOpenGL(1);
  this->SetWindowName("MRGI headless (EGL)");
}

//------------------------------------------------------------------------------
vtkMRGIEGLRenderWindow::~vtkMRGIEGLRenderWindow()
{
  this->Finalize();
}

//------------------------------------------------------------------------------
bool vtkMRGIEGLRenderWindow::InitializeHeadlessContext()
{
  if (this->EGL->Context != EGL_NO_CONTEXT)
  {
    return true;
  }
  this->LastErrorMessage.clear();
  vtkMRGIOSMesaRenderWindow::ReleaseCurrentOSMesaContext(); // see MakeCurrent()

  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
    eglGetProcAddress("eglGetPlatformDisplayEXT"));
  auto queryDevices =
    reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto queryDeviceString =
    reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));

  const char* request = std::getenv("MRGI_EGL_DEVICE");
  const bool wantSurfaceless = request && std::strcmp(request, "surfaceless") == 0;
  int wantedDevice = -1;
  if (request && !wantSurfaceless)
  {
    char* end = nullptr;
    long v = std::strtol(request, &end, 10);
    if (end == request || *end != '\0' || v < 0 || v > 64)
    {
      this->LastErrorMessage = std::string("MRGI_EGL_DEVICE='") + request +
        "' is neither a device index (0..64) nor 'surfaceless'";
      return false;
    }
    wantedDevice = static_cast<int>(v);
  }

  std::ostringstream tried;
  std::string why;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;

  // 1. Hardware EGL devices (NVIDIA's EGL device, Mesa's DRM devices).
  if (!wantSurfaceless && getPlatformDisplay && queryDevices &&
    HasExtension(clientExtensions, "EGL_EXT_platform_device"))
  {
    EGLint count = 0;
    queryDevices(0, nullptr, &count);
    std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count > 0 ? count : 0));
    if (count > 0 && queryDevices(count, devices.data(), &count))
    {
      for (EGLint i = 0; i < count && context == EGL_NO_CONTEXT; ++i)
      {
        if (wantedDevice >= 0 && i != wantedDevice)
        {
          continue;
        }
        const char* devExt =
          queryDeviceString ? queryDeviceString(devices[i], EGL_EXTENSIONS) : nullptr;
        // Mesa lists llvmpipe as a "software device"; prefer real GPUs and
        // reach llvmpipe through the surfaceless platform below.
        if (wantedDevice < 0 && HasExtension(devExt, "EGL_MESA_device_software"))
        {
          continue;
        }
        EGLDisplay candidate = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (CreateSurfacelessContext(candidate, display, context, why))
        {
          std::ostringstream desc;
          desc << "EGL device " << i;
          this->PlatformDescription = desc.str();
        }
        else
        {
          tried << "device " << i << ": " << why << "; ";
        }
      }
    }
  }

  // 2. Mesa's surfaceless platform (llvmpipe without a GPU).
  if (context == EGL_NO_CONTEXT && wantedDevice < 0 && getPlatformDisplay &&
    HasExtension(clientExtensions, "EGL_MESA_platform_surfaceless"))
  {
    EGLDisplay candidate =
      getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (CreateSurfacelessContext(candidate, display, context, why))
    {
      this->PlatformDescription = "EGL surfaceless (Mesa)";
    }
    else
    {
      tried << "surfaceless: " << why << "; ";
    }
  }

  if (context == EGL_NO_CONTEXT)
  {
    this->LastErrorMessage = "no headless OpenGL 3.2 context could be created (" +
      (tried.str().empty() ? std::string("no EGL device or surfaceless platform found") : tried.str()) +
      ")";
    return false;
  }

  this->EGL->Display = display;
  this->EGL->Context = context;
  this->SetIsCurrent(true);
  this->OpenGLInit();
  if (!this->Initialized)
  {
    this->LastErrorMessage = "OpenGL initialization failed on the EGL context";
    this->DestroyContext();
    return false;
  }
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (renderer)
  {
    this->PlatformDescription += std::string(", ") + renderer;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIEGLRenderWindow::IsHeadlessRenderingAvailable()
{
  vtkMRGIEGLRenderWindow* probe = vtkMRGIEGLRenderWindow::New();
  const bool ok = probe->InitializeHeadlessContext();
  probe->Delete();
  return ok;
}

//------------------------------------------------------------------------------
bool vtkMRGIEGLRenderWindow::LoadOpenGLFunctions(std::string* why)
{
  const GLenum result = glewInit();
  if (result != GLEW_OK && result != GLEW_ERROR_NO_GLX_DISPLAY)
  {
    if (why)
    {
      *why = std::string("GLEW could not be initialized on the EGL context: ") +
        reinterpret_cast<const char*>(glewGetErrorString(result));
    }
    return false;
  }
  if (!GLEW_VERSION_3_2)
  {
    if (why)
    {
      *why = "The EGL context does not provide OpenGL 3.2 core, which VTK requires.";
    }
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIEGLRenderWindow::OpenGLInitContext()
{
  // Mirrors vtkOpenGLRenderWindow::OpenGLInitContext (VTK 9.1/9.2) except for
  // the one glewInit() result it must accept: see the class documentation.
  this->ContextCreationTime.Modified();
  if (this->Initialized)
  {
    return;
  }
  std::string why;
  if (!LoadOpenGLFunctions(&why))
  {
    vtkErrorMacro(<< why);
    return;
  }
  this->Initialized = true;
  GLfloat lineWidthRange[2] = { 1.0f, 1.0f };
  glGetFloatv(this->LineSmoothing ? GL_SMOOTH_LINE_WIDTH_RANGE : GL_ALIASED_LINE_WIDTH_RANGE,
    lineWidthRange);
  this->MaximumHardwareLineWidth = (glGetError() == GL_NO_ERROR) ? lineWidthRange[1] : 1.0f;
}

//------------------------------------------------------------------------------
void vtkMRGIEGLRenderWindow::Initialize()
{
  if (!this->InitializeHeadlessContext())
  {
    vtkErrorMacro(<< this->LastErrorMessage);
  }
}

//------------------------------------------------------------------------------
void vtkMRGIEGLRenderWindow::Start()
{
  if (this->EGL->Context == EGL_NO_CONTEXT)
  {
    this->Initialize();
  }
  this->Superclass::Start();
}

//------------------------------------------------------------------------------
void vtkMRGIEGLRenderWindow::Render()
{
  if (this->Size[0] < 1 || this->Size[1] < 1)
  {
    vtkErrorMacro("cannot render a " << this->Size[0] << "x" << this->Size[1]
                                     << " window: width and height must be at least 1");
    return;
  }
  if (this->EGL->Context == EGL_NO_CONTEXT && !this->InitializeHeadlessContext())
  {
    vtkErrorMacro(<< this->LastErrorMessage);
    return;
  }
  // VTK 9.2 code outside Render() (seen while a scene is being set up) can
  // leave GL_INVALID_OPERATION behind on a context without a default
  // framebuffer; vtkGenericOpenGLRenderWindow::Render would report it as an
  // error of the frame. Clear such stale errors; the frame checks its own.
  this->MakeCurrent();
  int stale = 0;
  while (glGetError() != GL_NO_ERROR && stale < 16)
  {
    ++stale;
  }
  if (stale > 0)
  {
    vtkDebugMacro(<< stale << " stale OpenGL error(s) cleared before rendering");
  }
  this->Superclass::Render();
}

//------------------------------------------------------------------------------
void vtkMRGIEGLRenderWindow::Frame()
{
  // vtkGenericOpenGLRenderWindow::Frame resolves the render framebuffer into
  // the display framebuffer; with UseOffScreenBuffers it does not touch
  // framebuffer 0, which does not exist here.
  this->Superclass::Frame();
}

//------------------------------------------------------------------------------
void vtkMRGIEGLRenderWindow::MakeCurrent()
{
  if (this->EGL->Context != EGL_NO_CONTEXT && eglGetCurrentContext() != this->EGL->Context)
  {
    // libglvnd refuses eglMakeCurrent while an OSMesa window's context is
    // current on this thread (a no-op when libOSMesa was never loaded).
    vtkMRGIOSMesaRenderWindow::ReleaseCurrentOSMesaContext();
    eglMakeCurrent(this->EGL->Display, EGL_NO_SURFACE, EGL_NO_SURFACE, this->EGL->Context);
  }
}

//------------------------------------------------------------------------------
void vtkMRGIEGLRenderWindow::PushContext()
{
  // VTK frees a resource of this window from inside another window's render
  // (a mapper shared by two windows, a texture moved between them): it
  // pushes this context, frees, and pops. The base class's PopContext() does
  // nothing, which would leave this context current under the other
  // window's draw calls.
  this->EGL->ContextStack.emplace_back(eglGetCurrentDisplay(), eglGetCurrentContext());
  this->MakeCurrent();
}

//------------------------------------------------------------------------------
void vtkMRGIEGLRenderWindow::PopContext()
{
  if (this->EGL->ContextStack.empty())
  {
    return;
  }
  const std::pair<EGLDisplay, EGLContext> previous = this->EGL->ContextStack.back();
  this->EGL->ContextStack.pop_back();
  if (previous.second == eglGetCurrentContext())
  {
    return;
  }
  if (previous.second == EGL_NO_CONTEXT)
  {
    this->ReleaseCurrent();
  }
  else
  {
    eglMakeCurrent(previous.first, EGL_NO_SURFACE, EGL_NO_SURFACE, previous.second);
  }
}

//------------------------------------------------------------------------------
void vtkMRGIEGLRenderWindow::ReleaseCurrent()
{
  if (this->EGL->Context != EGL_NO_CONTEXT && eglGetCurrentContext() == this->EGL->Context)
  {
    eglMakeCurrent(this->EGL->Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIEGLRenderWindow::IsCurrent()
{
  return this->EGL->Context != EGL_NO_CONTEXT && eglGetCurrentContext() == this->EGL->Context;
}

//------------------------------------------------------------------------------
int vtkMRGIEGLRenderWindow::SupportsOpenGL()
{
  return (this->EGL->Context != EGL_NO_CONTEXT || this->InitializeHeadlessContext()) ? 1 : 0;
}

//------------------------------------------------------------------------------
void* vtkMRGIEGLRenderWindow::GetGenericContext()
{
  return this->EGL->Context;
}

//------------------------------------------------------------------------------
void* vtkMRGIEGLRenderWindow::GetGenericDisplayId()
{
  return this->EGL->Display;
}

//------------------------------------------------------------------------------
int vtkMRGIEGLRenderWindow::GetDepthBufferSize()
{
  return vtkMRGIHeadlessDepth::RenderFramebufferDepthBits(this, this->Initialized);
}

//------------------------------------------------------------------------------
int vtkMRGIEGLRenderWindow::GetColorBufferSizes(int* rgba)
{
  // VTK 9.2 asks framebuffer 0 for its bit depths, which a surfaceless context
  // does not have (GL_INVALID_OPERATION). VTK renders into its own RGBA8
  // framebuffers here, so those are the sizes that matter.
  if (!rgba)
  {
    return 0;
  }
  rgba[0] = rgba[1] = rgba[2] = rgba[3] = 8;
  return 32;
}

//------------------------------------------------------------------------------
void vtkMRGIEGLRenderWindow::Finalize()
{
  if (this->EGL && this->EGL->Context != EGL_NO_CONTEXT)
  {
    this->MakeCurrent();
    this->ReleaseGraphicsResources(this);
    this->DestroyContext();
  }
}

//------------------------------------------------------------------------------
void vtkMRGIEGLRenderWindow::DestroyContext()
{
  if (this->EGL->Context == EGL_NO_CONTEXT)
  {
    return;
  }
  this->ReleaseCurrent();
  eglDestroyContext(this->EGL->Display, this->EGL->Context);
  // The display is deliberately not terminated: EGL displays are shared per
  // device within a process, and eglTerminate would invalidate the contexts of
  // every other window on it.
  this->EGL->Context = EGL_NO_CONTEXT;
  this->EGL->Display = EGL_NO_DISPLAY;
  this->Initialized = false;
  this->SetIsCurrent(false);
}

//------------------------------------------------------------------------------
bool vtkMRGIEGLRenderWindow::CheckContextForRead()
{
  if (this->EGL->Context == EGL_NO_CONTEXT || !this->Initialized)
  {
    vtkErrorMacro("cannot read pixels: the window has no OpenGL context"
      << (this->LastErrorMessage.empty() ? std::string(" (it was never rendered)")
                                         : " (" + this->LastErrorMessage + ")"));
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkMRGIEGLRenderWindow::ReadPixels(
  const vtkRecti& rect, int front, int glFormat, int glType, void* data, int right)
{
  if (!this->CheckContextForRead())
  {
    return VTK_ERROR;
  }
  return this->Superclass::ReadPixels(rect, front, glFormat, glType, data, right);
}

//------------------------------------------------------------------------------
int vtkMRGIEGLRenderWindow::GetZbufferData(int x1, int y1, int x2, int y2, float* z)
{
  if (!this->CheckContextForRead())
  {
    return VTK_ERROR;
  }
  return this->Superclass::GetZbufferData(x1, y1, x2, y2, z);
}

//------------------------------------------------------------------------------
void vtkMRGIEGLRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PlatformDescription: "
     << (this->PlatformDescription.empty() ? "(none)" : this->PlatformDescription) << "\n";
  os << indent << "LastErrorMessage: "
     << (this->LastErrorMessage.empty() ? "(none)" : this->LastErrorMessage) << "\n";
}
