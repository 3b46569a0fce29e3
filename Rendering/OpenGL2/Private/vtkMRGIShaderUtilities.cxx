#include "vtkMRGIShaderUtilities.h"

#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"
#include "vtkShaderProgram.h"

#include "mrgi_buffers.h"
#include "mrgi_glsl_defines.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "vtkNew.h"

namespace vtkMRGIShaderUtilities
{
//------------------------------------------------------------------------------
void SelectDrawBuffers(vtkOpenGLFramebufferObject* fbo, unsigned int count)
{
  fbo->ActivateDrawBuffers(count);
  std::vector<GLenum> buffers(count);
  for (unsigned int a = 0; a < count; ++a)
  {
    buffers[a] = static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + a);
  }
  glDrawBuffers(static_cast<GLsizei>(count), buffers.data());
}

//------------------------------------------------------------------------------
const std::string& Defines()
{
  static const std::string block = []() {
    std::vector<char> buffer(16384);
    size_t written = 0;
    mrgi_error err;
    if (mrgi_glsl_defines(buffer.data(), buffer.size(), &written, &err) != MRGI_OK)
    {
      // The buffer is sized for the core's constants; failing here is a
      // programming error that every shader test would expose.
      return std::string("#error MRGI constants block: ") + err.message + "\n";
    }
    return std::string(buffer.data(), written);
  }();
  return block;
}

//------------------------------------------------------------------------------
std::string ResolveAttachments(std::string code)
{
  static const struct
  {
    const char* name;
    int value;
  } attachments[] = { { "MRGI_GBUFFER_DIRECT", MRGI_GBUFFER_DIRECT },
    { "MRGI_GBUFFER_POSITION", MRGI_GBUFFER_POSITION },
    { "MRGI_GBUFFER_NORMAL", MRGI_GBUFFER_NORMAL }, { "MRGI_GBUFFER_ALBEDO", MRGI_GBUFFER_ALBEDO },
    { "MRGI_GBUFFER_SPECULAR", MRGI_GBUFFER_SPECULAR },
    { "MRGI_GBUFFER_SHININESS", MRGI_GBUFFER_SHININESS },
    { "MRGI_RSM_POSITION", MRGI_RSM_POSITION }, { "MRGI_RSM_NORMAL", MRGI_RSM_NORMAL },
    { "MRGI_RSM_FLUX", MRGI_RSM_FLUX } };
  for (const auto& a : attachments)
  {
    vtkShaderProgram::Substitute(code, std::string("gl_FragData[") + a.name + "]",
      "gl_FragData[" + std::to_string(a.value) + "]", true);
  }
  return code;
}

//------------------------------------------------------------------------------
std::string FullScreenShader(const char* body)
{
  std::string code = "//VTK::System::Dec\n" + Defines() + ResolveAttachments(body);
  // vtkOpenGLQuadHelper binds texCoordIn, which the vertex shader passes on
  // as texCoord; passes that address texels by gl_FragCoord must still use
  // it, or the compiler drops the attribute and the helper reports an error.
  vtkShaderProgram::Substitute(code, "void main()\n{",
    "void main()\n{\n  if (texCoord.x < -1.0) { discard; } // never true: keeps texCoord alive", false);
  return code;
}

//------------------------------------------------------------------------------
void AddCaptureMarkers(std::string& fragmentShader)
{
  vtkShaderProgram::Substitute(
    fragmentShader, "//VTK::System::Dec", "//VTK::System::Dec\n//MRGI::Dec\n", false);
  vtkShaderProgram::Substitute(fragmentShader, "//VTK::DepthPeeling::Impl",
    "//MRGI::Capture::Impl\n  //VTK::DepthPeeling::Impl", false);
}

//------------------------------------------------------------------------------
bool CanCapture(const std::string& fs)
{
  return fs.find("//MRGI::Capture::Impl") != std::string::npos &&
    fs.find("vertexVC") != std::string::npos &&
    fs.find("normalVCVSOutput") != std::string::npos &&
    fs.find("vec3 diffuseColor") != std::string::npos;
}

//------------------------------------------------------------------------------
void InsertCapture(
  std::string& fs, const std::string& declarations, const std::string& capture)
{
  vtkShaderProgram::Substitute(fs, "//MRGI::Dec", Defines() + declarations, false);
  std::string impl = "  vec3 mrgiTextureFactor = vec3(1.0);\n";
  // VTK multiplies its lit colour by the texture colour after lighting, on
  // front faces (or all faces with showTexturesOnBackface): so is the albedo.
  if (fs.find("vec4 tcolor =") != std::string::npos &&
    fs.find("showTexturesOnBackface") != std::string::npos)
  {
    impl += "  if (gl_FrontFacing == true || showTexturesOnBackface) { mrgiTextureFactor = "
            "tcolor.rgb; }\n";
  }
  // PBR with a base colour texture: VTK's albedo is albedoSample.rgb * diffuseColor.
  if (fs.find("vec4 albedoSample =") != std::string::npos)
  {
    impl += "  mrgiTextureFactor = albedoSample.rgb;\n";
  }
  impl += ResolveAttachments(capture);
  vtkShaderProgram::Substitute(fs, "//MRGI::Capture::Impl", impl, false);
}

//------------------------------------------------------------------------------
void ReleaseTexture(vtkTextureObject*& t, vtkWindow* w)
{
  if (t)
  {
    if (w)
    {
      t->ReleaseGraphicsResources(w);
    }
    t->Delete();
    t = nullptr;
  }
}

//------------------------------------------------------------------------------
vtkTextureObject* NewTexture(vtkOpenGLRenderWindow* window, int internalFormat, int w, int h)
{
  const bool integer = internalFormat == GL_RGBA32UI;
  vtkTextureObject* t = vtkTextureObject::New();
  t->SetContext(window);
  t->SetInternalFormat(static_cast<unsigned int>(internalFormat));
  t->SetFormat(integer ? GL_RGBA_INTEGER : GL_RGBA);
  t->SetDataType(integer ? GL_UNSIGNED_INT : GL_FLOAT);
  t->SetMinificationFilter(vtkTextureObject::Nearest);
  t->SetMagnificationFilter(vtkTextureObject::Nearest);
  t->SetWrapS(vtkTextureObject::ClampToEdge);
  t->SetWrapT(vtkTextureObject::ClampToEdge);
  if (w < 1 || h < 1 ||
    !t->Allocate2D(static_cast<unsigned int>(w), static_cast<unsigned int>(h), 4,
      integer ? VTK_UNSIGNED_INT : VTK_FLOAT))
  {
    t->Delete();
    return nullptr;
  }
  return t;
}

//------------------------------------------------------------------------------
vtkTextureObject* NewMaskTexture(vtkOpenGLRenderWindow* window, int w, int h)
{
  return NewTexture(window, GL_R8, w, h);
}

//------------------------------------------------------------------------------
vtkTextureObject* NewFlagsTexture(vtkOpenGLRenderWindow* window, int w, int h)
{
  return NewTexture(window, GL_R16F, w, h);
}

//------------------------------------------------------------------------------
vtkTextureObject* NewDepthStencil(vtkOpenGLRenderWindow* window, int w, int h)
{
  vtkTextureObject* t = vtkTextureObject::New();
  t->SetContext(window);
  t->SetMinificationFilter(vtkTextureObject::Nearest);
  t->SetMagnificationFilter(vtkTextureObject::Nearest);
  if (w < 1 || h < 1 ||
    !t->AllocateDepthStencil(static_cast<unsigned int>(w), static_cast<unsigned int>(h)))
  {
    t->Delete();
    return nullptr;
  }
  return t;
}

//------------------------------------------------------------------------------
bool ReadTextureRGBA(vtkOpenGLRenderWindow* window, vtkTextureObject* texture, std::vector<float>& rgba)
{
  if (!window || !texture || texture->GetHandle() == 0)
  {
    return false;
  }
  const int w = static_cast<int>(texture->GetWidth());
  const int h = static_cast<int>(texture->GetHeight());
  rgba.assign(static_cast<size_t>(w) * static_cast<size_t>(h) * 4, 0.0f);
  return ReadTextureRegion(window, texture, 0, 0, w, h, 4, rgba.data());
}

bool ReadTextureRegion(vtkOpenGLRenderWindow* window, vtkTextureObject* texture, int x, int y,
  int w, int h, int components, float* out)
{
  if (!window || !texture || texture->GetHandle() == 0 || !out || w < 1 || h < 1 || x < 0 ||
    y < 0 || x + w > static_cast<int>(texture->GetWidth()) ||
    y + h > static_cast<int>(texture->GetHeight()) || (components != 3 && components != 4))
  {
    return false;
  }
  window->MakeCurrent();
  while (glGetError() != GL_NO_ERROR)
  {
  }
  vtkOpenGLState* ostate = window->GetState();
  ostate->PushReadFramebufferBinding();
  vtkNew<vtkOpenGLFramebufferObject> fbo;
  fbo->SetContext(window);
  fbo->Bind(GL_READ_FRAMEBUFFER);
  fbo->AddColorAttachment(0, texture);
  fbo->ActivateReadBuffer(0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x, y, w, h, components == 4 ? GL_RGBA : GL_RGB, GL_FLOAT, out);
  fbo->RemoveColorAttachments(1);
  ostate->PopReadFramebufferBinding();
  fbo->ReleaseGraphicsResources(window);
  return glGetError() == GL_NO_ERROR;
}
}

//------------------------------------------------------------------------------
const char* const vtkMRGIShaderUtilities::StagePrefix = "MRGI ";

//------------------------------------------------------------------------------
vtkMRGIShaderUtilities::ScopedStage::ScopedStage(vtkRenderTimerLog* timer, const char* stage)
{
  if (timer)
  {
    this->Logger = timer->StartScopedEvent(std::string(StagePrefix) + stage);
  }
}

//------------------------------------------------------------------------------
namespace
{
void CollectStages(const vtkRenderTimerLog::Event& event, std::vector<std::string>& names,
  std::vector<double>& times)
{
  if (event.Name.compare(0, std::strlen(vtkMRGIShaderUtilities::StagePrefix), vtkMRGIShaderUtilities::StagePrefix) == 0)
  {
    // A step drawn once per level logs one event per level: their sum.
    const std::string name = event.Name.substr(std::strlen(vtkMRGIShaderUtilities::StagePrefix));
    const double ms = static_cast<double>(event.ElapsedTimeNanoseconds()) * 1e-6;
    const auto found = std::find(names.begin(), names.end(), name);
    if (found != names.end())
    {
      times[static_cast<size_t>(found - names.begin())] += ms;
    }
    else
    {
      names.push_back(name);
      times.push_back(ms);
    }
  }
  for (const auto& child : event.Events)
  {
    CollectStages(child, names, times);
  }
}

}

//------------------------------------------------------------------------------
vtkRenderTimerLog* vtkMRGIShaderUtilities::StageTimer(vtkRenderer* renderer, bool enabled)
{
  vtkRenderWindow* window = renderer ? renderer->GetRenderWindow() : nullptr;
  vtkRenderTimerLog* timer = window ? window->GetRenderTimer() : nullptr;
  // Logging is switched on between frames only (FetchStageTimings, or the
  // application): VTK brackets its own rendering with timer events, and
  // switching mid-frame would leave those unbalanced.
  return (timer && enabled && timer->GetLoggingEnabled()) ? timer : nullptr;
}

//------------------------------------------------------------------------------
bool vtkMRGIShaderUtilities::CollectStageTimes(
  vtkRenderTimerLog* timer, std::vector<std::string>& names, std::vector<double>& times)
{
  bool found = false;
  while (timer->FrameReady())
  {
    vtkRenderTimerLog::Frame frame = timer->PopFirstReadyFrame();
    std::vector<std::string> frameNames;
    std::vector<double> frameTimes;
    for (const auto& event : frame.Events)
    {
      CollectStages(event, frameNames, frameTimes);
    }
    if (!frameNames.empty())
    {
      names.swap(frameNames);
      times.swap(frameTimes);
      found = true;
    }
  }
  return found;
}
