#include "vtk_glew.h" // first: GLEW must precede every other GL header

#include "vtkMRGIOSMesaRenderWindow.h"

#include "vtkMRGIHeadlessDepth.h"

#include "vtkObjectFactory.h"

#include <EGL/egl.h>

#include <dlfcn.h>

#include <cstdlib>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIOSMesaRenderWindow);

namespace
{
// GL/osmesa.h cannot be included after GLEW (it needs GL/gl.h's GLAPI, which
// glew.h undefines), and libOSMesa is loaded at run time: the few names this
// file uses, with the values of Mesa's osmesa.h.
using OSMesaContext = struct osmesa_context*;
constexpr int kOSMesaFormat = 0x22;
constexpr int kOSMesaDepthBits = 0x30;
constexpr int kOSMesaStencilBits = 0x31;
constexpr int kOSMesaProfile = 0x33;
constexpr int kOSMesaCoreProfile = 0x34;
constexpr int kOSMesaContextMajorVersion = 0x36;
constexpr int kOSMesaContextMinorVersion = 0x37;

// libGLdispatch's per-thread state, version 1 of the ABI between it and the
// window-system libraries (libGLX, libEGL). Its header is not installed by
// Debian; the layout is fixed by that ABI version, checked at load time.
struct GLdispatchThreadState
{
  int Tag; // 0 GLX, 1 EGL; the value below for this window
  void (*ThreadDestroyedCallback)(GLdispatchThreadState*);
  void* Private; // owned by libGLdispatch
};
constexpr int kGLdispatchABIVersion = 1;
constexpr int kTagEGL = 1;
constexpr int kTagOSMesa = 0x4f534d45; // 'OSME'

void ThreadDestroyed(GLdispatchThreadState*) {}

// libOSMesa and the libGLdispatch entry points, loaded once per process and
// never unloaded (GL contexts and dispatch tables outlive any one window).
struct OSMesaLibrary
{
  std::string Path;
  OSMesaContext (*CreateContextAttribs)(const int*, OSMesaContext) = nullptr;
  GLboolean (*MakeCurrent)(OSMesaContext, void*, GLenum, GLsizei, GLsizei) = nullptr;
  OSMesaContext (*GetCurrentContext)() = nullptr;
  void (*DestroyContext)(OSMesaContext) = nullptr;
  void* (*GetProcAddress)(const char*) = nullptr;

  void* (*CreateTable)(void* (*)(const char*, void*), void*) = nullptr;
  GLboolean (*DispatchMakeCurrent)(GLdispatchThreadState*, void*, int, const void*) = nullptr;
  void (*LoseCurrent)() = nullptr;
  GLdispatchThreadState* (*CurrentThreadState)() = nullptr;
  void* Table = nullptr; // entries from OSMesaGetProcAddress, shared by every context
  int VendorID = 0;
};

std::mutex& LibraryMutex()
{
  static std::mutex mutex;
  return mutex;
}

OSMesaLibrary*& LoadedLibrary()
{
  static OSMesaLibrary* library = nullptr;
  return library;
}

template <typename T>
bool Resolve(void* handle, const char* name, T& out, std::string& missing)
{
  out = reinterpret_cast<T>(dlsym(handle, name));
  if (!out)
  {
    missing += missing.empty() ? name : std::string(", ") + name;
  }
  return out != nullptr;
}

void* LookUpOSMesa(const char* name, void* library)
{
  return static_cast<OSMesaLibrary*>(library)->GetProcAddress(name);
}

// The loaded library, loading it on first use; nullptr with `why` on failure
// (a later call tries again, e.g. after MRGI_OSMESA_LIBRARY changed).
OSMesaLibrary* Library(std::string& why)
{
  std::lock_guard<std::mutex> lock(LibraryMutex());
  if (LoadedLibrary())
  {
    return LoadedLibrary();
  }
  const char* requested = std::getenv("MRGI_OSMESA_LIBRARY");
  std::vector<std::string> candidates;
  if (requested && requested[0])
  {
    candidates.emplace_back(requested);
  }
  else
  {
    candidates = { "libOSMesa.so.8", "libOSMesa.so.6" };
  }
  void* handle = nullptr;
  std::string path, errors;
  for (const std::string& candidate : candidates)
  {
    // RTLD_LOCAL: OSMesa's gl* symbols must not interpose on libglvnd's.
    handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle)
    {
      path = candidate;
      break;
    }
    const char* e = dlerror();
    errors += (errors.empty() ? "" : "; ") + std::string(e ? e : candidate.c_str());
  }
  if (!handle)
  {
    why = "libOSMesa could not be loaded (" + errors +
      (requested && requested[0] ? ")"
                                 : "); on Debian it is the package libosmesa6, or set "
                                   "MRGI_OSMESA_LIBRARY to the library file");
    return nullptr;
  }
  std::unique_ptr<OSMesaLibrary> lib(new OSMesaLibrary);
  lib->Path = path;
  std::string missing;
  Resolve(handle, "OSMesaCreateContextAttribs", lib->CreateContextAttribs, missing);
  Resolve(handle, "OSMesaMakeCurrent", lib->MakeCurrent, missing);
  Resolve(handle, "OSMesaGetCurrentContext", lib->GetCurrentContext, missing);
  Resolve(handle, "OSMesaDestroyContext", lib->DestroyContext, missing);
  Resolve(handle, "OSMesaGetProcAddress", lib->GetProcAddress, missing);
  if (!missing.empty())
  {
    dlclose(handle);
    why = path + " lacks " + missing + " (OSMesa 11.2 or newer is needed)";
    return nullptr;
  }

  // VTK reaches GL through libglvnd, which libGLdispatch routes: already
  // loaded with VTK's libOpenGL/libGL, opened here only to look it up.
  void* dispatch = dlopen("libGLdispatch.so.0", RTLD_NOW | RTLD_LOCAL | RTLD_NOLOAD);
  if (!dispatch)
  {
    dlclose(handle);
    why = "libGLdispatch.so.0 is not loaded: this VTK does not call OpenGL through libglvnd, "
          "so its GL calls cannot be routed to OSMesa";
    return nullptr;
  }
  int (*abiVersion)() = nullptr;
  int (*newVendorID)() = nullptr;
  void (*init)() = nullptr;
  Resolve(dispatch, "__glDispatchGetABIVersion", abiVersion, missing);
  Resolve(dispatch, "__glDispatchInit", init, missing);
  Resolve(dispatch, "__glDispatchNewVendorID", newVendorID, missing);
  Resolve(dispatch, "__glDispatchCreateTable", lib->CreateTable, missing);
  Resolve(dispatch, "__glDispatchMakeCurrent", lib->DispatchMakeCurrent, missing);
  Resolve(dispatch, "__glDispatchLoseCurrent", lib->LoseCurrent, missing);
  Resolve(dispatch, "__glDispatchGetCurrentThreadState", lib->CurrentThreadState, missing);
  // The handle only takes a reference to a library VTK keeps loaded anyway.
  dlclose(dispatch);
  if (!missing.empty() || abiVersion() != kGLdispatchABIVersion)
  {
    dlclose(handle);
    std::ostringstream msg;
    msg << "libGLdispatch.so.0 does not offer the dispatch ABI version " << kGLdispatchABIVersion;
    if (missing.empty())
    {
      msg << " (it has version " << abiVersion() << ")";
    }
    else
    {
      msg << " (it lacks " << missing << ")";
    }
    why = msg.str();
    return nullptr;
  }
  init(); // reference counted; libGLX/libEGL hold theirs
  lib->VendorID = newVendorID();
  lib->Table = lib->CreateTable(LookUpOSMesa, lib.get());
  if (!lib->Table)
  {
    dlclose(handle);
    why = "libGLdispatch could not create a dispatch table for OSMesa";
    return nullptr;
  }
  LoadedLibrary() = lib.release();
  return LoadedLibrary();
}

// The current thread's libglvnd state, or nullptr when libOSMesa was never loaded.
GLdispatchThreadState* CurrentThreadState(OSMesaLibrary* lib)
{
  return lib ? lib->CurrentThreadState() : nullptr;
}
}

namespace
{
// The OSMesa window whose context this thread made current last, so that
// PopContext() can make it current again: like GL's own current context, a
// per-thread fact, kept here because an OSMesa context alone cannot be made
// current without its window's dispatch state and pixel buffer.
thread_local vtkMRGIOSMesaRenderWindow* CurrentOSMesaWindow = nullptr;
}

struct vtkMRGIOSMesaRenderWindow::OSMesaState
{
  // What PushContext() found current, for PopContext() to restore.
  struct Previous
  {
    vtkMRGIOSMesaRenderWindow* OSMesaWindow;
    EGLDisplay Display;
    EGLContext Context;
  };
  std::vector<Previous> ContextStack;
  OSMesaLibrary* Library = nullptr;
  OSMesaContext Context = nullptr;
  GLdispatchThreadState Thread = { kTagOSMesa, ThreadDestroyed, nullptr };
  // OSMesa's framebuffer 0: one RGBA pixel. VTK draws into its own
  // framebuffers (UseOffScreenBuffers), sized to the window.
  unsigned char Pixel[4] = { 0, 0, 0, 0 };
};

//------------------------------------------------------------------------------
vtkMRGIOSMesaRenderWindow::vtkMRGIOSMesaRenderWindow()
  : OSMesa(new OSMesaState)
{
  this->ShowWindow = false;
  this->UseOffScreenBuffers = true;
  this->SetReadyForRendering(true);
  this->SetIsDirect(1);
  this->SetSupportsOpenGL(1);
  this->SetWindowName("MRGI headless (OSMesa)");
}

//------------------------------------------------------------------------------
vtkMRGIOSMesaRenderWindow::~vtkMRGIOSMesaRenderWindow()
{
  this->Finalize();
}

//------------------------------------------------------------------------------
bool vtkMRGIOSMesaRenderWindow::InitializeHeadlessContext()
{
  if (this->OSMesa->Context)
  {
    return true;
  }
  this->LastErrorMessage.clear();
  std::string why;
  OSMesaLibrary* lib = Library(why);
  if (!lib)
  {
    this->LastErrorMessage = why;
    return false;
  }
  this->OSMesa->Library = lib;

  // VTK needs 3.2 core; ask for the newest first, since OSMesa (unlike EGL)
  // returns exactly the version asked for.
  static const int versions[][2] = { { 4, 5 }, { 3, 3 }, { 3, 2 } };
  OSMesaContext context = nullptr;
  int version = 0;
  for (const auto& v : versions)
  {
    // Framebuffer 0 gets no depth or stencil: nothing draws into it, and
    // GetDepthBufferSize() (which vtkRenderer asks to pick its near plane)
    // reports VTK's render framebuffer instead (vtkMRGIHeadlessDepth.h), as
    // the surfaceless EGL window does: both windows frame alike.
    const int attributes[] = { kOSMesaFormat, GL_RGBA, kOSMesaDepthBits, 0, kOSMesaStencilBits, 0,
      kOSMesaProfile, kOSMesaCoreProfile, kOSMesaContextMajorVersion, v[0],
      kOSMesaContextMinorVersion, v[1], 0 };
    context = lib->CreateContextAttribs(attributes, nullptr);
    if (context)
    {
      version = v[0] * 10 + v[1];
      break;
    }
  }
  if (!context)
  {
    this->LastErrorMessage =
      "OSMesaCreateContextAttribs could not make an OpenGL 3.2 (or newer) core context with " +
      lib->Path;
    return false;
  }
  this->OSMesa->Context = context;
  this->ContextVersion = version;

  this->MakeCurrent();
  if (!this->IsCurrent())
  {
    const std::string reason = this->LastErrorMessage;
    this->DestroyContext();
    this->LastErrorMessage =
      reason.empty() ? "the OSMesa context could not be made current" : reason;
    return false;
  }
  this->SetIsCurrent(true);
  this->OpenGLInit();
  if (!this->Initialized)
  {
    this->DestroyContext();
    this->LastErrorMessage = "OpenGL initialization failed on the OSMesa context";
    return false;
  }
  std::ostringstream desc;
  desc << "OSMesa, OpenGL " << version / 10 << "." << version % 10 << " core";
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (renderer)
  {
    desc << ", " << renderer;
  }
  this->PlatformDescription = desc.str();
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIOSMesaRenderWindow::IsHeadlessRenderingAvailable()
{
  vtkMRGIOSMesaRenderWindow* probe = vtkMRGIOSMesaRenderWindow::New();
  const bool ok = probe->InitializeHeadlessContext();
  probe->Delete();
  return ok;
}

//------------------------------------------------------------------------------
void vtkMRGIOSMesaRenderWindow::ReleaseCurrentOSMesaContext()
{
  OSMesaLibrary* lib = nullptr;
  {
    std::lock_guard<std::mutex> lock(LibraryMutex());
    lib = LoadedLibrary();
  }
  GLdispatchThreadState* current = CurrentThreadState(lib);
  if (current && current->Tag == kTagOSMesa)
  {
    lib->LoseCurrent();
    lib->MakeCurrent(nullptr, nullptr, 0, 0, 0);
  }
}

//------------------------------------------------------------------------------
void vtkMRGIOSMesaRenderWindow::OpenGLInitContext()
{
  // As vtkMRGIEGLRenderWindow::OpenGLInitContext: the GLX flavour of GLEW
  // loads every entry point (glvnd stubs, routed to OSMesa while this context
  // is current) and then fails its GLX check, the one result accepted here.
  this->ContextCreationTime.Modified();
  if (this->Initialized)
  {
    return;
  }
  const GLenum result = glewInit();
  if (result != GLEW_OK && result != GLEW_ERROR_NO_GLX_DISPLAY)
  {
    vtkErrorMacro("GLEW could not be initialized on the OSMesa context: "
      << reinterpret_cast<const char*>(glewGetErrorString(result)));
    return;
  }
  if (!GLEW_VERSION_3_2)
  {
    vtkErrorMacro("The OSMesa context does not provide OpenGL 3.2 core, which VTK requires.");
    return;
  }
  this->Initialized = true;
  GLfloat lineWidthRange[2] = { 1.0f, 1.0f };
  glGetFloatv(
    this->LineSmoothing ? GL_SMOOTH_LINE_WIDTH_RANGE : GL_ALIASED_LINE_WIDTH_RANGE, lineWidthRange);
  this->MaximumHardwareLineWidth = (glGetError() == GL_NO_ERROR) ? lineWidthRange[1] : 1.0f;
}

//------------------------------------------------------------------------------
void vtkMRGIOSMesaRenderWindow::Initialize()
{
  if (!this->InitializeHeadlessContext())
  {
    vtkErrorMacro(<< this->LastErrorMessage);
  }
}

//------------------------------------------------------------------------------
void vtkMRGIOSMesaRenderWindow::Start()
{
  if (!this->OSMesa->Context)
  {
    this->Initialize();
  }
  this->Superclass::Start();
}

//------------------------------------------------------------------------------
void vtkMRGIOSMesaRenderWindow::Render()
{
  if (this->Size[0] < 1 || this->Size[1] < 1)
  {
    vtkErrorMacro("cannot render a " << this->Size[0] << "x" << this->Size[1]
                                     << " window: width and height must be at least 1");
    return;
  }
  if (!this->OSMesa->Context && !this->InitializeHeadlessContext())
  {
    vtkErrorMacro(<< this->LastErrorMessage);
    return;
  }
  this->MakeCurrent();
  if (!this->IsCurrent())
  {
    vtkErrorMacro(<< this->LastErrorMessage);
    return;
  }
  // As in the EGL window: errors left behind by GL calls outside Render()
  // are not this frame's.
  int stale = 0;
  while (glGetError() != GL_NO_ERROR && stale < 16)
  {
    ++stale;
  }
  this->Superclass::Render();
}

//------------------------------------------------------------------------------
void vtkMRGIOSMesaRenderWindow::MakeCurrent()
{
  OSMesaState& s = *this->OSMesa;
  if (!s.Context || this->IsCurrent())
  {
    return;
  }
  // libglvnd keeps one window-system API current per thread and refuses to
  // switch while another is: release what is current first.
  GLdispatchThreadState* current = CurrentThreadState(s.Library);
  if (current && current->Tag == kTagOSMesa)
  {
    s.Library->LoseCurrent();
  }
  else if (current && current->Tag == kTagEGL)
  {
    eglMakeCurrent(eglGetCurrentDisplay(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  else if (current)
  {
    this->LastErrorMessage = "cannot make the OSMesa context current: a GLX context is current "
                             "on this thread (release it first)";
    return;
  }
  if (!s.Library->MakeCurrent(s.Context, s.Pixel, GL_UNSIGNED_BYTE, 1, 1))
  {
    this->LastErrorMessage = "OSMesaMakeCurrent failed";
    return;
  }
  if (!s.Library->DispatchMakeCurrent(&s.Thread, s.Library->Table, s.Library->VendorID, nullptr))
  {
    s.Library->MakeCurrent(nullptr, nullptr, 0, 0, 0);
    this->LastErrorMessage = "libGLdispatch refused to make the OSMesa dispatch table current";
    return;
  }
  CurrentOSMesaWindow = this;
}

//------------------------------------------------------------------------------
void vtkMRGIOSMesaRenderWindow::PushContext()
{
  // VTK frees a resource of this window from inside another window's render
  // (a mapper shared by two windows): it pushes this context, frees, and
  // pops. The base class's PopContext() does nothing, which would leave this
  // context current under the other window's draw calls.
  OSMesaState::Previous previous = { nullptr, eglGetCurrentDisplay(), eglGetCurrentContext() };
  if (CurrentOSMesaWindow && CurrentOSMesaWindow->IsCurrent())
  {
    previous.OSMesaWindow = CurrentOSMesaWindow;
  }
  this->OSMesa->ContextStack.push_back(previous);
  this->MakeCurrent();
}

//------------------------------------------------------------------------------
void vtkMRGIOSMesaRenderWindow::PopContext()
{
  if (this->OSMesa->ContextStack.empty())
  {
    return;
  }
  const OSMesaState::Previous previous = this->OSMesa->ContextStack.back();
  this->OSMesa->ContextStack.pop_back();
  if (previous.OSMesaWindow == this)
  {
    return;
  }
  if (previous.OSMesaWindow)
  {
    previous.OSMesaWindow->MakeCurrent();
  }
  else if (previous.Context != EGL_NO_CONTEXT)
  {
    this->ReleaseCurrent();
    eglMakeCurrent(previous.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, previous.Context);
  }
  else
  {
    this->ReleaseCurrent();
  }
}

//------------------------------------------------------------------------------
void vtkMRGIOSMesaRenderWindow::ReleaseCurrent()
{
  if (CurrentOSMesaWindow == this)
  {
    CurrentOSMesaWindow = nullptr;
  }
  if (this->IsCurrent())
  {
    this->OSMesa->Library->LoseCurrent();
    this->OSMesa->Library->MakeCurrent(nullptr, nullptr, 0, 0, 0);
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIOSMesaRenderWindow::IsCurrent()
{
  const OSMesaState& s = *this->OSMesa;
  return s.Context && CurrentThreadState(s.Library) == &s.Thread &&
    s.Library->GetCurrentContext() == s.Context;
}

//------------------------------------------------------------------------------
int vtkMRGIOSMesaRenderWindow::SupportsOpenGL()
{
  return (this->OSMesa->Context || this->InitializeHeadlessContext()) ? 1 : 0;
}

//------------------------------------------------------------------------------
void* vtkMRGIOSMesaRenderWindow::GetGenericContext()
{
  return this->OSMesa->Context;
}

//------------------------------------------------------------------------------
void* vtkMRGIOSMesaRenderWindow::GetGenericDisplayId()
{
  return nullptr;
}

//------------------------------------------------------------------------------
int vtkMRGIOSMesaRenderWindow::GetDepthBufferSize()
{
  return vtkMRGIHeadlessDepth::RenderFramebufferDepthBits(this, this->Initialized);
}

//------------------------------------------------------------------------------
int vtkMRGIOSMesaRenderWindow::GetColorBufferSizes(int* rgba)
{
  // VTK renders into its own RGBA8 framebuffers here; OSMesa's single-buffered
  // framebuffer 0 has no back buffer for VTK 9.2's query.
  if (!rgba)
  {
    return 0;
  }
  rgba[0] = rgba[1] = rgba[2] = rgba[3] = 8;
  return 32;
}

//------------------------------------------------------------------------------
void vtkMRGIOSMesaRenderWindow::Finalize()
{
  if (this->OSMesa && this->OSMesa->Context)
  {
    this->MakeCurrent();
    if (this->IsCurrent())
    {
      this->ReleaseGraphicsResources(this);
    }
    this->DestroyContext();
  }
}

//------------------------------------------------------------------------------
void vtkMRGIOSMesaRenderWindow::DestroyContext()
{
  OSMesaState& s = *this->OSMesa;
  if (!s.Context)
  {
    return;
  }
  this->ReleaseCurrent();
  s.Library->DestroyContext(s.Context);
  s.Context = nullptr;
  this->Initialized = false;
  this->SetIsCurrent(false);
}

//------------------------------------------------------------------------------
bool vtkMRGIOSMesaRenderWindow::CheckContextForRead()
{
  if (!this->OSMesa->Context || !this->Initialized)
  {
    vtkErrorMacro("cannot read pixels: the window has no OpenGL context"
      << (this->LastErrorMessage.empty() ? std::string(" (it was never rendered)")
                                         : " (" + this->LastErrorMessage + ")"));
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkMRGIOSMesaRenderWindow::ReadPixels(
  const vtkRecti& rect, int front, int glFormat, int glType, void* data, int right)
{
  if (!this->CheckContextForRead())
  {
    return VTK_ERROR;
  }
  return this->Superclass::ReadPixels(rect, front, glFormat, glType, data, right);
}

//------------------------------------------------------------------------------
int vtkMRGIOSMesaRenderWindow::GetZbufferData(int x1, int y1, int x2, int y2, float* z)
{
  if (!this->CheckContextForRead())
  {
    return VTK_ERROR;
  }
  return this->Superclass::GetZbufferData(x1, y1, x2, y2, z);
}

//------------------------------------------------------------------------------
void vtkMRGIOSMesaRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PlatformDescription: "
     << (this->PlatformDescription.empty() ? "(none)" : this->PlatformDescription) << "\n";
  os << indent << "ContextVersion: " << this->ContextVersion << "\n";
  os << indent << "Library: "
     << (this->OSMesa->Library ? this->OSMesa->Library->Path : std::string("(not loaded)")) << "\n";
  os << indent
     << "LastErrorMessage: " << (this->LastErrorMessage.empty() ? "(none)" : this->LastErrorMessage)
     << "\n";
}
