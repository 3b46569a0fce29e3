/**
 * @class   vtkMRGIGather
 * @brief   The stenciled multiresolution gather (nichols-shopf-wyman-2009
 *          3.2.2): every selected texel of a vtkMRGIMultiresolution buffer
 *          gathers the VPLs, or one area light's samples, into a flattened
 *          irradiance buffer.
 *
 * The texels and their receivers come from the buffer (Update() and
 * BuildReceivers() done this frame); which stencil selects the texels is an
 * argument (the buffer's selection, the incremental stencil of
 * vtkMRGIIncrementalStencil, or the specular stencil of
 * vtkMRGISpecularStencil), and so is the light term: VPLs (the VPL cache
 * texture) or an area light (vtkMRGIAreaLightTerm). One draw per level into
 * that level's rectangle of the flattened layout; early stencil culling
 * skips the texels not selected.
 *
 * C twins: the VPL gather is mrgi_gather_full() (mrgi_gather.h) on the same
 * receivers, the area-light term mrgi_area_light_diffuse()
 * (mrgi_area_light.h), its visibility mrgi_voxel_march() (naive) or the
 * incremental masks (mrgi_visibility_pyramid.h). Shaders:
 * vtkMRGIGatherFS.glsl with vtkMRGIVPLIrradiance.glsl and
 * vtkMRGIAreaLightDiffuse.glsl; multiresolution splatting
 * vtkMRGIMultiresSplat{VS,FS}.glsl.
 *
 * With CollectStatistics on, an occlusion query per level counts the
 * texels gathered (nichols-shopf-wyman-2009 table 1).
 */
#ifndef vtkMRGIGather_h
#define vtkMRGIGather_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <functional> // For std::function
#include <memory>     // For std::unique_ptr

struct mrgi_area_light_uniforms;
struct mrgi_multires_layout;
struct vtkMRGIFrameContext;
class vtkFloatArray;
class vtkMRGIMultiresolution;
class vtkMRGISpecularStencil;
class vtkMRGIVisibilityPyramid;
class vtkMRGIVoxelization;
class vtkOpenGLRenderWindow;
class vtkRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

#ifndef __VTK_WRAP__
/**
 * The light term of an area-light gather (nichols-penmatsa-wyman-2010 3.2):
 * its samples (MRGI_AREA_LIGHT_SAMPLE_TEXELS x SampleCount RGBA32F, the
 * core's mrgi_area_light_sample records), its uniforms
 * (mrgi_area_light_uniforms_init(), world space), and its visibility:
 * none; Voxels (voxelized this frame: each sample counts where the voxel
 * march finds it visible, 3.3.1); or Masks (updated this frame on this
 * selection: where the texel's bit of the incremental visibility is set,
 * 3.3.2).
 */
struct vtkMRGIAreaLightTerm
{
  vtkTextureObject* Samples = nullptr;
  int SampleCount = 0;
  const mrgi_area_light_uniforms* Light = nullptr;
  vtkMRGIVoxelization* Voxels = nullptr;
  vtkMRGIVisibilityPyramid* Masks = nullptr;
};
#endif

class MRGIRENDERING_EXPORT vtkMRGIGather : public vtkObject
{
public:
  static vtkMRGIGather* New();
  vtkTypeMacro(vtkMRGIGather, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum GatherModes
  {
    GatherStenciled = 0, ///< one draw per level, early stencil culling (default)
    GatherSplatting = 1  ///< multiresolution splatting, nichols-wyman-2009 3.4
  };

  ///@{
  /**
   * How GatherVPLs() computes the selected texels (the same numbers either
   * way): the stenciled gather of nichols-shopf-wyman-2009 section 3.2.2
   * (default), or the multiresolution splatting it replaced
   * (nichols-wyman-2009 section 3.4: every VPL draws one point per selected
   * texel, additive blending), kept so that the papers' comparison can be
   * repeated (Documentation/Multiresolution.md). Splatting reads the
   * selection back to build its subsplat list (timer step
   * "gather.subsplats"); the splats themselves are "gather.vpls", as the
   * stenciled gather's draws. Area lights are always gathered stenciled.
   */
  vtkSetClampMacro(GatherMode, int, GatherStenciled, GatherSplatting);
  vtkGetMacro(GatherMode, int);
  void SetGatherModeToStenciled() { this->SetGatherMode(GatherStenciled); }
  void SetGatherModeToSplatting() { this->SetGatherMode(GatherSplatting); }
  ///@}

  ///@{
  /**
   * Per-frame statistics (nichols-shopf-wyman-2009 table 1): with
   * CollectStatistics on, each gather counts the texels it gathers at each
   * level with occlusion queries and the valid pixels (the full-resolution
   * gather's work) from the coarsest receivers. Reading them waits for the
   * GPU, hence off by default.
   */
  vtkSetMacro(CollectStatistics, bool);
  vtkGetMacro(CollectStatistics, bool);
  vtkBooleanMacro(CollectStatistics, bool);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Gather `vplCount` VPLs (the VPL cache texture) at the texels the
   * buffer's selection selects (its receivers built this frame) into the
   * flattened irradiance buffer (E, RGB; 0 where nothing was selected).
   * Uses the frame's window, eye -> world matrix and timer ("gather.vpls").
   * False on error.
   */
  bool GatherVPLs(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    vtkTextureObject* vpls, int vplCount);

  /**
   * The full-resolution gather (vtkMRGIPass::IndirectFull, the reference
   * the multiresolution one approximates): every pixel of frame.Viewport
   * gathers all `vplCount` VPLs (nichols-shopf-wyman-2009 eq. 1 and 5)
   * from the frame's position, normal and albedo, writing E into
   * `irradiance` and strength x albedo x E into `indirect` (window-sized
   * textures, the viewport only). No timer step of its own. False (with an
   * error) on missing input or a program that does not build.
   */
  bool GatherFull(const vtkMRGIFrameContext& frame, vtkTextureObject* vpls, int vplCount,
    double strength, vtkTextureObject* irradiance, vtkTextureObject* indirect);

  /**
   * Gather the direct light of one area light (its term, see
   * vtkMRGIAreaLightTerm) at the texels `stencil` selects: the buffer's
   * selection (GetStencilTexture()) or the incremental stencil
   * (vtkMRGIIncrementalStencil). Timer step "gather.samples". False on
   * error.
   */
  bool GatherAreaLight(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    const vtkMRGIAreaLightTerm& term, vtkTextureObject* stencil);

  /**
   * The specular gather of an area light (NPW10 3.2.1) at the texels of
   * `stencil` (built this frame on this buffer), one level at a time from
   * the finest gathering level (timer step "gather.specular"). `program` is
   * the caller's (ready, its own uniforms and textures set); for each level
   * this binds the receivers (mrgiPosition, mrgiNormal, mrgiReceiverOffset
   * as the gather's), the level's material (mrgiMaterial: x max k_s, y the
   * largest exponent), mrgiLevelOrigin (the level's offset in the flattened
   * layout) and mrgiLevelScale (2^level), sets the viewport to the level and
   * calls `draw(level)`, which draws (and may bind per-level inputs).
   * False on error.
   */
  bool GatherSpecular(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    vtkMRGISpecularStencil* stencil, vtkShaderProgram* program,
    const std::function<bool(int level)>& draw);
#endif

  /** The flattened irradiance of the last gather (RGBA32F, the buffer's flattened layout); null before. */
  vtkTextureObject* GetIrradianceTexture() const;

  /** Read the flattened irradiance of the last gather back (RGBA floats). */
  bool ReadIrradiance(vtkRenderWindow* window, vtkFloatArray* irradiance);

  /** Texels gathered at `level` by the last gather; -1 when not counted. */
  vtkIdType GetNumberOfGatheredTexels(int level) const;

  /** Valid (non-background) pixels of the last gather; -1 when not counted. */
  vtkIdType GetNumberOfValidPixels() const;

  /**
   * Texels gathered at all levels over the valid pixels: the share of the
   * full-resolution gather's work done (each texel gathers every VPL once,
   * as each pixel does at full resolution); -1 when not counted.
   */
  double GetGatherWorkFraction() const;

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIGather();
  ~vtkMRGIGather() override;

  int GatherMode = GatherStenciled;
  bool CollectStatistics = false;

#ifndef __VTK_WRAP__
  // The flattened irradiance for `layout`; false, with an error, when it
  // cannot be allocated.
  bool PrepareTarget(vtkOpenGLRenderWindow* window, const mrgi_multires_layout& layout);
  // The gathers after their inputs are checked: the stenciled one (VPLs, or
  // the area light of `term`) and the splatting (VPLs only).
  bool Run(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer, vtkTextureObject* vpls,
    int vplCount, const vtkMRGIAreaLightTerm* term, vtkTextureObject* stencil);
  bool RunStenciled(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    const mrgi_multires_layout& layout, vtkTextureObject* vpls, int vplCount,
    const vtkMRGIAreaLightTerm* term, vtkTextureObject* stencil);
  bool RunSplatting(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    const mrgi_multires_layout& layout, vtkTextureObject* vpls, int vplCount);
#endif

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIGather(const vtkMRGIGather&) = delete;
  void operator=(const vtkMRGIGather&) = delete;
};

#endif
