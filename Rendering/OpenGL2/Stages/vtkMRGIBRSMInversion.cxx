#include "vtkMRGIBRSMInversion.h"

#include "vtkMRGIResourceStatistics.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkMRGIBRSMInvertFS.h"

#include "mrgi_vpl.h"

vtkStandardNewMacro(vtkMRGIBRSMInversion);

//------------------------------------------------------------------------------
vtkMRGIBRSMInversion::vtkMRGIBRSMInversion() = default;

//------------------------------------------------------------------------------
vtkMRGIBRSMInversion::~vtkMRGIBRSMInversion()
{
  if (this->Quad || this->FrameBuffer || this->CDF || this->Samples)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  this->ReleaseGraphicsResources(nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGIBRSMInversion::ReleaseGraphicsResources(vtkWindow* w)
{
  if (this->Quad)
  {
    if (w)
    {
      this->Quad->ReleaseGraphicsResources(w);
    }
    delete this->Quad;
    this->Quad = nullptr;
  }
  for (vtkTextureObject** t : { &this->CDF, &this->Samples })
  {
    if (*t)
    {
      if (w)
      {
        (*t)->ReleaseGraphicsResources(w);
      }
      (*t)->Delete();
      *t = nullptr;
    }
  }
  if (this->FrameBuffer)
  {
    if (w)
    {
      this->FrameBuffer->ReleaseGraphicsResources(w);
    }
    this->FrameBuffer->Delete();
    this->FrameBuffer = nullptr;
  }
}

namespace
{
// (Re)upload `data` as a w x h float texture of `components` channels.
bool UploadFloat(vtkOpenGLRenderWindow* window, vtkTextureObject*& t, int w, int h,
  int components, const float* data)
{
  if (!t)
  {
    t = vtkTextureObject::New();
    t->SetContext(window);
  }
  t->SetMinificationFilter(vtkTextureObject::Nearest);
  t->SetMagnificationFilter(vtkTextureObject::Nearest);
  t->SetWrapS(vtkTextureObject::ClampToEdge);
  t->SetWrapT(vtkTextureObject::ClampToEdge);
  t->SetInternalFormat(components == 1 ? GL_R32F : GL_RG32F);
  t->SetFormat(components == 1 ? GL_RED : GL_RG);
  t->SetDataType(GL_FLOAT);
  vtkMRGIResourceStatistics::RecordTextureAllocation(w, h, 4 * components);
  return t->Create2DFromRaw(static_cast<unsigned int>(w), static_cast<unsigned int>(h),
    components, VTK_FLOAT, const_cast<float*>(data));
}
}

//------------------------------------------------------------------------------
bool vtkMRGIBRSMInversion::Invert(vtkOpenGLRenderWindow* window, int size,
  const std::vector<View>& views, const std::vector<float>& cdf, const std::vector<float>& samples,
  int count, vtkTextureObject* target, int firstRow, std::string& error)
{
  const int V = static_cast<int>(views.size());
  if (!window || !target || size < 1 || V < 1)
  {
    error = "BRSM GPU inversion needs a window, a target texture, an RSM size >= 1 and a view";
    return false;
  }
  for (const View& v : views)
  {
    if (!v.Position || !v.Normal || !v.Flux)
    {
      error = "BRSM GPU inversion: an RSM view texture is missing";
      return false;
    }
  }
  const size_t R = static_cast<size_t>(V) * static_cast<size_t>(size);
  if (cdf.size() != R * static_cast<size_t>(size + 1))
  {
    error = "BRSM GPU inversion: the float CDF holds " + std::to_string(cdf.size()) +
      " floats but " + std::to_string(R * static_cast<size_t>(size + 1)) + " are needed";
    return false;
  }
  if (count < MRGI_VPL_MIN_COUNT || count > MRGI_VPL_MAX_COUNT ||
    samples.size() != 2 * static_cast<size_t>(count))
  {
    error = "BRSM GPU inversion: " + std::to_string(samples.size()) + " sample values for " +
      std::to_string(count) + " VPLs (need 2 per VPL, 1.." + std::to_string(MRGI_VPL_MAX_COUNT) +
      " VPLs)";
    return false;
  }
  if (target->GetWidth() != MRGI_VPL_TEXELS || firstRow < 0 ||
    firstRow + count > static_cast<int>(target->GetHeight()))
  {
    error = "BRSM GPU inversion: rows " + std::to_string(firstRow) + ".." +
      std::to_string(firstRow + count) + " do not fit the VPL texture";
    return false;
  }
  if (!UploadFloat(window, this->CDF, static_cast<int>(R), size + 1, 1, cdf.data()) ||
    !UploadFloat(window, this->Samples, 1, count, 2, samples.data()))
  {
    error = "BRSM GPU inversion: cannot upload the CDF or the samples";
    return false;
  }
  if (this->Quad && this->QuadPicks != this->WritePicks)
  {
    this->Quad->ReleaseGraphicsResources(window);
    delete this->Quad;
    this->Quad = nullptr;
  }
  if (!this->Quad)
  {
    const std::string body =
      std::string("#define MRGI_BRSM_WRITE_PICKS ") + (this->WritePicks ? "1\n" : "0\n") +
      vtkMRGIBRSMInvertFS;
    this->Quad = new vtkOpenGLQuadHelper(window,
      vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
      vtkMRGIShaderUtilities::FullScreenShader(body.c_str()).c_str(), "");
    this->QuadPicks = this->WritePicks;
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(this->Quad->Program);
  }
  vtkShaderProgram* program = this->Quad->Program;
  if (!program || !program->GetCompiled())
  {
    error = "could not build the BRSM inversion shader";
    return false;
  }
  if (!this->FrameBuffer)
  {
    this->FrameBuffer = vtkOpenGLFramebufferObject::New();
    this->FrameBuffer->SetContext(window);
  }
  vtkOpenGLState* ostate = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depth(ostate, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable scissor(ostate, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglViewport viewport(ostate);
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDisable(GL_DEPTH_TEST);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  vtkOpenGLFramebufferObject* fbo = this->FrameBuffer;
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->AddColorAttachment(0, target);
  vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, 1);
  this->CDF->Activate();
  this->Samples->Activate();
  for (int v = 0; v < V; ++v)
  {
    const View& view = views[static_cast<size_t>(v)];
    view.Position->Activate();
    view.Normal->Activate();
    view.Flux->Activate();
    program->SetUniformi("mrgiRSMPosition", view.Position->GetTextureUnit());
    program->SetUniformi("mrgiRSMNormal", view.Normal->GetTextureUnit());
    program->SetUniformi("mrgiRSMFlux", view.Flux->GetTextureUnit());
    program->SetUniformi("mrgiCDF", this->CDF->GetTextureUnit());
    program->SetUniformi("mrgiSamples", this->Samples->GetTextureUnit());
    program->SetUniformi("mrgiRSMSize", size);
    program->SetUniformi("mrgiViewCount", V);
    program->SetUniformi("mrgiView", v);
    program->SetUniformi("mrgiFirstVPL", firstRow);
    program->SetUniformi("mrgiCount", count);
    ostate->vtkglViewport(0, firstRow, MRGI_VPL_TEXELS, count);
    this->Quad->Render();
    view.Flux->Deactivate();
    view.Normal->Deactivate();
    view.Position->Deactivate();
  }
  this->Samples->Deactivate();
  this->CDF->Deactivate();
  fbo->RemoveColorAttachments(1);
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIBRSMInversion::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "WritePicks: " << this->WritePicks << "\n";
}
