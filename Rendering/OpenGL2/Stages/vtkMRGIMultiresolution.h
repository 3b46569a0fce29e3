/**
 * @class   vtkMRGIMultiresolution
 * @brief   The multiresolution buffer: the flattened layout of the levels,
 *          their min-max mipmaps, refinement flags and the stencil
 *          selection of the texels that gather (nichols-shopf-wyman-2009
 *          3.2.1), and the receivers of every texel.
 *
 * A passive buffer: Update() fills it from a G-buffer and BuildReceivers()
 * adds the receivers; the stages that read it take it as an argument
 * (vtkMRGIGather, vtkMRGIUpsample, vtkMRGIIncrementalStencil,
 * vtkMRGISpecularStencil, vtkMRGIVisibilityPyramid) and never write it.
 *
 * The layout, the metrics, the thresholds and the rules are those of the C
 * core (mrgi_multires.h; its twin), which this class mirrors pass for pass:
 * one pass for level 0 of the mipmaps, one per coarser level (2x2
 * reduction), one per level for the flags (fine to coarse, since refinement
 * and the balance rule look at the finer level), and the one-pass stencil
 * selection, drawn once per level into that level's rectangle of the
 * flattened layout (no search for the level per fragment, nothing drawn
 * where no level lies). Mipmap and flag levels live in separate textures:
 * reading and writing one texture is a feedback loop in OpenGL 3.2.
 *
 * The stencil lives in a depth-stencil texture attached at
 * GL_DEPTH_STENCIL_ATTACHMENT by hand (VTK 9.1's framebuffer object attaches
 * depth-stencil textures at GL_DEPTH_ATTACHMENT only).
 *
 * BuildReceivers(): the receivers of every texel (mean position and normal
 * of its pixels; C twin mrgi_multires_receivers.h), level by level (level 1
 * straight from the G-buffer; level 0 is the G-buffer).
 */
#ifndef vtkMRGIMultiresolution_h
#define vtkMRGIMultiresolution_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <array>      // For std::array
#include <memory>     // For std::unique_ptr

struct mrgi_multires_layout;
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
    PresetBalanced = 1, ///< refined where the light changes, within 3% (default)
    PresetAccurate = 2  ///< the most accurate measured (~1%)
  };

  enum RefinementModes
  {
    RefinementGeometry = 0,    ///< the geometric selection alone
    RefinementIllumination = 1 ///< plus refinement where the gathered light changes
  };

  /**
   * Apply a preset (mrgi_multires_preset_params,
   * mrgi_multires_preset_illumination_threshold and
   * mrgi_multires_preset_area_light_params: thresholds, finest level,
   * refinement and the area lights' thresholds chosen from the measured
   * frontier, Documentation/Multiresolution.md; balance on). A new object
   * starts with Balanced. False (nothing changed) for an unknown preset.
   */
  bool SetPreset(int preset);

  /**
   * A preset's settings without applying it: depth threshold, normal
   * threshold (-1: off) and finest level. False for an unknown preset.
   */
  static bool GetPresetSettings(int preset, double settings[3]);

  /**
   * A preset's illumination threshold (RefinementIllumination), or -1 when
   * it refines by geometry alone or is unknown.
   */
  static double GetPresetIlluminationThreshold(int preset);

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
  /**
   * The area lights' thresholds (same meaning; vtkMRGIAreaLightStage
   * selects with these, mrgi_multires_preset_area_light_params()): their
   * shadows change at depth edges, which the indirect light's illumination
   * rule lets its own selection skip. Defaults: the Balanced preset's.
   */
  vtkSetMacro(AreaLightDepthThreshold, double);
  vtkGetMacro(AreaLightDepthThreshold, double);
  vtkSetMacro(AreaLightNormalThreshold, double);
  vtkGetMacro(AreaLightNormalThreshold, double);
  ///@}

  /**
   * Whether the area lights select as the indirect light does (equal
   * thresholds), so that one Update() serves both in a frame.
   */
  bool AreaLightsShareSelection() const;

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
  /**
   * How the indirect light's gather refines below the geometric cut
   * (vtkMRGIIndirectLight reads both with the buffer it is handed each
   * frame): RefinementGeometry, the thresholds above alone; or
   * RefinementIllumination, the levels gathered coarse to fine and a texel
   * gathered too where its parent's 3x3 gathered irradiance differs by more
   * than IlluminationThreshold, relative (vtkMRGIIncrementalStencil,
   * nichols-penmatsa-wyman-2010 3.4 applied to the indirect light). The
   * other readers of the buffer (area lights, the specular stencil) keep the
   * geometric selection and refine by their own rules. Defaults: the
   * Balanced preset's.
   */
  vtkSetClampMacro(Refinement, int, RefinementGeometry, RefinementIllumination);
  vtkGetMacro(Refinement, int);
  vtkSetClampMacro(IlluminationThreshold, double, 0.0, 1.0e30);
  vtkGetMacro(IlluminationThreshold, double);
  ///@}

  ///@{
  /**
   * Smallest view, in pixels, where RefinementIllumination runs; a smaller
   * view (and multiresolution splatting, which has no step between levels)
   * selects with the area lights' thresholds and geometry alone. The
   * presets that refine by illumination set
   * MRGI_MULTIRES_ILLUMINATION_MIN_PIXELS (384^2: below it the rule
   * measured slower and less accurate than the geometric preset); 0 runs
   * it at any size (vtkMRGIPass::SetRefinement() sets 0).
   */
  vtkSetClampMacro(IlluminationMinimumPixels, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(IlluminationMinimumPixels, vtkIdType);
  ///@}

  /**
   * Whether the indirect light's gather over a width x height view with
   * `stenciled` gathering (false: splatting) refines by illumination
   * (Refinement, IlluminationMinimumPixels). When it does not and
   * Refinement asks for it, it selects with the area lights' thresholds.
   */
  bool RefinesByIllumination(int width, int height, bool stenciled) const;

  /** Whether the last Update() selected as the area lights do. */
  bool SelectionServesAreaLights() const;

  ///@{
  /** Side of the coarsest level: levels stop when both sides are <= this (default 16). */
  vtkSetClampMacro(CoarsestSide, int, 1, 4096);
  vtkGetMacro(CoarsestSide, int);
  ///@}

  /**
   * Select from a G-buffer (eye-space position and normal textures, as
   * vtkMRGIPass captures them) whose pixel (0, 0) is texel (x0, y0); the
   * image is width x height. Pixel size at depth d is max(a |d| + b, tiny)
   * (mrgi_multires_pixel_size_coefficients). Timer steps "select.*" on
   * `timer` when given. `forAreaLights`: select with the area lights'
   * thresholds instead of the indirect light's. False on error.
   */
  bool Update(vtkOpenGLRenderWindow* window, vtkTextureObject* position,
    vtkTextureObject* normal, int x0, int y0, int width, int height, double a, double b,
    vtkRenderTimerLog* timer = nullptr, bool forAreaLights = false);

  /** Flattened layout size of the last Update(). */
  int GetFlattenedWidth() const;
  int GetFlattenedHeight() const;
  int GetNumberOfLevels() const;

  /** Size of `level` in the last Update(); false (size untouched) when there is no such level. */
  bool GetLevelSize(int level, int size[2]) const;

  /** The pixel size coefficients (a, b) of the last Update(). */
  void GetPixelSizeCoefficients(double coefficients[2]) const;

  /**
   * Read the selection back: one byte per flattened texel, 1 where the
   * stencil is set. `fromStencil` reads the stencil itself, otherwise the
   * colour the selection pass wrote with it.
   */
  bool ReadSelection(vtkRenderWindow* window, vtkUnsignedCharArray* mask, bool fromStencil);

  /**
   * Read the flattened receivers (position: mean xyz + pixel count; normal)
   * back. Level 0's receiver textures exist for this read-back only: the
   * first call allocates them (two full-size RGBA32F textures).
   */
  bool ReadReceivers(vtkRenderWindow* window, vtkFloatArray* position, vtkFloatArray* normal);

  /** Read the flags (MRGI_MULTIRES_FLAG_* bits) in the flattened layout. */
  bool ReadFlags(vtkRenderWindow* window, vtkUnsignedCharArray* flags);

  /**
   * After Update(): build the receivers of every level (mean position and
   * normal of each texel's pixels, mrgi_multires_receivers.h; level 0 is the
   * G-buffer itself, at (x0, y0)). The stages that gather read them. Timer
   * step "gather.receivers" on `timer` when given. False on error.
   */
  bool BuildReceivers(vtkOpenGLRenderWindow* window, vtkTextureObject* position,
    vtkTextureObject* normal, int x0, int y0, vtkRenderTimerLog* timer = nullptr);

  /** Whether BuildReceivers() ran on this Update()'s selection. */
  bool HasReceivers() const;

  /** The finest level that gathers: FinestLevel clamped to the levels of the last Update(). */
  int GetFinestGatherLevel() const;

  /**
   * The receivers of `level` (which: 0 position = eye-space mean xyz +
   * pixel count, 1 normal) after BuildReceivers(); level 0 is
   * the G-buffer. Texel t of the level's part of the flattened layout is
   * texel t + GetReceiverOffset(level) of this texture. Null when not built.
   */
  vtkTextureObject* GetReceiverTexture(int level, int which) const;
  bool GetReceiverOffset(int level, int offset[2]) const;

#ifndef __VTK_WRAP__
  /**
   * Activate level `level`'s receivers and bind them to `program` as
   * mrgiPosition / mrgiNormal with mrgiReceiverOffset (what every gather
   * reads); the caller deactivates the two textures returned. {null, null}
   * when the receivers are not built.
   */
  std::array<vtkTextureObject*, 2> BindReceivers(vtkShaderProgram* program, int level) const;
#endif

  /**
   * Level `level`'s min-max mipmap texture `which` (MRGI_MULTIRES_TEX_*:
   * depth, normal min, normal max) after Update(); null otherwise, and for
   * both normals at level 0 (a pixel's normal range is its G-buffer normal,
   * min = max, which the passes reading level 0 normalize where they read it).
   */
  vtkTextureObject* GetMipmapTexture(int level, int which) const;

  /**
   * The flags (MRGI_MULTIRES_FLAG_* bits as float(flags) in red, GL_R16F) of
   * `level` after Update(); null otherwise.
   */
  vtkTextureObject* GetFlagsTexture(int level) const;

  /**
   * The selection as colour (flattened layout; red 1 where the stencil is
   * set, 0 elsewhere; GL_R8) after Update().
   */
  vtkTextureObject* GetSelectionTexture() const;

#ifndef __VTK_WRAP__
  /** The flattened layout of the last Update(); false before. */
  bool GetLayout(mrgi_multires_layout* layout) const;
#endif

  /** The depth-stencil texture holding the selection (flattened layout). */
  vtkTextureObject* GetStencilTexture() const;

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIMultiresolution();
  ~vtkMRGIMultiresolution() override;

  double DepthThreshold = 4.0; // the constructor applies PresetBalanced
  double NormalThreshold = 0.25;
  int FinestLevel = 0;
  bool Balance = true;
  int Refinement = RefinementGeometry;
  double IlluminationThreshold = 0.1;
  vtkIdType IlluminationMinimumPixels = 0;
  double AreaLightDepthThreshold = 4.0;
  double AreaLightNormalThreshold = 1.0;
  int CoarsestSide = 16;

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIMultiresolution(const vtkMRGIMultiresolution&) = delete;
  void operator=(const vtkMRGIMultiresolution&) = delete;
};

#endif
