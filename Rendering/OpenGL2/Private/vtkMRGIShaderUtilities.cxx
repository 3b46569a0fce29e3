#include "vtkMRGIShaderUtilities.h"

#include "vtkMRGIResourceStatistics.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"

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
void SelectGBufferDrawBuffers(vtkOpenGLFramebufferObject* fbo, bool specular, bool lightTerms)
{
  const unsigned int count = lightTerms ? MRGI_GBUFFER_MAX_ATTACHMENTS
    : specular                          ? MRGI_GBUFFER_ATTACHMENTS
                                        : MRGI_GBUFFER_SPECULAR;
  fbo->ActivateDrawBuffers(count);
  std::vector<GLenum> buffers(count);
  for (unsigned int a = 0; a < count; ++a)
  {
    const bool unused =
      !specular && a >= MRGI_GBUFFER_SPECULAR && a < MRGI_GBUFFER_ATTACHMENTS;
    buffers[a] = unused ? static_cast<GLenum>(GL_NONE) : static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + a);
  }
  glDrawBuffers(static_cast<GLsizei>(count), buffers.data());
}

//------------------------------------------------------------------------------
void InsertLightTerms(std::string& fs, std::string& declarations, std::string& capture)
{
  const bool pbr = fs.find("vec3 Lo = vec3(0.0);") != std::string::npos;
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    declarations += "vec3 mrgiLightTerm" + std::to_string(s) + " = vec3(0.0);\n";
  }
  declarations += "vec3 mrgiLightLo;\n";
  // The strings below are VTK 9.1's and 9.2's light loop
  // (vtkOpenGLPolyDataMapper::ReplaceShaderLight; vtkShadowMapPass edits the
  // same lines). Each light's lines appear in light order, so the first
  // remaining occurrence belongs to the next light.
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    const std::string n = std::to_string(s);
    const std::string term = "mrgiLightTerm" + n;
    if (pbr)
    {
      for (const char* form : { "NdL", "NdV" })
      {
        const std::string line = std::string("Lo += radiance * (diffuse + specular) * ") + form + ";";
        const size_t at = fs.find(line);
        if (at != std::string::npos)
        {
          fs.replace(at, line.size(),
            std::string("mrgiLightLo = radiance * (diffuse + specular) * ") + form +
              "; Lo += mrgiLightLo; " + term + " += mrgiLightLo;");
          break;
        }
      }
      const std::string coat = "Lo += coatLayer;";
      const size_t at = fs.find(coat);
      if (at != std::string::npos)
      {
        fs.replace(at, coat.size(), "Lo += (coatLayer); " + term + " += coatLayer;");
      }
    }
    else
    {
      vtkShaderProgram::Substitute(fs, "diffuse += (df * lightColor" + n + ");",
        "diffuse += (df * lightColor" + n + "); " + term + " += df * lightColor" + n +
          " * diffuseColor;",
        false);
      vtkShaderProgram::Substitute(fs, "specular += (sf * lightColor" + n + ");",
        "specular += (sf * lightColor" + n + "); " + term + " += sf * lightColor" + n +
          " * specularColor;",
        false);
      if (s == 0)
      {
        // The headlight (VTK's light complexity 1): light 0 is the only one.
        vtkShaderProgram::Substitute(fs, "vec3 specular = sf * specularColor * lightColor0;",
          "vec3 specular = sf * specularColor * lightColor0; " + term + " = diffuse + specular;",
          false);
      }
    }
  }
  std::string factor = "mrgiTextureFactor";
  std::string sign = "1.0";
  if (pbr)
  {
    // VTK scales the whole lit colour by its occlusion term, then encodes
    // pow(color, 1/2.2): the terms take the occlusion, the sign marks the law.
    factor = fs.find("color = mix(color, color * ao, aoStrengthUniform);") != std::string::npos
      ? "vec3(1.0 + aoStrengthUniform * (ao - 1.0))"
      : "vec3(1.0)";
    sign = fs.find("pow(color, vec3(1.0/2.2))") != std::string::npos ? "-1.0" : "1.0";
  }
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    const std::string n = std::to_string(s);
    capture += "  gl_FragData[MRGI_GBUFFER_LIGHT" + n + "] = vec4(" + sign + " * max(mrgiLightTerm" +
      n + " * " + factor + ", vec3(0.0)), 1.0);\n";
  }
}

//------------------------------------------------------------------------------
std::string NoLightTerms()
{
  std::string capture;
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    capture += "  gl_FragData[MRGI_GBUFFER_LIGHT" + std::to_string(s) + "] = vec4(0.0, 0.0, 0.0, 1.0);\n";
  }
  return capture;
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
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    vtkShaderProgram::Substitute(code, "gl_FragData[MRGI_GBUFFER_LIGHT" + std::to_string(s) + "]",
      "gl_FragData[" + std::to_string(MRGI_GBUFFER_LIGHT0 + s) + "]", true);
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
  vtkMRGIResourceStatistics::RecordTextureAllocation(w, h, BytesPerTexel(internalFormat));
  return t;
}

int BytesPerTexel(int internalFormat)
{
  switch (internalFormat)
  {
    case GL_RGBA32F:
    case GL_RGBA32UI:
      return 16;
    case GL_RGBA16F:
    case GL_RG32F:
      return 8;
    case GL_R32F:
    case GL_RGBA8:
    case GL_DEPTH24_STENCIL8:
    case GL_DEPTH_COMPONENT24:
    case GL_DEPTH_COMPONENT32:
    case GL_DEPTH_COMPONENT32F:
      return 4;
    case GL_R16F:
      return 2;
    case GL_R8:
      return 1;
    default:
      return 16;
  }
}

void ResizeTexture(vtkTextureObject* t, int w, int h)
{
  if (t && (t->GetWidth() != static_cast<unsigned int>(w) || t->GetHeight() != static_cast<unsigned int>(h)))
  {
    t->Resize(static_cast<unsigned int>(w), static_cast<unsigned int>(h));
    vtkMRGIResourceStatistics::RecordTextureAllocation(
      w, h, BytesPerTexel(static_cast<int>(t->GetInternalFormat(VTK_FLOAT, 4, false))));
  }
}

bool EnsureTexture(
  vtkOpenGLRenderWindow* window, vtkTextureObject*& t, int size[2], int internalFormat, int w, int h)
{
  if (t && size[0] == w && size[1] == h)
  {
    return true;
  }
  ReleaseTexture(t, window);
  t = NewTexture(window, internalFormat, w, h);
  size[0] = t ? w : 0;
  size[1] = t ? h : 0;
  return t != nullptr;
}

void CameraProjection(vtkRenderer* renderer, float matrix[16])
{
  vtkMatrix4x4* projection = renderer->GetActiveCamera()->GetProjectionTransformMatrix(
    renderer->GetTiledAspectRatio(), -1, 1);
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      matrix[c * 4 + r] = static_cast<float>(projection->GetElement(r, c));
    }
  }
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
  vtkMRGIResourceStatistics::RecordTextureAllocation(w, h, BytesPerTexel(GL_DEPTH24_STENCIL8));
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
