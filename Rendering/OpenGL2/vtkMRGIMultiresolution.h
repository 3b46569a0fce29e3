/**
 * @class   vtkMRGIMultiresolution
 * @brief   The multiresolution gather on the GPU: selection of the texels
 *          that gather indirect light (min-max mipmaps of the G-buffer,
 *          discontinuity and refinement flags with the balance rule, the
 *          one-pass stencil selection of nichols-shopf-wyman-2009 section
 *          3.2.1), their receivers, and the stenciled gather.
 *
 * The layout, the metrics, the thresholds and the rules are those of the C
 * core (mrgi_multires.h), which this class mirrors pass for pass: one pass
 * for level 0 of the mipmaps, one per coarser level (2x2 reduction), one per
 * level for the flags (fine to coarse, since refinement and the balance rule
 * look at the finer level), and the one-pass stencil selection, drawn once
 * per level into that level's rectangle of the flattened layout (no search
 * for the level per fragment, nothing drawn where no level lies). Mipmap and
 * flag levels live in separate textures: reading and writing one texture is
 * a feedback loop in OpenGL 3.2.
 *
 * The stencil lives in a depth-stencil texture attached at
 * GL_DEPTH_STENCIL_ATTACHMENT by hand (VTK 9.1's framebuffer object attaches
 * depth-stencil textures at GL_DEPTH_ATTACHMENT only).
 *
 * Gather(): the receivers of every texel (mean position and normal of its
 * pixels, mrgi_multires_receivers.h) are built level by level (level 1
 * straight from the G-buffer; level 0 is the G-buffer), then the gather is
 * drawn once per level into the flattened irradiance buffer, reading that
 * level's receivers; early stencil culling skips the texels not selected.
 * The gather is vtkMRGIGatherFS.glsl, whose C twin is mrgi_gather_full() on
 * the same receivers. With CollectStatistics on, an occlusion query per
 * level counts the texels gathered.
 *
 * Upsample(): coarse to fine, one pass per level for the state and value of
 * each texel and one for the tent (or mask-weighted) filter
 * (mrgi_upsample.h); Resolve() writes the full-resolution E and
 * strength x albedo x E where vtkMRGIPass composites them.
 */
#ifndef vtkMRGIMultiresolution_h
#define vtkMRGIMultiresolution_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <functional> // For std::function
#include <memory>     // For std::unique_ptr

struct mrgi_area_light_uniforms;
struct mrgi_multires_layout;
class vtkMRGIVisibilityPyramid;
class vtkMRGIVoxelization;
class vtkFloatArray;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkRenderTimerLog;
class vtkRenderWindow;
class vtkTextureObject;
class vtkUnsignedCharArray;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIMultiresolution : public vtkObject
{
public:
  static vtkMRGIMultiresolution* New();
  vtkTypeMacro(vtkMRGIMultiresolution, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Presets
  {
    PresetFast = 0,     ///< finest level 1: ~4% from the full gather, gather ~16x cheaper
    PresetBalanced = 1, ///< the cheapest measured within 3% of the full gather (default)
    PresetAccurate = 2  ///< the most accurate measured (~2%)
  };

  /**
   * Apply a preset (mrgi_multires_preset_params: thresholds and finest level
   * chosen from the measured frontier, Documentation/Multiresolution.md;
   * balance on). A new object starts with Balanced. False (nothing changed)
   * for an unknown preset.
   */
  bool SetPreset(int preset);

  /**
   * A preset's settings without applying it: depth threshold, normal
   * threshold (-1: off) and finest level. False for an unknown preset.
   */
  static bool GetPresetSettings(int preset, double settings[3]);

  /** "fast", "balanced", "accurate"; nullptr for an unknown preset. */
  static const char* GetPresetName(int preset);

  ///@{
  /**
   * Thresholds (mrgi_multires.h section 3; +inf or a negative value: off).
   * Depth: depth change per pixel width in a texel's 3x3 window; normal:
   * spread of a unit-normal component. Defaults: the Balanced preset.
   */
  vtkSetMacro(DepthThreshold, double);
  vtkGetMacro(DepthThreshold, double);
  vtkSetMacro(NormalThreshold, double);
  vtkGetMacro(NormalThreshold, double);
  ///@}

  ///@{
  /** Finest level that gathers (0 = full resolution). Clamped to the levels there are. */
  vtkSetClampMacro(FinestLevel, int, 0, 23);
  vtkGetMacro(FinestLevel, int);
  ///@}

  ///@{
  /** Neighbouring selected texels differ by at most one level (default on). */
  vtkSetMacro(Balance, bool);
  vtkGetMacro(Balance, bool);
  vtkBooleanMacro(Balance, bool);
  ///@}

  ///@{
  /** Side of the coarsest level: levels stop when both sides are <= this (default 16). */
  vtkSetClampMacro(CoarsestSide, int, 1, 4096);
  vtkGetMacro(CoarsestSide, int);
  ///@}

  /**
   * Select from a G-buffer (eye-space position and normal textures, as
   * vtkMRGIPass captures them) whose pixel (0, 0) is texel (x0, y0); the
   * image is width x height. Pixel size at depth d is max(a |d| + b, tiny)
   * (mrgi_multires_pixel_size_coefficients). False on error.
   */
  bool Update(vtkOpenGLRenderWindow* window, vtkTextureObject* position,
    vtkTextureObject* normal, int x0, int y0, int width, int height, double a, double b);

  /** Flattened layout size of the last Update(). */
  int GetFlattenedWidth() const;
  int GetFlattenedHeight() const;
  int GetNumberOfLevels() const;

  /** Size of `level` in the last Update(); false (size untouched) when there is no such level. */
  bool GetLevelSize(int level, int size[2]) const;

  /**
   * Read the selection back: one byte per flattened texel, 1 where the
   * stencil is set. `fromStencil` reads the stencil itself, otherwise the
   * colour the selection pass wrote with it.
   */
  bool ReadSelection(vtkRenderWindow* window, vtkUnsignedCharArray* mask, bool fromStencil);

  /**
   * After Update(): gather `vplCount` VPLs (the VPL cache texture) at the
   * selected texels into the flattened irradiance buffer (E, RGB; 0 where
   * nothing was selected). `viewToWorld` is the column-major eye -> world
   * matrix. False on error.
   */
  bool Gather(vtkOpenGLRenderWindow* window, vtkTextureObject* position, vtkTextureObject* normal,
    int x0, int y0, vtkTextureObject* vpls, int vplCount, const float viewToWorld[16]);

#ifndef __VTK_WRAP__
  /**
   * After Update(): gather the direct light of one area light instead of
   * the VPLs (nichols-penmatsa-wyman-2010 section 3.2, no visibility): its
   * samples texture (MRGI_AREA_LIGHT_SAMPLE_TEXELS x sampleCount RGBA32F,
   * the core's mrgi_area_light_sample records) and its uniforms
   * (mrgi_area_light_uniforms_init(), world space). The same receivers and
   * selection; always the stenciled gather (timer step "gather.samples").
   * Upsample() and Resolve() then work as after Gather(). C twin:
   * mrgi_area_light_diffuse(). With `visibility` (voxelized this frame),
   * each sample counts only where the voxel march (3.3.1, the naive query:
   * one march per texel and sample; vtkMRGIVoxelMarch.glsl, C twin
   * mrgi_voxel_march()) finds it visible; with `masks` (Update()d this frame
   * on this selection), where the texel's bit of the incremental visibility
   * (3.3.2) is set, and, with IncrementalStencil on, at the texels of the
   * incremental stencil (3.4) instead of the selection.
   */
  bool GatherAreaLight(vtkOpenGLRenderWindow* window, vtkTextureObject* position,
    vtkTextureObject* normal, int x0, int y0, vtkTextureObject* samples, int sampleCount,
    const mrgi_area_light_uniforms& light, const float viewToWorld[16],
    vtkMRGIVoxelization* visibility = nullptr, vtkMRGIVisibilityPyramid* masks = nullptr);
#endif

  ///@{
  /**
   * Incremental stencil rendering for area lights with visibility masks
   * (nichols-penmatsa-wyman-2010 section 3.4; C twin and contract:
   * mrgi_incremental_stencil_build() in Rendering/Core/
   * mrgi_incremental_stencil.h). On (the default), GatherAreaLight() with
   * masks also renders a texel below the geometric selection when its
   * parent's 3x3 masks disagree on at least ceil(IncrementalStencilFraction
   * N) of the N samples (the masks' refinement metric), so that penumbrae
   * are gathered at the resolution the shadow needs instead of the coarse
   * texel the flat geometry asks for; Upsample() then interpolates from the
   * finest rendered texel. Off: the geometric selection alone.
   */
  vtkSetMacro(IncrementalStencil, bool);
  vtkGetMacro(IncrementalStencil, bool);
  vtkBooleanMacro(IncrementalStencil, bool);
  vtkSetClampMacro(IncrementalStencilFraction, double, 0.0, 1.0);
  vtkGetMacro(IncrementalStencilFraction, double);
  ///@}

  ///@{
  /**
   * The lobe-size refinement metric of the multiresolution specular gather
   * (nichols-penmatsa-wyman-2010 3.2.1, "image-space sample spacing must be
   * denser than the lobe width"; mrgi_specular_stencil.h). On (default):
   * BuildSpecularStencil() also refines a texel whose Phong lobe is
   * narrower than its spacing (m > 1). Off: the geometric refinement and
   * mixed exponents alone (for comparisons and tests).
   */
  vtkSetMacro(SpecularLobeRefinement, bool);
  vtkGetMacro(SpecularLobeRefinement, bool);
  vtkBooleanMacro(SpecularLobeRefinement, bool);
  /**
   * Refine where the lobe metric m exceeds this (> 0). 1 is NPW10's
   * "spacing denser than the lobe width"; smaller values refine earlier
   * (several samples across a lobe). Default 0.125: measured at 256^2
   * against the full-resolution highlight (k_s 0.5, exponents 40 / 120),
   * 1 left 21% / 34% relative RMS on the Cornell box (the metric hardly
   * fired on its 16-pixel wall texels), 0.25 18% / 11%, 0.125 7% / 4%
   * (living room 2-3% at every value), at the same cost.
   */
  vtkSetClampMacro(SpecularLobeThreshold, double, 1e-3, 1e3);
  vtkGetMacro(SpecularLobeThreshold, double);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * After Update() (and this frame's receivers, built here when missing):
   * the stencil of the multiresolution specular gather of one area light
   * (NPW10 3.2.1 and 3.4; C twin and contract: mrgi_specular_stencil.h).
   * Builds the material pyramid (max k_s, max and min Phong exponent per
   * texel) from the specular G-buffer targets, the refinement bits (the
   * geometric REFINE flag, mixed exponents and the lobe metric) and the
   * selection (texels with specular material only), with its stencil.
   * Timer step "select.specular". False on error.
   */
  bool BuildSpecularStencil(vtkOpenGLRenderWindow* window, vtkTextureObject* position,
    vtkTextureObject* normal, vtkTextureObject* specular, vtkTextureObject* shininess, int x0,
    int y0, const mrgi_area_light_uniforms& light, const float viewToWorld[16], bool parallel);

  /**
   * After BuildSpecularStencil(): the stenciled specular gather into the
   * flattened irradiance buffer, one level at a time from the finest
   * gathering level (timer step "gather.specular"). `program` is the
   * caller's (ready, its own uniforms and textures set); for each level this
   * binds the receivers (mrgiPosition, mrgiNormal, mrgiReceiverOffset as
   * the gather's), the level's material (mrgiMaterial: x max k_s, y the
   * largest exponent), mrgiLevelOrigin (the level's offset in the flattened
   * layout) and mrgiLevelScale (2^level), sets the viewport to the level and
   * calls `draw(level)`, which draws (and may bind per-level inputs).
   * Upsample() then reads the specular selection. False on error.
   */
  bool GatherAreaSpecular(vtkOpenGLRenderWindow* window, vtkTextureObject* position,
    vtkTextureObject* normal, int x0, int y0, vtkShaderProgram* program,
    const std::function<bool(int level)>& draw);
#endif

  /**
   * Read back the last BuildSpecularStencil(): the selection (1 = selected)
   * and the refinement bits (MRGI_SPECULAR_STENCIL_*), one byte per
   * flattened texel; `fromStencil` reads the selection from the stencil.
   * `bits` may be null.
   */
  bool ReadSpecularStencil(vtkRenderWindow* window, vtkUnsignedCharArray* selection,
    vtkUnsignedCharArray* bits, bool fromStencil = false);

  /** Read the material pyramid of the last BuildSpecularStencil() (4 floats per flattened texel). */
  bool ReadSpecularMaterial(vtkRenderWindow* window, vtkFloatArray* material);

  /** The pixel size coefficients (a, b) of the last Update(). */
  void GetPixelSizeCoefficients(double coefficients[2]) const;

  /**
   * Read back the texels the last area-light gather rendered with the
   * incremental stencil (one byte per flattened texel, 1 = rendered). False
   * when the last gather used the geometric selection.
   */
  bool ReadIncrementalStencil(vtkRenderWindow* window, vtkUnsignedCharArray* mask);

  enum GatherModes
  {
    GatherStenciled = 0, ///< one draw per level, early stencil culling (default)
    GatherSplatting = 1  ///< multiresolution splatting, nichols-wyman-2009 3.4
  };

  ///@{
  /**
   * How Gather() computes the selected texels (the same numbers either
   * way): the stenciled gather of nichols-shopf-wyman-2009 section 3.2.2
   * (default), or the multiresolution splatting it replaced
   * (nichols-wyman-2009 section 3.4: every VPL draws one point per selected
   * texel, additive blending), kept so that the papers' comparison can be
   * repeated (Documentation/Multiresolution.md). Splatting reads the
   * selection back to build its subsplat list (timer step
   * "gather.subsplats"); the splats themselves are "gather.vpls", as the
   * stenciled gather's draws.
   */
  vtkSetClampMacro(GatherMode, int, GatherStenciled, GatherSplatting);
  vtkGetMacro(GatherMode, int);
  void SetGatherModeToStenciled() { this->SetGatherMode(GatherStenciled); }
  void SetGatherModeToSplatting() { this->SetGatherMode(GatherSplatting); }
  ///@}

  enum UpsampleModes
  {
    UpsampleTent = 0,        ///< nichols-wyman-2009 3.5 (default)
    UpsampleMaskWeighted = 1 ///< besenthal et al. eq. 1
  };

  /** After Gather(): upsample and combine the levels (mode: UpsampleTent or UpsampleMaskWeighted). */
  bool Upsample(vtkOpenGLRenderWindow* window, int mode, double maskWeight);

  ///@{
  /**
   * Surface-detail modulation (nichols-wyman-2009 section 4.2, eq. 2): the
   * resolved E is multiplied by alpha max(V.N, 0) + 1 - alpha, bringing back
   * the shading detail coarse texels blur out. 0 (default) is off.
   */
  vtkSetClampMacro(SurfaceDetail, double, 0.0, 1.0);
  vtkGetMacro(SurfaceDetail, double);
  ///@}

  /**
   * After Upsample(): write the full-resolution irradiance E and the indirect
   * radiance strength x albedo x E into `irradiance` and `indirect` (window-
   * sized textures, like the albedo and the G-buffer `position` and `normal`)
   * over the viewport at (x0, y0). `parallel`: the camera's projection, for
   * the view vector of the surface-detail modulation.
   */
  bool Resolve(vtkOpenGLRenderWindow* window, vtkTextureObject* albedo,
    vtkTextureObject* position, vtkTextureObject* normal, bool parallel,
    vtkTextureObject* irradiance, vtkTextureObject* indirect, int x0, int y0, double strength);

  /** Read the upsampled level 0 (RGB = E, A = 1 where it holds data) back, W x H RGBA. */
  bool ReadUpsampled(vtkRenderWindow* window, vtkFloatArray* upsampled);

  /** Read the flattened receivers (position: mean xyz + pixel count; normal) back. */
  bool ReadReceivers(vtkRenderWindow* window, vtkFloatArray* position, vtkFloatArray* normal);

  /** Read the flattened irradiance E of the last Gather() back (RGBA floats). */
  bool ReadIrradiance(vtkRenderWindow* window, vtkFloatArray* irradiance);

  /** Read the flags (MRGI_MULTIRES_FLAG_* bits) in the flattened layout. */
  bool ReadFlags(vtkRenderWindow* window, vtkUnsignedCharArray* flags);

  ///@{
  /**
   * Per-frame statistics (nichols-shopf-wyman-2009 table 1): with
   * CollectStatistics on, Gather() counts the texels it gathers at each
   * level with occlusion queries and the valid pixels (the full-resolution
   * gather's work) from the coarsest receivers. Reading them waits for the
   * GPU, hence off by default.
   */
  vtkSetMacro(CollectStatistics, bool);
  vtkGetMacro(CollectStatistics, bool);
  vtkBooleanMacro(CollectStatistics, bool);
  ///@}

  /** Texels gathered at `level` by the last Gather(); -1 when not counted. */
  vtkIdType GetNumberOfGatheredTexels(int level) const;

  /** Valid (non-background) pixels of the last Gather(); -1 when not counted. */
  vtkIdType GetNumberOfValidPixels() const;

  /**
   * Texels gathered at all levels over the valid pixels: the share of the
   * full-resolution gather's work done (each texel gathers every VPL once,
   * as each pixel does at full resolution); -1 when not counted.
   */
  double GetGatherWorkFraction() const;

  /**
   * After Update(): build the receivers of every level (mean position and
   * normal of each texel's pixels, mrgi_multires_receivers.h; level 0 is the
   * G-buffer itself). Gather() builds them when this frame's are missing;
   * passes that need them before the gather (the incremental area-light
   * visibility) call this first. False on error.
   */
  bool BuildReceivers(vtkOpenGLRenderWindow* window, vtkTextureObject* position,
    vtkTextureObject* normal, int x0, int y0);

  /**
   * The receivers of `level` (which: 0 position = eye-space mean xyz +
   * pixel count, 1 normal) after BuildReceivers() or Gather(); level 0 is
   * the G-buffer. Texel t of the level's part of the flattened layout is
   * texel t + GetReceiverOffset(level) of this texture. Null when not built.
   */
  vtkTextureObject* GetReceiverTexture(int level, int which) const;
  bool GetReceiverOffset(int level, int offset[2]) const;

  /** The flags (MRGI_MULTIRES_FLAG_* bits, red channel) of `level` after Update(); null otherwise. */
  vtkTextureObject* GetFlagsTexture(int level) const;

  /** The selection as colour (flattened layout; 1 where the stencil is set) after Update(). */
  vtkTextureObject* GetSelectionTexture() const;

#ifndef __VTK_WRAP__
  /** The flattened layout of the last Update(); false before. */
  bool GetLayout(mrgi_multires_layout* layout) const;
#endif

  /** The depth-stencil texture holding the selection (flattened layout). */
  vtkTextureObject* GetStencilTexture() const;

  /**
   * Log each step as a nested GPU timer event ("select.mipmaps",
   * "gather.vpls", ...) on this timer; null (the default) logs nothing. Not
   * reference counted: the caller keeps the timer alive while it is set.
   */
  void SetStageTimer(vtkRenderTimerLog* timer) { this->StageTimer = timer; }

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIMultiresolution();
  ~vtkMRGIMultiresolution() override;

  double DepthThreshold = 4.0; // the constructor applies PresetBalanced
  double NormalThreshold = 0.25;
  int FinestLevel = 0;
  bool Balance = true;
  int CoarsestSide = 16;
  bool CollectStatistics = false;
  double SurfaceDetail = 0.0;
  int GatherMode = GatherStenciled;
  bool IncrementalStencil = true;
  double IncrementalStencilFraction = 0.25;
  bool SpecularLobeRefinement = true;
  double SpecularLobeThreshold = 0.125;
  vtkRenderTimerLog* StageTimer = nullptr;

  // The incremental stencil (3.4) of the area-light gather in progress.
  bool BuildIncrementalStencil(vtkOpenGLRenderWindow* window, vtkMRGIVisibilityPyramid* masks);

  // The two ways of Gather() (after the receivers are built).
  bool RunStenciledGather(vtkOpenGLRenderWindow* window, vtkTextureObject* position,
    vtkTextureObject* normal, int x0, int y0, vtkTextureObject* vpls, int vplCount,
    const float viewToWorld[16]);
  bool RunSplatting(vtkOpenGLRenderWindow* window, vtkTextureObject* position,
    vtkTextureObject* normal, int x0, int y0, vtkTextureObject* vpls, int vplCount,
    const float viewToWorld[16]);

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIMultiresolution(const vtkMRGIMultiresolution&) = delete;
  void operator=(const vtkMRGIMultiresolution&) = delete;
};

#endif
