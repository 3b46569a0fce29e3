/**
 * @class   vtkMRGIAreaLightStage
 * @brief   The direct light of vtkMRGIAreaLight rectangles
 *          (nichols-penmatsa-wyman-2010) for vtkMRGIPass: diffuse gather at
 *          the multiresolution texels, shadows from a screen-space
 *          voxelization, Phong highlights, and reuse of an unchanged frame.
 *
 * Per frame, given the frame's G-buffer (vtkMRGIFrameContext) and the
 * multiresolution buffer (its selection made here when the indirect light
 * did not make it this frame):
 * 1. "voxelize": with visibility on, the visible scene is voxelized once for
 *    every light (vtkMRGIVoxelization, 3.3);
 * 2. per light, "visibility.pyramid": with incremental visibility, the
 *    light's visibility masks over every level (vtkMRGIVisibilityPyramid,
 *    3.3.2) and the incremental stencil (vtkMRGIIncrementalStencil, 3.4);
 * 3. "gather.samples": the light's samples gathered at the selected texels
 *    (vtkMRGIGather, 3.2), upsampled and resolved to albedo x X
 *    (vtkMRGIUpsample);
 * 4. "specular": with specular props, the light's Phong highlight (3.2.1),
 *    at every pixel or at the texels of the specular stencil
 *    (vtkMRGISpecularStencil), shadowed (3.3.3, vtkMRGIVarianceShadowQuery);
 * 5. each light is added to the lights' sum, and the sum to the image once.
 *
 * When nothing the sum depends on changed since it was computed (camera,
 * viewport, visible props and their data, the lights and their pictures,
 * every setting), the sum is added again instead ("buffers are not
 * re-rendered when their inputs did not change"); Reuse off, or statistics
 * collection, computes every frame.
 *
 * The stage owns its textures, programs and stages; vtkMRGIPass owns the
 * stage and forwards its area-light API to it.
 */
#ifndef vtkMRGIAreaLightStage_h
#define vtkMRGIAreaLightStage_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr
#include <string> // For std::string
#include <vector> // For std::vector

struct vtkMRGIAreaLightTerm;
struct vtkMRGIFrameContext;
class vtkMRGIAreaLight;
class vtkMRGIGather;
class vtkMRGIIncrementalStencil;
class vtkMRGIMultiresolution;
class vtkMRGIRSMCompositor;
class vtkMRGISpecularStencil;
class vtkMRGIUpsample;
class vtkMRGIVarianceShadowQuery;
class vtkMRGIVisibilityPyramid;
class vtkMRGIVoxelization;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIAreaLightStage : public vtkObject
{
public:
  static vtkMRGIAreaLightStage* New();
  vtkTypeMacro(vtkMRGIAreaLightStage, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The lights (registered; each owns its GPU sample and picture textures). */
  void AddLight(vtkMRGIAreaLight* light);
  void RemoveLight(vtkMRGIAreaLight* light);
  void RemoveAllLights();
  int GetNumberOfLights() const;
  vtkMRGIAreaLight* GetLight(int index) const;
  ///@}

  enum VisibilityModes
  {
    VisibilityOff = 0,        ///< no shadows (NPW10 3.2)
    VisibilityNaive = 1,      ///< a voxel march per texel and light sample (NPW10 3.3.1)
    VisibilityIncremental = 2 ///< coarse to fine, reusing agreeing coarse bits (NPW10 3.3.2; default)
  };

  ///@{
  /** Shadows (see vtkMRGIPass::SetAreaLightVisibility()). */
  vtkSetClampMacro(Visibility, int, VisibilityOff, VisibilityIncremental);
  vtkGetMacro(Visibility, int);
  ///@}

  ///@{
  /** Phong highlights on props with a vtkProperty Specular > 0 (default on). */
  vtkSetMacro(Specular, bool);
  vtkGetMacro(Specular, bool);
  vtkBooleanMacro(Specular, bool);
  ///@}

  enum SpecularResolutions
  {
    SpecularFullResolution = 0, ///< every pixel gathers its highlight (default)
    SpecularMultiresolution = 1 ///< stenciled multiresolution gather refined by lobe size (NPW10 3.2.1)
  };

  ///@{
  /** Where highlights are gathered (see vtkMRGIPass::SetAreaLightSpecularResolution()). */
  vtkSetClampMacro(SpecularResolution, int, SpecularFullResolution, SpecularMultiresolution);
  vtkGetMacro(SpecularResolution, int);
  ///@}

  ///@{
  /**
   * Incremental stencil rendering (NPW10 3.4) with incremental visibility
   * (default on): the diffuse gather also renders texels below the
   * geometric selection where the coarser masks disagree
   * (GetIncrementalStencilStage() holds the threshold). Off: the geometric
   * selection alone.
   */
  vtkSetMacro(IncrementalStencil, bool);
  vtkGetMacro(IncrementalStencil, bool);
  vtkBooleanMacro(IncrementalStencil, bool);
  ///@}

  ///@{
  /** Reuse an unchanged frame's sum (default on; off in benchmarks). */
  vtkSetMacro(Reuse, bool);
  vtkGetMacro(Reuse, bool);
  vtkBooleanMacro(Reuse, bool);
  ///@}

  ///@{
  /** Upsampling of the gathers: vtkMRGIUpsample::UpsampleTent (default) or UpsampleMaskWeighted, and its weight. */
  vtkSetClampMacro(UpsampleMode, int, 0, 1);
  vtkGetMacro(UpsampleMode, int);
  vtkSetClampMacro(UpsampleMaskWeight, double, 1.0, 1e6);
  vtkGetMacro(UpsampleMaskWeight, double);
  ///@}

  /** How many frames computed the lights (the others reused the sum). */
  vtkGetMacro(NumberOfUpdates, vtkIdType);

  ///@{
  /** The stages, for their settings, statistics and read-backs. */
  vtkMRGIVoxelization* GetVoxelization() { return this->Voxelization; }
  vtkMRGIVisibilityPyramid* GetVisibilityPyramid() { return this->VisibilityPyramid; }
  vtkMRGIVarianceShadowQuery* GetVarianceShadowQuery() { return this->VarianceShadowQuery; }
  vtkMRGIGather* GetGather() { return this->Gather; }
  vtkMRGIUpsample* GetUpsample() { return this->Upsample; }
  vtkMRGIIncrementalStencil* GetIncrementalStencilStage() { return this->IncrementalStencilStage; }
  vtkMRGISpecularStencil* GetSpecularStencilStage() { return this->SpecularStencilStage; }
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Draw every light's direct light and add the lights' sum to `color`
   * (window-sized, like the frame's G-buffer) over the frame's viewport.
   * `selected`: `buffer` holds this frame's selection already (the
   * indirect light made it); otherwise it is made here. Timed as the stage
   * "area". False when no light was drawn.
   */
  bool Render(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer, bool selected,
    vtkTextureObject* color);
#endif

  /** The lights' sum of the last frame that drew them (RGB float, window-sized); null before. */
  vtkTextureObject* GetSumTexture() const { return this->SumTexture; }

  /** Whether the last frame's diffuse gathers used the incremental stencil. */
  vtkGetMacro(IncrementalStencilUsed, bool);

  /** Free every GL resource (the lights' too). */
  void ReleaseGraphicsResources(vtkWindow* w);

  ///@{
  /**
   * Distributed rendering: with a compositor of more than one process, the
   * processes decide together whether the lights' sum is reused (any
   * process's change recomputes it on all) and OR their voxelizations, so
   * that geometry on any process shadows the area lights on every process.
   * Render() is then collective. Set by vtkMRGIPass::SetRSMCompositor().
   */
  virtual void SetCompositor(vtkMRGIRSMCompositor* compositor);
  vtkGetObjectMacro(Compositor, vtkMRGIRSMCompositor);
  ///@}

protected:
  vtkMRGIAreaLightStage();
  ~vtkMRGIAreaLightStage() override;

#ifndef __VTK_WRAP__
  // What the lights' sum depends on; empty when it must be computed anyway.
  std::string Inputs(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer);
  // One light's diffuse term (its samples, uniforms and visibility) into
  // DirectTexture.
  bool RenderDiffuse(
    const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer, const vtkMRGIAreaLightTerm& term);
  // One light's highlight into DirectTexture: at every pixel, or at the
  // texels of the specular stencil (upsampled, times k_s c_s).
  bool RenderSpecular(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    vtkMRGIAreaLight* light, vtkMRGIVoxelization* voxels, vtkMRGIVisibilityPyramid* masks);
  bool RenderSpecularMultiresolution(const vtkMRGIFrameContext& frame,
    vtkMRGIMultiresolution* buffer, vtkMRGIAreaLight* light, vtkMRGIVoxelization* voxels,
    vtkMRGIVisibilityPyramid* masks, bool shadowed);
  // `source`'s RGB added to `target`'s over the frame's viewport.
  bool Add(const vtkMRGIFrameContext& frame, vtkTextureObject* source, vtkTextureObject* target);
#endif

  std::vector<vtkMRGIAreaLight*> Lights;
  int Visibility = VisibilityIncremental;
  bool Specular = true;
  int SpecularResolution = SpecularFullResolution;
  bool IncrementalStencil = true;
  bool Reuse = true;
  int UpsampleMode = 0;
  double UpsampleMaskWeight = 100.0;
  vtkIdType NumberOfUpdates = 0;
  bool IncrementalStencilUsed = false;
  // What the sum was computed from (empty: nothing cached).
  std::string Signature;

  vtkMRGIRSMCompositor* Compositor = nullptr;
  vtkMRGIVoxelization* Voxelization = nullptr;
  vtkMRGIVisibilityPyramid* VisibilityPyramid = nullptr;
  vtkMRGIVarianceShadowQuery* VarianceShadowQuery = nullptr;
  vtkMRGIGather* Gather = nullptr;
  vtkMRGIUpsample* Upsample = nullptr;
  vtkMRGIIncrementalStencil* IncrementalStencilStage = nullptr;
  vtkMRGISpecularStencil* SpecularStencilStage = nullptr;

  vtkTextureObject* IrradianceTexture = nullptr; // the resolves' E (scratch)
  vtkTextureObject* DirectTexture = nullptr;     // one light's term
  vtkTextureObject* SumTexture = nullptr;        // the lights' sum

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIAreaLightStage(const vtkMRGIAreaLightStage&) = delete;
  void operator=(const vtkMRGIAreaLightStage&) = delete;
};

#endif
