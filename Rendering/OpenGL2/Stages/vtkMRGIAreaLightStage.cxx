#include "vtk_glew.h"

#include "vtkMRGIAreaLightStage.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataObject.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIIncrementalStencil.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIRSMCompositor.h"
#include "vtkMRGIShaderLibraries.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGISpecularStencil.h"
#include "vtkMRGIStageResources.h"
#include "vtkMRGIUpsample.h"
#include "vtkMRGIVarianceShadowQuery.h"
#include "vtkMRGIVisibilityPyramid.h"
#include "vtkMRGIVoxelization.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderTimerLog.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTexture.h"
#include "vtkTextureObject.h"
#include "vtkTypeUInt32Array.h"

#include "mrgi_area_light.h"
#include "mrgi_multires.h"
#include "mrgi_voxel_march.h"

#include <algorithm>
#include <set>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIAreaLightStage);
vtkCxxSetObjectMacro(vtkMRGIAreaLightStage, Compositor, vtkMRGIRSMCompositor);

namespace
{
using vtkMRGIShaderUtilities::ScopedStage;

// Draw `quad` once per batch of `batch` light samples (uniforms
// mrgiSpecularBatchFirst / Count), the later batches added to the first
// (RGB summed, alpha kept): each draw's marches stay within llvmpipe's
// loop budget (mrgi_voxel_samples_per_batch()). The caller restores the
// blend state.
void RenderSampleBatches(vtkOpenGLState* ostate, vtkShaderProgram* program,
  vtkOpenGLQuadHelper* quad, int sampleCount, int batch)
{
  for (int first = 0; first < sampleCount; first += batch)
  {
    if (first == batch)
    {
      ostate->vtkglEnable(GL_BLEND);
      ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
    }
    program->SetUniformi("mrgiSpecularBatchFirst", first);
    program->SetUniformi("mrgiSpecularBatchCount", std::min(batch, sampleCount - first));
    quad->Render();
  }
}

// The highlight's program (vtkMRGIAreaSpecularFS.glsl): at every pixel or
// at the specular stencil's texels (`multires`); unshadowed, shadowed with
// the masks' bits (`masked`) or with a march per sample in batches
// (`marched`), the lobe grid by the variance shadow query when shadowed.
vtkOpenGLQuadHelper* ReadySpecular(vtkMRGIProgramCache& programs, vtkOpenGLRenderWindow* window,
  bool multires, bool masked, bool marched)
{
  const std::string defines = std::string(multires ? "#define MRGI_AREA_SPECULAR_MULTIRES 1\n" : "") +
    (masked ? "#define MRGI_AREA_SPECULAR_VISIBILITY 1\n#define MRGI_AREA_SPECULAR_MASKS 1\n" : "") +
    (marched ? "#define MRGI_AREA_SPECULAR_VISIBILITY 1\n#define MRGI_AREA_SPECULAR_BATCHES 1\n" : "");
  return programs.Ready(window, "specular", defines, [masked, marched] {
    return marched ? vtkMRGIShaderLibraries::Compose({ "vtkMRGIVoxelMarch", "vtkMRGIVPLIrradiance",
                       "vtkMRGIVarianceShadowResolve", "vtkMRGIAreaSpecularFS" })
      : masked ? vtkMRGIShaderLibraries::Compose(
                   { "vtkMRGIVPLIrradiance", "vtkMRGIVarianceShadowResolve", "vtkMRGIAreaSpecularFS" })
               : vtkMRGIShaderLibraries::Compose({ "vtkMRGIAreaSpecularFS" });
  });
}
}

struct vtkMRGIAreaLightStage::Internals
{
  // The framebuffer and the programs: the highlight's (full resolution and
  // multiresolution; unshadowed, masked, marched) and the add.
  vtkMRGIStageResources GL;
  // Sample counts already warned about: more than the incremental masks
  // hold, so such a light falls back to naive visibility (one warning per
  // count, not one per frame).
  std::set<int> FallbackWarned;
};

//------------------------------------------------------------------------------
vtkMRGIAreaLightStage::vtkMRGIAreaLightStage()
  : Internal(new Internals)
{
  this->Voxelization = vtkMRGIVoxelization::New();
  // Two layers of depth slices, not NPW10's one: thinner voxels for little
  // march time (Documentation/AreaLights.md, "Depth slices").
  this->Voxelization->SetNumberOfSlices(MRGI_VOXEL_AREA_LIGHT_SLICES);
  this->VisibilityPyramid = vtkMRGIVisibilityPyramid::New();
  // 2x2 interleaving off by default: measured at 256^2 on llvmpipe it saved
  // 5-15% of the area-light time but raised the error against the ground
  // truth from 0.111 to 0.179 (living room; Cornell box 0.137 -> 0.142).
  this->VisibilityPyramid->InterleaveOff();
  this->VarianceShadowQuery = vtkMRGIVarianceShadowQuery::New();
  this->Gather = vtkMRGIGather::New();
  this->Upsample = vtkMRGIUpsample::New();
  this->IncrementalStencilStage = vtkMRGIIncrementalStencil::New();
  this->SpecularStencilStage = vtkMRGISpecularStencil::New();
}

//------------------------------------------------------------------------------
vtkMRGIAreaLightStage::~vtkMRGIAreaLightStage()
{
  this->SetCompositor(nullptr);
  this->ReleaseGraphicsResources(nullptr);
  this->RemoveAllLights();
  this->Voxelization->Delete();
  this->VisibilityPyramid->Delete();
  this->VarianceShadowQuery->Delete();
  this->Gather->Delete();
  this->Upsample->Delete();
  this->IncrementalStencilStage->Delete();
  this->SpecularStencilStage->Delete();
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLightStage::ReleaseGraphicsResources(vtkWindow* w)
{
  // Without a window (the destructor) the GL objects are gone with the
  // context; the C++ objects are freed either way.
  if (w)
  {
    this->Voxelization->ReleaseGraphicsResources(w);
    this->VisibilityPyramid->ReleaseGraphicsResources(w);
    this->VarianceShadowQuery->ReleaseGraphicsResources(w);
    this->Gather->ReleaseGraphicsResources(w);
    this->Upsample->ReleaseGraphicsResources(w);
    this->IncrementalStencilStage->ReleaseGraphicsResources(w);
    this->SpecularStencilStage->ReleaseGraphicsResources(w);
    for (vtkMRGIAreaLight* light : this->Lights)
    {
      light->ReleaseGraphicsResources(w);
    }
  }
  this->Internal->GL.Release(w);
  vtkMRGIShaderUtilities::ReleaseTexture(this->IrradianceTexture, w);
  vtkMRGIShaderUtilities::ReleaseTexture(this->DirectTexture, w);
  vtkMRGIShaderUtilities::ReleaseTexture(this->SumTexture, w);
  this->Signature.clear(); // the sum it describes is gone
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLightStage::AddLight(vtkMRGIAreaLight* light)
{
  if (!light || std::find(this->Lights.begin(), this->Lights.end(), light) != this->Lights.end())
  {
    return;
  }
  light->Register(this);
  this->Lights.push_back(light);
  this->Modified();
}

void vtkMRGIAreaLightStage::RemoveLight(vtkMRGIAreaLight* light)
{
  auto it = std::find(this->Lights.begin(), this->Lights.end(), light);
  if (it == this->Lights.end())
  {
    return;
  }
  // The light keeps its GPU textures (its own ReleaseGraphicsResources).
  this->Lights.erase(it);
  light->UnRegister(this);
  this->Modified();
}

void vtkMRGIAreaLightStage::RemoveAllLights()
{
  while (!this->Lights.empty())
  {
    this->RemoveLight(this->Lights.back());
  }
}

int vtkMRGIAreaLightStage::GetNumberOfLights() const
{
  return static_cast<int>(this->Lights.size());
}

vtkMRGIAreaLight* vtkMRGIAreaLightStage::GetLight(int index) const
{
  return index >= 0 && index < this->GetNumberOfLights() ? this->Lights[static_cast<size_t>(index)]
                                                             : nullptr;
}


//------------------------------------------------------------------------------
bool vtkMRGIAreaLightStage::Render(const vtkMRGIFrameContext& frame,
  vtkMRGIMultiresolution* buffer, bool selected, vtkTextureObject* color)
{
  vtkOpenGLRenderWindow* renWin = frame.Window;
  vtkRenderer* renderer = frame.Renderer;
  vtkRenderTimerLog* timer = frame.Timer;
  this->IncrementalStencilUsed = false;
  if (!renWin || !renderer || !buffer || !color || !frame.Position || !frame.Normal || !frame.Albedo)
  {
    vtkErrorMacro("area lights need a window, a renderer, the G-buffer, the multiresolution buffer and a colour target");
    return false;
  }
  // nichols-penmatsa-wyman-2010 3.2: the area light's direct light at the
  // multiresolution texels, upsampled like the indirect light. One gather,
  // upsampling and resolve per light, each added to the lights' sum, which
  // is added to the colour once (and read by GetAreaLightBuffer()). Timed as
  // the stage "area" with its steps.
  const std::string signature = this->Inputs(frame, buffer);
  bool reuse = !signature.empty() && signature == this->Signature && this->SumTexture;
  const bool distributed = this->Compositor && this->Compositor->GetNumberOfProcesses() > 1;
  if (distributed)
  {
    // Together: a process recomputing alone would wait in the voxels' OR.
    double recompute = reuse ? 0.0 : 1.0;
    this->Compositor->AllReduceMax(&recompute, 1);
    reuse = recompute == 0.0;
  }
  if (reuse)
  {
    // Nothing the lights' sum depends on changed: add it again.
    ScopedStage stage(timer, "area");
    return this->Add(frame, this->SumTexture, color);
  }
  this->Signature.clear();
  // The indirect light's selection serves when it selects as the area
  // lights do; else they select with their own thresholds.
  if (!selected || !buffer->SelectionServesAreaLights())
  {
    ScopedStage stage(timer, "select");
    if (!buffer->Update(renWin, frame.Position, frame.Normal, frame.Viewport[0], frame.Viewport[1],
          frame.Viewport[2], frame.Viewport[3], frame.PixelSize[0], frame.PixelSize[1], timer,
          true))
    {
      return false;
    }
  }
  ScopedStage stage(timer, "area");
  // Steps: "voxelize", "visibility.pyramid" and "gather.samples" (the
  // gathers; receivers are this frame's, built once).
  if (!buffer->HasReceivers() &&
    !buffer->BuildReceivers(renWin, frame.Position, frame.Normal, frame.Viewport[0], frame.Viewport[1], timer))
  {
    return false;
  }
  const int w = static_cast<int>(color->GetWidth()), h = static_cast<int>(color->GetHeight());
  auto ensure = [&](vtkTextureObject*& t) {
    if (!t)
    {
      t = vtkMRGIShaderUtilities::NewTexture(renWin, GL_RGBA32F, w, h);
    }
    else
    {
      vtkMRGIShaderUtilities::ResizeTexture(t, static_cast<int>(w), static_cast<int>(h));
    }
    return t != nullptr;
  };
  if (!ensure(this->IrradianceTexture) || !ensure(this->DirectTexture) || !ensure(this->SumTexture))
  {
    vtkErrorMacro("could not allocate the area lights' buffers (" << w << " x " << h << ")");
    return false;
  }
  this->Internal->GL.Prepare(renWin);
  {
    // Clear the sum over the viewport.
    vtkOpenGLState* ostate = renWin->GetState();
    vtkMRGIViewportStep state(ostate, frame.Viewport);
    vtkOpenGLFramebufferObject* fbo = this->Internal->GL.FrameBuffer;
    fbo->SaveCurrentBindingsAndBuffers();
    fbo->Bind();
    fbo->AddColorAttachment(0, this->SumTexture);
    vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, 1);
    vtkOpenGLState::ScopedglClearColor clearColor(ostate);
    ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
    ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
    fbo->UnBind();
    fbo->RestorePreviousBindingsAndBuffers();
  }
  // Visibility: one voxelization per frame for every light, over the
  // visible props' depth range within the camera's clipping range (VTK pads
  // the clipping range; mrgi_voxel_fit_depth_range() says why it matters).
  vtkMRGIVoxelization* voxels = nullptr;
  if (this->Visibility != VisibilityOff)
  {
    double range[2] = { 0.0, 1.0 };
    vtkMRGIVoxelization::ComputeDepthRange(renderer, range);
    if (distributed)
    {
      // One grid on every process (their voxels are OR-ed below): the
      // union of the processes' ranges (each sees its own props' bounds),
      // or the shared clipping range when the reduction fails.
      double extent[2] = { -range[0], range[1] };
      if (this->Compositor->AllReduceMax(extent, 2))
      {
        range[0] = -extent[0];
        range[1] = extent[1];
      }
      else
      {
        renderer->GetActiveCamera()->GetClippingRange(range);
      }
    }
    if (this->Voxelization->Voxelize(renderer, range[0], range[1], timer))
    {
      voxels = this->Voxelization;
    }
    else
    {
      vtkErrorMacro("area lights: could not voxelize the scene; drawing them without shadows");
    }
    if (distributed)
    {
      // Every process's geometry in every process's voxels (same camera,
      // clipping range and voxel size: the same grid). A process that
      // could not voxelize still takes part, with no bits.
      int size[2];
      this->Voxelization->ComputeVoxelSize(renderer, range[0], range[1], size);
      vtkNew<vtkTypeUInt32Array> bits;
      if (!voxels || !this->Voxelization->ReadVoxels(renWin, bits))
      {
        bits->SetNumberOfComponents(
          this->Voxelization->GetNumberOfSlices() / MRGI_VOXEL_CHANNEL_BITS);
        bits->SetNumberOfTuples(static_cast<vtkIdType>(size[0]) * size[1]);
        bits->Fill(0);
      }
      if (!this->Compositor->AllReduceBitwiseOr(bits->GetPointer(0), bits->GetNumberOfValues()) ||
        (voxels && !this->Voxelization->WriteVoxels(renWin, bits)))
      {
        vtkErrorMacro("area lights: could not merge the processes' voxels; shadows from other "
                      "processes' geometry are missing");
      }
    }
  }
  bool drawn = false;
  for (size_t i = 0; i < this->Lights.size(); ++i)
  {
    vtkMRGIAreaLight* light = this->Lights[i];
    // The light's samples on the GPU, uploaded by the light once per rebuild.
    int count = 0;
    vtkTextureObject* texture = light->GetSampleTexture(renWin, &count);
    mrgi_area_light_uniforms uniforms;
    if (!texture || count < 1 || !light->GetCoreUniforms(&uniforms))
    {
      continue; // the light reported why
    }
    // Incremental visibility: the masks of every level first (they need
    // this selection's receivers), then the gather reads its texel's bits.
    vtkMRGIVisibilityPyramid* masks = nullptr;
    const int maxMaskSamples = vtkMRGIVisibilityPyramid::GetMaximumNumberOfSamples();
    if (voxels && this->Visibility == VisibilityIncremental && count > maxMaskSamples &&
      this->Internal->FallbackWarned.insert(count).second)
    {
      vtkWarningMacro("area light with " << count << " samples: incremental visibility keeps at most "
                                         << maxMaskSamples << " bits per texel, so this light's "
                                         << "shadows use naive visibility (slower); set at most "
                                         << maxMaskSamples << " samples to keep it incremental");
    }
    if (voxels && this->Visibility == VisibilityIncremental && count <= maxMaskSamples)
    {
      double w2v[16];
      float worldToView[16];
      voxels->GetLastWorldToView(w2v);
      std::copy(w2v, w2v + 16, worldToView);
      if (this->VisibilityPyramid->Update(
            renWin, buffer, voxels, texture, count, uniforms.two_sided != 0, worldToView, timer))
      {
        masks = this->VisibilityPyramid;
      }
    }
    vtkMRGIAreaLightTerm term;
    term.Samples = texture;
    term.SampleCount = count;
    term.Light = &uniforms;
    term.Voxels = masks ? nullptr : voxels;
    term.Masks = masks;
    if (!this->RenderDiffuse(frame, buffer, term))
    {
      break;
    }
    this->Add(frame, this->DirectTexture, this->SumTexture);
    if (frame.Specular && this->RenderSpecular(frame, buffer, light, voxels, masks))
    {
      this->Add(frame, this->DirectTexture, this->SumTexture);
    }
    drawn = true;
  }
  // The lights' sum (what GetAreaLightBuffer() reads) joins the image once.
  if (drawn)
  {
    this->Add(frame, this->SumTexture, color);
    this->Signature = signature;
    ++this->NumberOfUpdates;
  }
  return drawn;
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLightStage::RenderDiffuse(
  const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer, const vtkMRGIAreaLightTerm& term)
{
  // NPW10 3.2 (the same multiresolution framework as the indirect light),
  // visibility 3.3.1 (voxels: a march per texel and sample) or 3.3.2 (the
  // masks); with masks, 3.4's incremental stencil chooses the texels.
  vtkMRGIVisibilityPyramid* masks = term.Masks;
  vtkTextureObject* stencil = buffer->GetStencilTexture();
  vtkTextureObject* rendered = buffer->GetSelectionTexture();
  if (masks && this->IncrementalStencil)
  {
    if (!this->IncrementalStencilStage->Build(frame, buffer, masks, term.Light))
    {
      return false;
    }
    stencil = this->IncrementalStencilStage->GetStencilTexture();
    rendered = this->IncrementalStencilStage->GetSelectionTexture();
    this->IncrementalStencilUsed = true;
  }
  // Surface-detail modulation (nichols-wyman-2009 eq. 2) is for indirect
  // light; direct light is resolved without it.
  return this->Gather->GatherAreaLight(frame, buffer, term, stencil) &&
    this->Upsample->Upsample(frame, buffer, this->Gather->GetIrradianceTexture(), rendered,
      this->UpsampleMode, this->UpsampleMaskWeight) &&
    this->Upsample->Resolve(
      frame, buffer, frame.Albedo, this->IrradianceTexture, this->DirectTexture, 1.0, 0.0);
}

//------------------------------------------------------------------------------
std::string vtkMRGIAreaLightStage::Inputs(
  const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer)
{
  vtkOpenGLRenderWindow* renWin = frame.Window;
  vtkRenderer* renderer = frame.Renderer;
  // Everything the area lights' sum is computed from, as modification
  // times: the camera and viewport (the G-buffer), the visible props and
  // their data (an actor's matrix, property, texture, mapper and input;
  // other props' GetRedrawMTime()), each light and its picture (asking for its
  // samples rebuilds them when the picture changed), and the settings of
  // the pass and of its stages. Empty: do not reuse.
  if (!this->Reuse || this->Gather->GetCollectStatistics() ||
    this->VisibilityPyramid->GetCollectStatistics())
  {
    return std::string();
  }
  std::ostringstream s;
  vtkCamera* camera = renderer->GetActiveCamera();
  s << camera << ':' << camera->GetMTime() << ';' << renderer->GetMTime() << ';';
  for (int k = 0; k < 4; ++k)
  {
    s << frame.Viewport[k] << ',';
  }
  s << frame.Position->GetWidth() << 'x' << frame.Position->GetHeight() << ';'
    << (frame.Specular != nullptr) << frame.Parallel << ';' << this->GetMTime() << ','
    << buffer->GetMTime() << ',' << this->VisibilityPyramid->GetMTime() << ','
    << this->Voxelization->GetMTime() << ',' << this->VarianceShadowQuery->GetMTime() << ','
    << this->Gather->GetMTime() << ',' << this->IncrementalStencilStage->GetMTime() << ','
    << this->SpecularStencilStage->GetMTime() << ';';
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (!prop->GetVisibility())
    {
      continue;
    }
    vtkActor* actor = vtkActor::SafeDownCast(prop);
    if (!actor)
    {
      s << prop << ':' << prop->GetRedrawMTime() << ';';
      continue;
    }
    // An actor by what it draws rather than its own MTime, which VTK's
    // mappers bump when they first give it a shader property (after this
    // frame's signature: the next frame would recompute for nothing).
    s << actor << ':';
    vtkMatrix4x4* matrix = actor->GetMatrix();
    for (int k = 0; k < 16; ++k)
    {
      s << matrix->GetElement(k / 4, k % 4) << ',';
    }
    s << actor->GetProperty()->GetMTime() << ','
      << (actor->GetBackfaceProperty() ? actor->GetBackfaceProperty()->GetMTime() : 0) << ','
      << (actor->GetTexture() ? actor->GetTexture()->GetMTime() : 0) << ',';
    if (vtkMapper* mapper = actor->GetMapper())
    {
      vtkDataObject* input = mapper->GetInputDataObject(0, 0);
      s << mapper->GetMTime() << ',' << (input ? input->GetMTime() : 0);
    }
    s << ';';
  }
  for (vtkMRGIAreaLight* light : this->Lights)
  {
    int count = 0;
    light->GetSampleTexture(renWin, &count);
    s << light << ':' << light->GetMTime() << ',' << light->GetNumberOfTextureBuilds() << ','
      << light->GetNumberOfSampleBuilds() << ';';
  }
  return s.str();
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLightStage::RenderSpecular(const vtkMRGIFrameContext& frame,
  vtkMRGIMultiresolution* buffer, vtkMRGIAreaLight* light, vtkMRGIVoxelization* voxels,
  vtkMRGIVisibilityPyramid* masks)
{
  vtkOpenGLRenderWindow* renWin = frame.Window;
  vtkRenderTimerLog* timer = frame.Timer;
  float* viewToWorld = const_cast<float*>(frame.ViewToWorld);
  // nichols-penmatsa-wyman-2010 3.2.1 (the highlight, its own pass) and
  // 3.3.3 (its shadows): with visibility, each sample's term of a glossy
  // lobe counts where the sample is visible (the level-0 bit of the
  // incremental masks, or a march per sample: the naive query, in batches
  // that fit llvmpipe's loop budget), and each lobe-grid cell of a sharp
  // lobe is weighted by the variance shadow query (its moments pass first).
  vtkMRGIShaderUtilities::ScopedStage step(timer, "specular");
  bool shadowed = voxels != nullptr;
  if (shadowed)
  {
    shadowed = this->VarianceShadowQuery->ComputeMoments(frame, light, voxels);
    if (!shadowed)
    {
      vtkErrorMacro("area lights: no variance shadow query; drawing the highlights without shadows");
    }
  }
  if (this->SpecularResolution == SpecularMultiresolution)
  {
    return this->RenderSpecularMultiresolution(frame, buffer, light, voxels, masks, shadowed);
  }
  const bool masked = shadowed && masks != nullptr;
  const bool marched = shadowed && !masked;
  vtkOpenGLQuadHelper* quad = ReadySpecular(this->Internal->GL.Programs, renWin, false, masked, marched);
  vtkShaderProgram* program = quad ? quad->Program : nullptr;
  if (!program)
  {
    vtkErrorMacro("could not build the area-light specular shader");
    return false;
  }
  int sampleCount = 0;
  if (!light->SetShaderUniforms(program, renWin) || !light->GetSampleTexture(renWin, &sampleCount))
  {
    return false;
  }
  // Texture units: the G-buffer's 4, the light's 2, and with shadows the
  // moments' 3 and the masks' (up to 4) or the voxels (1): 13 at most.
  std::vector<vtkTextureObject*> active;
  if (shadowed)
  {
    const int origin[2] = { frame.Viewport[0], frame.Viewport[1] };
    program->SetUniform2i("mrgiViewportOrigin", origin);
    this->VarianceShadowQuery->SetResolveUniforms(program);
    if (masked)
    {
      // Level 0 of the pyramid is the viewport at full resolution; missing
      // words (fewer than 384 samples) read the first texture: their bits
      // are never asked for.
      vtkTextureObject* first = masks->GetMaskTexture(0, 0);
      first->Activate();
      active.push_back(first);
      for (int w = 0; w < 4; ++w)
      {
        vtkTextureObject* t = masks->GetMaskTexture(0, w);
        if (t && t != first)
        {
          t->Activate();
          active.push_back(t);
        }
        program->SetUniformi(("mrgiVisibilityMask" + std::to_string(w)).c_str(),
          (t ? t : first)->GetTextureUnit());
      }
    }
    else
    {
      double w2v[16];
      voxels->GetLastWorldToView(w2v);
      float worldToView[16];
      std::copy(w2v, w2v + 16, worldToView);
      program->SetUniformMatrix4x4("mrgiWCToVC", worldToView);
      if (!voxels->SetMarchUniforms(program))
      {
        this->VarianceShadowQuery->DeactivateTextures();
        light->DeactivateTextures();
        return false;
      }
      active.push_back(voxels->GetVoxelTexture());
    }
  }
  vtkOpenGLFramebufferObject* fbo = this->Internal->GL.FrameBuffer;
  vtkOpenGLState* ostate = renWin->GetState();
  vtkMRGIViewportStep state(ostate, frame.Viewport);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->AddColorAttachment(0, this->DirectTexture);
  vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, 1);
  vtkTextureObject* inputs[4] = { frame.Position, frame.Normal, frame.Specular,
    frame.Shininess };
  const char* names[4] = { "mrgiPosition", "mrgiNormal", "mrgiSpecular", "mrgiShininess" };
  for (int k = 0; k < 4; ++k)
  {
    inputs[k]->Activate();
    program->SetUniformi(names[k], inputs[k]->GetTextureUnit());
  }
  program->SetUniformMatrix4x4("mrgiVCToWC", viewToWorld);
  program->SetUniformi("mrgiParallel", frame.Parallel ? 1 : 0);
  if (marched)
  {
    // One march per sample and pixel can run past the loop iterations
    // llvmpipe gives one invocation (mrgi_voxel_march.h): batches of
    // samples, one draw each, added to the first.
    RenderSampleBatches(ostate, program, quad, sampleCount,
      mrgi_voxel_samples_per_batch(voxels->GetMarchStepBound()));
  }
  else
  {
    quad->Render();
  }
  for (vtkTextureObject* t : inputs)
  {
    t->Deactivate();
  }
  for (vtkTextureObject* t : active)
  {
    t->Deactivate();
  }
  if (shadowed)
  {
    this->VarianceShadowQuery->DeactivateTextures();
  }
  light->DeactivateTextures();
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLightStage::RenderSpecularMultiresolution(const vtkMRGIFrameContext& frame,
  vtkMRGIMultiresolution* buffer, vtkMRGIAreaLight* light, vtkMRGIVoxelization* voxels,
  vtkMRGIVisibilityPyramid* masks, bool shadowed)
{
  vtkOpenGLRenderWindow* renWin = frame.Window;
  float* viewToWorld = const_cast<float*>(frame.ViewToWorld);
  // nichols-penmatsa-wyman-2010 3.2.1: the highlight gathered at the texels
  // of the specular stencil (this frame's multiresolution selection plus
  // the lobe-size metric, texels without specular material skipped;
  // mrgi_specular_stencil.h), then upsampled and resolved like the diffuse
  // term, the resolve's "albedo" being k_s c_s. Shadows (3.3.3): the
  // sample path reads the level's incremental masks (3.3.2, every level
  // has them) or marches at the texel's receiver (naive visibility, in
  // batches); the lobe grid reads the variance shadow query at the
  // footprint's centre pixel.
  mrgi_area_light_uniforms uniforms;
  mrgi_multires_layout layout;
  int sampleCount = 0;
  if (!light->GetCoreUniforms(&uniforms) || !light->GetSampleTexture(renWin, &sampleCount) ||
    !buffer->GetLayout(&layout) || !this->SpecularStencilStage->Build(frame, buffer, uniforms))
  {
    return false;
  }
  const bool masked = shadowed && masks != nullptr &&
    masks->GetNumberOfLevels() == layout.level_count;
  const bool marched = shadowed && !masked;
  vtkOpenGLQuadHelper* quad = ReadySpecular(this->Internal->GL.Programs, renWin, true, masked, marched);
  vtkShaderProgram* program = quad ? quad->Program : nullptr;
  if (!program || !light->SetShaderUniforms(program, renWin))
  {
    vtkErrorMacro("could not build the multiresolution area-light specular shader");
    return false;
  }
  // Texture units: receivers 2, material 1, the light's 2, and with shadows
  // the moments' 3 and the masks' (up to 4) or the voxels (1): 12 at most.
  std::vector<vtkTextureObject*> active;
  bool ok = true;
  if (shadowed)
  {
    const int size[2] = { frame.Viewport[2], frame.Viewport[3] };
    program->SetUniform2i("mrgiViewportSize", size);
    this->VarianceShadowQuery->SetResolveUniforms(program);
    if (marched)
    {
      double w2v[16];
      voxels->GetLastWorldToView(w2v);
      float worldToView[16];
      std::copy(w2v, w2v + 16, worldToView);
      program->SetUniformMatrix4x4("mrgiWCToVC", worldToView);
      ok = voxels->SetMarchUniforms(program);
      active.push_back(voxels->GetVoxelTexture());
    }
  }
  program->SetUniformMatrix4x4("mrgiVCToWC", viewToWorld);
  program->SetUniformi("mrgiParallel", frame.Parallel ? 1 : 0);
  const int batch = marched ? mrgi_voxel_samples_per_batch(voxels->GetMarchStepBound()) : sampleCount;
  auto draw = [&](int level) -> bool {
    std::vector<vtkTextureObject*> levelMasks;
    if (masked)
    {
      // The level's masks, level-local texels (as the diffuse gather's).
      vtkTextureObject* first = masks->GetMaskTexture(level, 0);
      if (!first)
      {
        return false;
      }
      first->Activate();
      levelMasks.push_back(first);
      for (int w = 0; w < 4; ++w)
      {
        vtkTextureObject* t = masks->GetMaskTexture(level, w);
        if (t && t != first)
        {
          t->Activate();
          levelMasks.push_back(t);
        }
        program->SetUniformi(("mrgiVisibilityMask" + std::to_string(w)).c_str(),
          (t ? t : first)->GetTextureUnit());
      }
    }
    if (shadowed)
    {
      const int origin[2] = { layout.level_offset[level], 0 };
      program->SetUniform2i("mrgiViewportOrigin", origin);
    }
    if (marched)
    {
      RenderSampleBatches(renWin->GetState(), program, quad, sampleCount, batch);
    }
    else
    {
      quad->Render();
    }
    for (vtkTextureObject* t : levelMasks)
    {
      t->Deactivate();
    }
    return true;
  };
  ok = ok && this->Gather->GatherSpecular(frame, buffer, this->SpecularStencilStage, program, draw);
  for (vtkTextureObject* t : active)
  {
    t->Deactivate();
  }
  if (shadowed)
  {
    this->VarianceShadowQuery->DeactivateTextures();
  }
  light->DeactivateTextures();
  // Upsampled S times each pixel's k_s c_s (the resolve's albedo) into
  // AreaDirectTexture; the irradiance output is scratch.
  return ok &&
    this->Upsample->Upsample(frame, buffer, this->Gather->GetIrradianceTexture(),
      this->SpecularStencilStage->GetSelectionTexture(), this->UpsampleMode, this->UpsampleMaskWeight) &&
    this->Upsample->Resolve(
      frame, buffer, frame.Specular, this->IrradianceTexture, this->DirectTexture, 1.0, 0.0);
}

//------------------------------------------------------------------------------
bool vtkMRGIAreaLightStage::Add(
  const vtkMRGIFrameContext& frame, vtkTextureObject* source, vtkTextureObject* target)
{
  if (!vtkMRGIFullScreenStep::AddRGB(
        frame.Window, this->Internal->GL.Programs, this->Internal->GL.FrameBuffer, frame.Viewport, source, target))
  {
    vtkErrorMacro("could not build the MRGI composite shader");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLightStage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Lights: " << this->Lights.size() << "\n";
  os << indent << "Visibility: "
     << (this->Visibility == VisibilityIncremental ? "Incremental"
          : this->Visibility == VisibilityNaive    ? "Naive"
                                                   : "Off")
     << "\n";
  os << indent << "Specular: " << (this->Specular ? "On" : "Off") << "\n";
  os << indent << "SpecularResolution: "
     << (this->SpecularResolution == SpecularMultiresolution ? "Multiresolution" : "FullResolution") << "\n";
  os << indent << "IncrementalStencil: " << (this->IncrementalStencil ? "On" : "Off") << "\n";
  os << indent << "Reuse: " << (this->Reuse ? "On" : "Off") << "\n";
  os << indent << "NumberOfUpdates: " << this->NumberOfUpdates << "\n";
  os << indent << "Voxelization:\n";
  this->Voxelization->PrintSelf(os, indent.GetNextIndent());
  os << indent << "VisibilityPyramid:\n";
  this->VisibilityPyramid->PrintSelf(os, indent.GetNextIndent());
  os << indent << "VarianceShadowQuery:\n";
  this->VarianceShadowQuery->PrintSelf(os, indent.GetNextIndent());
  os << indent << "IncrementalStencilStage:\n";
  this->IncrementalStencilStage->PrintSelf(os, indent.GetNextIndent());
  os << indent << "SpecularStencilStage:\n";
  this->SpecularStencilStage->PrintSelf(os, indent.GetNextIndent());
}
