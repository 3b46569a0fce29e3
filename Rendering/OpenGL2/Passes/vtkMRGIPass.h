/**
 * @class   vtkMRGIPass
 * @brief   Adds one-bounce indirect light to a VTK renderer: G-buffer,
 *          reflective shadow maps, VPLs, gather and composite, with GPU
 *          time per stage.
 *
 * Installed like vtkSSAOPass:
 * @code
 * vtkNew<vtkRenderStepsPass> steps;
 * vtkNew<vtkMRGIPass> gi;
 * gi->SetDelegatePass(steps);
 * renderer->SetPass(gi);
 * @endcode
 *
 * Per frame (Documentation/IndirectLight.md has the equations):
 * 1. "scene": the opaque props are drawn by the delegate into MRGI's float
 *    buffers; VTK's own shading is the direct light, and shader replacement
 *    captures the G-buffer (eye-space position, normal, albedo: mrgi_buffers.h).
 * 2. "rsm": reflective shadow maps of the lights (vtkMRGIReflectiveShadowMapPass),
 *    re-rendered only when lights or props changed.
 * 3. "vpl": VPL selection into the VPL cache (vtkMRGIVPLSelection).
 * 4. "gather": every pixel gathers every VPL (nichols-shopf-wyman-2009
 *    eq. 1 and 5), giving E and the indirect radiance albedo * E * strength.
 * 5. "add": the indirect radiance is added to the direct light.
 * 6. "forward": translucent props and volumes are drawn on top
 *    (not lit indirectly, depth peeling as configured on the renderer),
 *    when the delegate is a vtkRenderStepsPass; other delegates draw
 *    everything in step 1.
 * 7. "output": the HDR result, exposed (Exposure, AutoExposure) and tone
 *    mapped (ToneMapping), with depth, goes to the framebuffer VTK was
 *    drawing into; with renderer->UseFXAAOn() FXAA runs on that display
 *    image first, in MRGI's own single-sample buffer. Then the 2D overlays
 *    of a vtkRenderStepsPass delegate are drawn over it, untouched by
 *    exposure, tone mapping and FXAA.
 *
 * With IndirectMode Off, or no VPLs, or no light reaching anything, steps 2-5
 * do not run and nothing is captured: the pass costs one copy.
 *
 * Buffers can be read back for inspection, tests and EXR output:
 * GetColorBuffer() (final HDR), GetIndirectBuffer() (what was added),
 * GetIrradianceBuffer() (E), GetGBuffer().
 *
 * Exposure and tone mapping: SetExposure(EV) scales the HDR image by 2^EV
 * before the output; AutoExposureOn() picks EV per frame so the
 * log-average luminance of the drawn pixels lands on AutoExposureKey
 * (Reinhard et al. 2002); ToneMappingOn() rolls highlights off towards 1
 * while keeping every value up to 0.5, mid-grey included, as it is
 * (mrgi_exposure.h). The HDR read-backs (GetColorBuffer, EXR) are never
 * exposed nor tone mapped. VTK's own vtkToneMappingPass may also wrap this
 * pass (Documentation/Composition.md lists the nestings that work).
 *
 * Anti-aliasing: renderer->UseFXAAOn() (see step 7; works whatever the
 * window's multisampling). The window's multisamples (MSAA) cannot reach
 * MRGI's single-sample float buffers: a window with MultiSamples > 1 gets
 * one error naming the fix, and renders without MSAA.
 */
#ifndef vtkMRGIPass_h
#define vtkMRGIPass_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkImageProcessingPass.h"
#include "vtkMRGIFrameBudget.h" // For the inline frame-budget setters and Knobs
#include "vtkNew.h"             // For vtkNew

#include "mrgi_buffers.h"       // For MRGI_SHADOW_SLOTS
#include "mrgi_direct_shadow.h" // For MRGI_DIRECT_SHADOW_MAX_SIDE

#include <memory> // For std::unique_ptr
#include <string> // For std::string
#include <vector> // For std::vector

class vtkFloatArray;
class vtkImageData;
struct vtkMRGIFrameContext;
class vtkMRGIAreaLight;
class vtkMRGIAreaLightStage;
class vtkMRGIGather;
class vtkMRGIIndirectLight;
class vtkMRGIMultiresolution;
class vtkMRGIUpsample;
class vtkMRGISSAO;
class vtkMRGISSGI;
class vtkMRGIVarianceShadowQuery;
class vtkMRGIVisibilityPyramid;
class vtkMRGIVoxelization;
class vtkMRGIReflectiveShadowMapPass;
class vtkMRGIDirectShadows;
class vtkMRGIShadowedDirectLight;
class vtkMRGIRSMCompositor;
class vtkMRGIVPLSelection;
class vtkOpenGLFXAAFilter;
class vtkOpenGLRenderWindow;
class vtkRenderTimerLog;
class vtkRenderWindow;
class vtkSequencePass;
class vtkTextureObject;

class MRGIRENDERING_EXPORT vtkMRGIPass : public vtkImageProcessingPass
{
public:
  static vtkMRGIPass* New();
  vtkTypeMacro(vtkMRGIPass, vtkImageProcessingPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

  enum IndirectModes
  {
    IndirectOff = 0, ///< direct light only
    IndirectFull = 1,    ///< full-resolution gather: every pixel gathers every VPL
    IndirectMultires = 2 ///< stencil-selected multiresolution gather, upsampled (vtkMRGIMultiresolution)
  };

  ///@{
  /**
   * How indirect light is computed (default IndirectMultires with the
   * Balanced preset of vtkMRGIMultiresolution; IndirectFull is the
   * reference it approximates).
   */
  vtkSetClampMacro(IndirectMode, int, IndirectOff, IndirectMultires);
  vtkGetMacro(IndirectMode, int);
  ///@}

  ///@{
  /** Factor on the indirect light added to the direct light (default 1, physically based). */
  vtkSetClampMacro(IndirectStrength, double, 0.0, 1e6);
  vtkGetMacro(IndirectStrength, double);
  ///@}

  ///@{
  /** VPLs per frame, 0..4096 (default 256 = 16 x 16). Forwarded to the VPL selection. */
  void SetNumberOfVPLs(int count);
  int GetNumberOfVPLs();
  ///@}

  ///@{
  /**
   * VPL selection (vtkMRGIVPLSelection::SelectionMode): 0 grid (default),
   * 1 flux importance, 2 multiresolution clusters, 3 the VPL tree
   * (nichols-shopf-wyman-2009 section 3.5; the gather walks it per pixel),
   * 4 bidirectional RSM importance (ritschel-et-al-2011 sections 4 and 6.5:
   * texels weighted by their contribution to view samples of the frame).
   */
  void SetVPLSelectionMode(int mode);
  int GetVPLSelectionMode();
  ///@}

  ///@{
  /**
   * Light-space discontinuity thresholds of the Clusters VPL selection
   * (nichols-shopf-wyman-2009 section 3.4), with the eye side's meaning
   * (mrgi_multires.h section 3): >= 0, +inf turns a test off (+inf for both
   * gives the 16 x 16 grid). Defaults 4 and 0.25. Forwarded to the VPL selection.
   */
  void SetClusterDepthThreshold(double threshold);
  double GetClusterDepthThreshold();
  void SetClusterNormalThreshold(double threshold);
  double GetClusterNormalThreshold();
  ///@}

  ///@{
  /**
   * Refinement threshold tau of the Tree VPL selection on the form-factor
   * bound (mrgi_vpl_tree_gather.h section 1): 0 (every RSM texel) .. +inf
   * (>= 1: the 16 x 16 roots), default 0.05. Forwarded to the VPL selection.
   */
  void SetTreeThreshold(double threshold);
  double GetTreeThreshold();
  ///@}

  ///@{
  /** Reflective shadow map resolution, 16..2048 (default 256). */
  void SetRSMResolution(int resolution);
  int GetRSMResolution();
  ///@}

  ///@{
  /**
   * Distributed rendering (ParaView's ranks, each with a piece of the
   * data): with a compositor of more than one process
   * (vtkMRGIControllerRSMCompositor over a vtkMultiProcessController, in
   * MRGI::RenderingParallel), the reflective shadow maps are composited
   * across the processes by depth before the VPLs are selected, so that
   * every process gathers the same VPLs on its own G-buffer. Every process
   * must then render the same frames with the same lights and settings
   * (vtkMRGIReflectiveShadowMapPass says what is collective). Null (default)
   * or one process: no communication. Forwarded to the reflective shadow
   * map pass.
   */
  void SetRSMCompositor(vtkMRGIRSMCompositor* compositor);
  vtkMRGIRSMCompositor* GetRSMCompositor();
  ///@}

  /**
   * Bytes this process sent for the maps' composite in the last frame (see
   * vtkMRGIReflectiveShadowMapPass::GetCompositeBytes); 0 without a compositor.
   */
  vtkTypeInt64 GetRSMCompositeBytes();

  /**
   * The multiresolution buffer (IndirectMultires, and the area lights): its
   * thresholds, finest level, balance rule and coarsest side choose the
   * texels that gather; read-backs of the selection, flags and receivers.
   */
  vtkMRGIMultiresolution* GetMultiresolution() { return this->Multiresolution; }

  /**
   * The indirect light's multiresolution gather (gather mode, statistics,
   * the flattened irradiance) and its upsampling (read-back of the
   * upsampled E). The area lights have their own: GetAreaLightStage().
   */
  vtkMRGIGather* GetGather();
  vtkMRGIUpsample* GetUpsample();

  ///@{
  /**
   * Visibility of the VPLs: indirect shadows (issue 13,
   * Documentation/IndirectLight.md "Indirect visibility").
   * vtkMRGIIndirectLight::VisibilityOff (default: light bounces through
   * occluders, as with any reflective-shadow-map method), VisibilityISM
   * (imperfect shadow maps, ritschel-et-al-2011) or VisibilityVoxels (the
   * screen-space voxels of the area lights, marched to each VPL).
   * Forwarded to the indirect-light stage.
   */
  void SetIndirectVisibility(int mode);
  int GetIndirectVisibility();
  ///@}

  ///@{
  /**
   * Which texels the multiresolution gather refines (issue 17 part 2):
   * vtkMRGIMultiresolution::RefinementGeometry (depth and normal
   * discontinuities) or RefinementIllumination (also where neighbouring
   * coarse results differ by more than IlluminationThreshold, relative).
   * Defaults: the multiresolution preset's (Balanced and Accurate refine by
   * illumination from views of 384^2 pixels up,
   * vtkMRGIMultiresolution::IlluminationMinimumPixels). Forwarded to
   * GetMultiresolution(); SetRefinement() applies at any view size (sets
   * IlluminationMinimumPixels to 0); a preset applied later sets all again.
   */
  void SetRefinement(int mode);
  int GetRefinement();
  void SetIlluminationThreshold(double threshold);
  double GetIlluminationThreshold();
  ///@}

  ///@{
  /**
   * The imperfect shadow maps of VisibilityISM (vtkMRGIImperfectShadowMaps):
   * points drawn per VPL (default 256), tile side (power of two, default
   * 32), point density (0 uniform, 1 adaptive from one view sample, 2
   * adaptive from 8, default 2) and lazy update (1 / frames of the points
   * resampled per frame, default 8; 1 resamples every frame). Forwarded.
   */
  void SetISMPointsPerVPL(int points);
  int GetISMPointsPerVPL();
  void SetISMTileSize(int side);
  int GetISMTileSize();
  void SetISMPointMode(int mode);
  int GetISMPointMode();
  void SetISMLazyFrames(int frames);
  int GetISMLazyFrames();
  ///@}

  /** The indirect-light stage (VPL selection, visibility, gather, upsampling). */
  vtkMRGIIndirectLight* GetIndirectLightStage() { return this->IndirectLight; }

  ///@{
  /**
   * Upsampling of the multiresolution gathers (indirect light and area
   * lights): vtkMRGIUpsample::UpsampleTent (default) or
   * UpsampleMaskWeighted, and the mask weight (default 100).
   */
  void SetUpsampleMode(int mode);
  int GetUpsampleMode();
  void SetUpsampleMaskWeight(double weight);
  double GetUpsampleMaskWeight();
  ///@}

  enum DirectShadowModes
  {
    DirectShadowsOff = 0,  ///< VTK's direct light as VTK draws it (no shadows)
    DirectShadowsHard = 1, ///< percentage-closer filtering on the RSMs
    DirectShadowsSoft = 2  ///< PCSS: blocker search, then filtering (default)
  };

  ///@{
  /**
   * Shadows in VTK's direct light, from the reflective shadow maps the
   * indirect light already renders (no extra render of the scene), for the
   * first MRGI_SHADOW_SLOTS (2) switched-on VTK lights: spot, point (cube
   * faces) and directional. Each light's term is captured from VTK's own
   * light loop and scaled by its shadow factor, so lit pixels keep VTK's
   * exact colour: Phong and PBR, textures, scalars
   * (Documentation/DirectShadows.md). Translucent props, volumes and
   * overlays are drawn as before, unshadowed. Default: soft.
   */
  vtkSetClampMacro(DirectShadows, int, DirectShadowsOff, DirectShadowsSoft);
  vtkGetMacro(DirectShadows, int);
  void SetDirectShadowsToOff() { this->SetDirectShadows(DirectShadowsOff); }
  void SetDirectShadowsToHard() { this->SetDirectShadows(DirectShadowsHard); }
  void SetDirectShadowsToSoft() { this->SetDirectShadows(DirectShadowsSoft); }
  ///@}

  ///@{
  /**
   * Soft shadows (PCSS, mrgi_direct_shadow.h): the filter's taps per side
   * n, 1..14 (n x n taps; default 8), and the radius of the lights in world
   * units (VTK's lights are points; a directional light's radius is read
   * as an angle against the scene's bounding radius). 0 (default):
   * automatic, 1% of the visible props' bounding radius.
   */
  vtkSetClampMacro(SoftShadowKernelSize, int, 1, MRGI_DIRECT_SHADOW_MAX_SIDE);
  vtkGetMacro(SoftShadowKernelSize, int);
  vtkSetClampMacro(ShadowLightRadius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ShadowLightRadius, double);
  ///@}

  /**
   * The direct-shadow step (vtkMRGIShadowedDirectLight): the shadowed
   * lights, the automatic light radius (GetLastLightRadius(),
   * GetNumberOfLightRadiusUpdates()), the factors and their composite.
   */
  vtkMRGIShadowedDirectLight* GetShadowedDirectLight() { return this->DirectLight; }
  /** The stage that computes the shadow factors (the direct-shadow step's vtkMRGIDirectShadows). */
  vtkMRGIDirectShadows* GetDirectShadowStage();

  ///@{
  /**
   * Surface-detail modulation of the indirect light (nichols-wyman-2009
   * section 4.2, eq. 2): the resolved E is multiplied by alpha max(V.N, 0)
   * + 1 - alpha, bringing back the shading detail coarse texels blur out.
   * 0 (default) is off. Direct light from area lights is never modulated.
   */
  vtkSetClampMacro(SurfaceDetail, double, 0.0, 1.0);
  vtkGetMacro(SurfaceDetail, double);
  ///@}

  ///@{
  /**
   * Screen-space ambient occlusion of the direct light, computed from the
   * G-buffer and applied as vtkSSAOPass (VTK 9.1) does: its kernel for the
   * same size, radius, bias, range check, and optional 3x3 blur; AO
   * multiplies the scene's colour before indirect and area light are added
   * (they carry their own visibility). Off by default; KernelSize 1..1000
   * (default 32), Radius > 0 (0.5) and Bias (0.01) in world units, Blur
   * off: vtkSSAOPass's defaults. vtkMRGISSAO is the stage.
   */
  vtkSetMacro(SSAO, bool);
  vtkGetMacro(SSAO, bool);
  vtkBooleanMacro(SSAO, bool);
  vtkSetClampMacro(SSAOKernelSize, int, 1, 1000);
  vtkGetMacro(SSAOKernelSize, int);
  vtkSetMacro(SSAORadius, double);
  vtkGetMacro(SSAORadius, double);
  vtkSetMacro(SSAOBias, double);
  vtkGetMacro(SSAOBias, double);
  vtkSetMacro(SSAOBlur, bool);
  vtkGetMacro(SSAOBlur, bool);
  vtkBooleanMacro(SSAOBlur, bool);
  vtkMRGISSAO* GetSSAOStage() { return this->SSAOStage; }
  ///@}

  /** Where a screen-space effect is evaluated. */
  enum ScreenSpaceResolutions
  {
    ResolutionFull = 0,           ///< every pixel at full resolution
    ResolutionMultiresolution = 1 ///< BMR: four levels under edge stencils, blended
  };

  ///@{
  /**
   * The direct shadows' resolution: ResolutionFull (default) or
   * ResolutionMultiresolution (vtkMRGIDirectShadows::ComputeMultiresolution(),
   * BMR's SSM preset; Documentation/ScreenSpaceEffects-Benchmark.md).
   */
  vtkSetClampMacro(ShadowResolution, int, ResolutionFull, ResolutionMultiresolution);
  vtkGetMacro(ShadowResolution, int);
  ///@}

  ///@{
  /**
   * SSAO's resolution: ResolutionFull (default: on llvmpipe the masks and
   * the blend cost more than the AO they save, see
   * Documentation/ScreenSpaceEffects-SSAO.md) or ResolutionMultiresolution
   * (vtkMRGISSAO::RenderMultiresolution(), BMR's SSAO preset).
   */
  vtkSetClampMacro(SSAOResolution, int, ResolutionFull, ResolutionMultiresolution);
  vtkGetMacro(SSAOResolution, int);
  ///@}

  ///@{
  /**
   * Screen-space one-bounce light (SSGI, Ritschel et al. 2009 as BMR
   * evaluates it) from the direct light after shadows and SSAO, added to
   * the colour. Exclusive with the VPL gather: while SSGI is on, the frame
   * gathers no VPL light (IndirectMode is kept, the RSMs still cast direct
   * shadows), so no bounce is counted twice (Documentation/
   * ScreenSpaceEffects-SSGI.md). Off by default; Samples 1..512 (64),
   * Radius > 0 (0.5) and Bias >= 0 (0.01) in world units. vtkMRGISSGI is
   * the stage.
   */
  vtkSetMacro(SSGI, bool);
  vtkGetMacro(SSGI, bool);
  vtkBooleanMacro(SSGI, bool);
  vtkSetClampMacro(SSGISamples, int, 1, 512);
  vtkGetMacro(SSGISamples, int);
  vtkSetMacro(SSGIRadius, double);
  vtkGetMacro(SSGIRadius, double);
  vtkSetMacro(SSGIBias, double);
  vtkGetMacro(SSGIBias, double);
  vtkMRGISSGI* GetSSGIStage() { return this->SSGIStage; }
  ///@}

  ///@{
  /**
   * SSGI's resolution: ResolutionFull (default, like the other effects) or
   * ResolutionMultiresolution (vtkMRGISSGI::RenderMultiresolution(), BMR's
   * SSGI preset of Table 1; Documentation/ScreenSpaceEffects-SSGI.md).
   */
  vtkSetClampMacro(SSGIResolution, int, ResolutionFull, ResolutionMultiresolution);
  vtkGetMacro(SSGIResolution, int);
  ///@}

  /** The screen-space presets (mrgi_screen_space_preset.h). */
  enum ScreenSpacePresets
  {
    ScreenSpaceFast = 0,     ///< fewer samples and taps, coarser BMR masks
    ScreenSpaceBalanced = 1, ///< the defaults
    ScreenSpaceAccurate = 2  ///< BMR figure 6's sample counts, finer BMR masks
  };

  /**
   * Apply a screen-space preset: the SSAO kernel size, the soft-shadow
   * kernel, the SSGI samples, the three effects' resolutions and the BMR
   * mask thresholds of the SSAO, SSGI and direct-shadow stages, from the one
   * table of mrgi_screen_space_preset_get(). Effects are not switched on or
   * off; radii and biases are kept. Setters called afterwards override
   * single knobs. Measured error and time of each preset:
   * Documentation/ScreenSpaceEffects.md. False, with an error and nothing
   * changed, for an unknown preset.
   */
  bool SetScreenSpacePreset(int preset);
  /**
   * The last preset applied by SetScreenSpacePreset(), -1 before (a knob
   * set afterwards does not reset it).
   */
  vtkGetMacro(ScreenSpacePreset, int);

  ///@{
  /**
   * Area lights (vtkMRGIAreaLight: textured rectangles, direct light and,
   * with AreaLightIndirect, one bounce through the RSMs;
   * nichols-penmatsa-wyman-2010). Each adds albedo x X to the image, X its
   * irradiance gathered from its light samples at the multiresolution
   * texels (the selection of GetMultiresolution(), shared with the indirect
   * light), upsampled, without visibility (no shadows yet). They are drawn
   * whatever IndirectMode is; a light's emitter geometry is the caller's
   * (vtkMRGIAreaLight::GetGeometryActor()). A light whose parameters are
   * invalid is skipped with its error.
   */
  void AddAreaLight(vtkMRGIAreaLight* light);
  void RemoveAreaLight(vtkMRGIAreaLight* light);
  void RemoveAllAreaLights();
  int GetNumberOfAreaLights() const;
  vtkMRGIAreaLight* GetAreaLight(int index) const;
  ///@}

  ///@{
  /**
   * Whether area lights also cast one bounce of indirect light (default
   * on): their reflective shadow maps (hemicube views from each emitter's
   * centre, mrgi_area_light_rsm.h) join the vtkLights' maps, so the same
   * VPL selection and gather use them. Like the vtkLights' bounce, it needs
   * IndirectMode not Off (mrgi-render --gi off turns both off).
   */
  vtkSetMacro(AreaLightIndirect, bool);
  vtkGetMacro(AreaLightIndirect, bool);
  vtkBooleanMacro(AreaLightIndirect, bool);
  ///@}

  enum AreaLightVisibilityModes
  {
    VisibilityOff = 0,        ///< no shadows from area lights (NPW10 3.2)
    VisibilityNaive = 1,      ///< a voxel march per texel and light sample (NPW10 3.3.1)
    VisibilityIncremental = 2 ///< coarse to fine, reusing agreeing coarse bits (NPW10 3.3.2; default)
  };

  ///@{
  /**
   * Shadows of the area lights (nichols-penmatsa-wyman-2010 3.3): none;
   * naive (the visible scene is voxelized into 256 depth slices per pixel
   * of a voxel buffer, GetVoxelization() holds its size, slices and march
   * knobs,
   * and each light sample is marched from each gathering texel); or
   * incremental (default: one visibility bit per sample and texel, computed
   * coarse to fine over the multiresolution levels, a coarse bit reused
   * where the 3x3 coarser neighbours on the same surface agree; 2x2
   * interleaving is available and off by default, measured less accurate;
   * GetVisibilityPyramid() holds its knobs and ray statistics; lights with
   * more samples than it takes, 512, fall back to naive). Occluders outside
   * the view are unknown to a screen-space method.
   */
  void SetAreaLightVisibility(int mode);
  int GetAreaLightVisibility();
  ///@}

  ///@{
  /**
   * Phong highlights of the area lights on surfaces with a vtkProperty
   * Specular > 0 (nichols-penmatsa-wyman-2010 3.2.1; default on): the
   * G-buffer then also captures k_s c_s and SpecularPower. Shadowed as
   * AreaLightVisibility says (3.3.3; see GetVarianceShadowQuery()).
   */
  void SetAreaLightSpecular(bool specular);
  bool GetAreaLightSpecular();
  void AreaLightSpecularOn() { this->SetAreaLightSpecular(true); }
  void AreaLightSpecularOff() { this->SetAreaLightSpecular(false); }
  ///@}

  enum AreaLightSpecularResolutions
  {
    SpecularFullResolution = 0, ///< every pixel gathers its highlight (default)
    SpecularMultiresolution = 1 ///< stenciled multiresolution gather refined by lobe size (NPW10 3.2.1)
  };

  ///@{
  /**
   * Where the area lights' Phong highlights are gathered: at every pixel
   * (SpecularFullResolution, the default), or at the texels of a specular
   * stencil (SpecularMultiresolution, nichols-penmatsa-wyman-2010 3.2.1:
   * the multiresolution selection plus the lobe-size metric "image-space
   * sample spacing must be denser than the lobe width", texels without
   * specular material skipped; mrgi_specular_stencil.h), then upsampled
   * like the diffuse term and multiplied by each pixel's k_s c_s.
   * Visibility as AreaLightVisibility says: the level's incremental masks,
   * or the naive march at the texel's receiver; lobe-grid cells read the
   * variance shadow query at the footprint's centre pixel. The lobe metric
   * can be turned off with
   * GetAreaLightStage()->GetSpecularStencilStage()->LobeRefinementOff().
   * Experimental: measured at 256x256 (--specular 0.5:40 / 0.5:120) the
   * highlight's relative RMS error against full resolution is 2.6% / 3.4%
   * on living-room but 21% / 34% on cornell-area (flat walls gathered at
   * 16-pixel texels: the lobe metric m > 1 fires only at coarser spacing),
   * with no speed gain yet (the full-resolution variance shadow moments and
   * the stencil dominate).
   */
  void SetAreaLightSpecularResolution(int resolution);
  int GetAreaLightSpecularResolution();
  ///@}

  /**
   * The area lights' stage (vtkMRGIAreaLightStage): it owns their
   * textures, programs and stages (gather, upsampling, incremental and
   * specular stencils, voxelization, visibility, variance shadow query).
   * The area-light methods of this class forward to it.
   */
  vtkMRGIAreaLightStage* GetAreaLightStage() { return this->AreaLightStage; }

  /** The screen-space voxelization of the area-light visibility (voxel buffer size, march knobs). */
  vtkMRGIVoxelization* GetVoxelization();

  /** The incremental visibility (knobs, per-level ray statistics of the last light gathered). */
  vtkMRGIVisibilityPyramid* GetVisibilityPyramid();

  /**
   * The shadows of sharp area-light highlights (NPW10 3.3.3's variance
   * shadow query: blur radius, minimum variance, the last light's moments).
   * With AreaLightVisibility on, a highlight is shadowed like the diffuse
   * light: on glossy lobes each light sample's term counts where the
   * sample is visible (the texel's bit of the incremental visibility at
   * full resolution, or a voxel march per sample when visibility is naive
   * or the light has more samples than the pyramid takes); on sharp lobes
   * (the 5 x 5 lobe grid) each cell's term is weighted by this query.
   */
  vtkMRGIVarianceShadowQuery* GetVarianceShadowQuery();

  /**
   * The direct light of the area lights in the last frame (albedo x X,
   * summed over the lights; RGB float, the viewport only). False when no
   * area light was drawn.
   */
  bool GetAreaLightBuffer(vtkRenderWindow* window, vtkImageData* image);

  ///@{
  /**
   * Exposure in stops (EV, default 0): the HDR colour is multiplied by
   * 2^Exposure before tone mapping and output. Clamped to [-20, 20]
   * (MRGI_EXPOSURE_MIN_EV/MAX_EV). Ignored while AutoExposure is on.
   */
  void SetExposure(double ev);
  vtkGetMacro(Exposure, double);
  ///@}

  ///@{
  /**
   * Automatic exposure (default off): each frame, EV = log2(key / Lw),
   * Lw the log-average luminance of the pixels something was drawn on
   * (background ignored; Reinhard et al. 2002 eq. 1), key =
   * AutoExposureKey (default 0.18), capped so that 97% of those pixels
   * stay at or below 1 (mrgi_exposure.h says why). Reads the colour and
   * depth back once per frame.
   */
  vtkSetMacro(AutoExposure, bool);
  vtkGetMacro(AutoExposure, bool);
  vtkBooleanMacro(AutoExposure, bool);
  void SetAutoExposureKey(double key);
  vtkGetMacro(AutoExposureKey, double);
  ///@}

  /** The EV the last frame was output with (Exposure, or the automatic one). */
  vtkGetMacro(LastExposure, double);

  ///@{
  /**
   * Tone mapping of the output (default off): mrgi_tone_curve per
   * channel, the identity up to 0.5 and a smooth roll-off to 1 above it,
   * so mid-grey (0.18) keeps the display value the plain output gives it.
   */
  vtkSetMacro(ToneMapping, bool);
  vtkGetMacro(ToneMapping, bool);
  vtkBooleanMacro(ToneMapping, bool);
  ///@}

  /** Whether the last frame drew area lights. */
  vtkGetMacro(AreaLightsComputed, bool);

  /**
   * How many frames computed the area lights' light (voxelization,
   * visibility, gathers). A frame whose inputs did not change since the
   * last computation (camera, viewport, the visible props and their data,
   * the area lights and their pictures, the pass's and its stages'
   * settings) adds the previous result again instead: "buffers are not
   * re-rendered when their inputs did not change". Statistics collection
   * (the area-light stage's vtkMRGIGather, vtkMRGIVisibilityPyramid) always
   * computes, and so does every frame with AreaLightReuse off (benchmarks:
   * they measure the computation).
   */
  vtkIdType GetNumberOfAreaLightUpdates();
  void SetAreaLightReuse(bool reuse);
  bool GetAreaLightReuse();
  void AreaLightReuseOn() { this->SetAreaLightReuse(true); }
  void AreaLightReuseOff() { this->SetAreaLightReuse(false); }

  /** The sub-stages, for inspection (statistics, read-backs). */
  vtkMRGIReflectiveShadowMapPass* GetReflectiveShadowMapPass() { return this->RSMPass; }
  vtkMRGIVPLSelection* GetVPLSelection();

  ///@{
  /**
   * Frame-budget tuner (vtkMRGIFrameBudget, issue 17 part 4). SetFrameBudget(ms)
   * > 0: each frame the preset, VPL count, RSM size and (with voxel
   * visibility) voxel side are chosen to meet ms at the least predicted
   * error, with hysteresis during interaction; SetErrorBudget(e) > 0: the
   * cheapest setting predicted within relative RMS e of the dense reference.
   * 0 (default): off, the pass's own settings hold. While on, the tuner
   * overrides those settings every frame. Calibrate(window) measures this
   * machine once and stores it (per-user cache, keyed by the GL renderer).
   */
  void SetFrameBudget(double ms) { this->FrameBudgetTuner->SetFrameBudget(ms); }
  double GetFrameBudget() { return this->FrameBudgetTuner->GetFrameBudget(); }
  void SetErrorBudget(double error) { this->FrameBudgetTuner->SetErrorBudget(error); }
  double GetErrorBudget() { return this->FrameBudgetTuner->GetErrorBudget(); }
  bool Calibrate(vtkRenderWindow* window);
  vtkMRGIFrameBudget* GetFrameBudgetTuner() { return this->FrameBudgetTuner; }
  ///@}

  ///@{
  /**
   * Bracket each stage with GPU timer queries (vtkRenderTimerLog). The
   * window's timer log must be logging when a frame starts: switch it on
   * before the first render (`window->GetRenderTimer()->SetLoggingEnabled(true)`),
   * or let the first FetchStageTimings() switch it on (timing then starts
   * with the next frame).
   */
  vtkSetMacro(StageTimingEnabled, bool);
  vtkGetMacro(StageTimingEnabled, bool);
  vtkBooleanMacro(StageTimingEnabled, bool);
  ///@}

  /**
   * Collect GPU stage times of the most recent frame whose timer queries have
   * completed (wait = true: close the frame just rendered and drain the GPU
   * first). Returns the number of stages found.
   */
  int FetchStageTimings(vtkRenderWindow* window, bool wait);

  ///@{
  /** The stages collected by the last FetchStageTimings(), in render order. */
  int GetNumberOfStages() const { return static_cast<int>(this->StageNames.size()); }
  const char* GetStageName(int stage) const;
  double GetStageTimeMilliseconds(int stage) const;
  ///@}

  ///@{
  /**
   * Read the last frame's buffers back into `image` (float, bottom-up rows,
   * the renderer's viewport only). Colour: final HDR RGBA. Indirect: the
   * indirect radiance added to the direct light (RGB). Irradiance: E of the
   * gather before albedo and strength (RGB). All zero where nothing was
   * gathered. Return false (with an error) before the first render or when
   * the buffer was not computed (e.g. indirect light off).
   */
  bool GetColorBuffer(vtkRenderWindow* window, vtkImageData* image);
  bool GetIndirectBuffer(vtkRenderWindow* window, vtkImageData* image);
  bool GetIrradianceBuffer(vtkRenderWindow* window, vtkImageData* image);
  ///@}

  ///@{
  /**
   * Direct shadows of the last frame (RGBA float each): VTK's direct light
   * before shadows were applied; the shadow factors (channel s: VTK's
   * shader light s, 1 = lit); and the term of shader light `slot` that
   * VTK's light loop added (mrgi_buffers.h). False when the last frame had
   * no direct shadows.
   */
  bool GetUnshadowedBuffer(vtkRenderWindow* window, vtkImageData* image);
  bool GetShadowFactorBuffer(vtkRenderWindow* window, vtkImageData* image);
  bool GetLightTermBuffer(vtkRenderWindow* window, int slot, vtkImageData* image);
  ///@}

  /** The G-buffer of the last frame (RGBA float each; see mrgi_buffers.h). */
  bool GetGBuffer(vtkRenderWindow* window, vtkImageData* position, vtkImageData* normal,
    vtkImageData* albedo);

  /**
   * The specular part of the last frame's G-buffer (RGBA float each):
   * k_s c_s and the Phong exponent (red channel), mrgi_buffers.h. Captured
   * only while area lights reflect specularly (AreaLightSpecular on and at
   * least one area light); false otherwise.
   */
  bool GetSpecularGBuffer(vtkRenderWindow* window, vtkImageData* specular, vtkImageData* shininess);

  /** The VPL cache of the last frame: MRGI_VPL_FLOATS floats per VPL. */
  bool GetVPLs(vtkRenderWindow* window, vtkFloatArray* vpls);

  /** Eye -> world matrix (column-major, 16 values) used by the last gather. */
  const double* GetLastViewToWorld() const { return this->LastViewToWorld; }

  /** Width and height of the renderer's viewport in the last frame. */
  vtkGetVector2Macro(BufferSize, int);

  /** The renderer's viewport (x, y, width, height) in MRGI's window-sized buffers, last frame. */
  vtkGetVector4Macro(Viewport, int);

  ///@{
  /** The G-buffer textures (window-sized; the viewport is where the renderer drew). */
  vtkTextureObject* GetPositionTexture();
  vtkTextureObject* GetNormalTexture();
  vtkTextureObject* GetAlbedoTexture();
  /** E of the indirect gather (RGB; alpha 1 where gathered), window-sized. */
  vtkTextureObject* GetIrradianceTexture();
  ///@}

  /** Whether the last frame computed indirect light. */
  vtkGetMacro(IndirectComputed, bool);

  ///@{
  /** Shader hooks: G-buffer capture on opaque polygonal props. */
  bool PreReplaceShaderValues(std::string& vertexShader, std::string& geometryShader,
    std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop) override;
  bool PostReplaceShaderValues(std::string& vertexShader, std::string& geometryShader,
    std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop) override;
  /**
   * Re-selects MRGI's G-buffer targets for each draw of the capture: an
   * enclosing vtkSSAOPass selects its own three targets there.
   */
  bool SetShaderParameters(vtkShaderProgram* program, vtkAbstractMapper* mapper, vtkProp* prop,
    vtkOpenGLVertexArrayObject* VAO = nullptr) override;
  ///@}

protected:
  vtkMRGIPass();
  ~vtkMRGIPass() override;

  void RenderScene(const vtkRenderState* s, bool capture, bool split);
  void RenderForward(const vtkRenderState* s);
#ifndef __VTK_WRAP__
  // The frame's context once the G-buffer is captured (camera transforms,
  // pixel size). False when nothing gathers: no capture, or (with an
  // error) an undefined pixel size.
  bool MakeFrame(vtkOpenGLRenderWindow* renWin, vtkRenderer* renderer, vtkRenderTimerLog* timer,
    bool capture, vtkMRGIFrameContext& frame);
  // SSAO, then SSGI (each at its resolution) on `colour`, the frame's
  // direct light after the shadows; a failure is reported once per run of
  // failures and leaves the frame without that effect.
  void RenderScreenSpaceEffects(const vtkMRGIFrameContext& frame, vtkTextureObject* colour);
  // Adds `source`'s RGB to `target`'s (additive blending, target alpha kept).
  void RenderAdd(const vtkMRGIFrameContext& frame, vtkTextureObject* source, vtkTextureObject* target);
#endif
  bool ReadViewport(vtkRenderWindow* window, vtkTextureObject* texture, int components,
    vtkImageData* image, const char* what);
  // Frees every GL resource (with `w`) or, without, the C++ objects that
  // hold them: the destructor and ReleaseGraphicsResources() share it.
  void ReleaseResources(vtkWindow* w);

  int IndirectMode = IndirectMultires;
  double IndirectStrength = 1.0;
  bool AreaLightIndirect = true;
  double SurfaceDetail = 0.0;
  bool SSAO = false;
  int SSAOKernelSize;   // MRGI_SSAO_DEFAULT_KERNEL_SIZE (constructor)
  double SSAORadius;   // MRGI_SSAO_DEFAULT_RADIUS (constructor)
  double SSAOBias;     // MRGI_SSAO_DEFAULT_BIAS (constructor)
  bool SSAOBlur = false;
  int SSAOResolution = ResolutionFull;
  int ShadowResolution = ResolutionFull;
  bool SSAOFailureReported = false;
  bool SSGI = false;
  int SSGISamples;     // MRGI_SSGI_DEFAULT_SAMPLES (constructor)
  double SSGIRadius;   // MRGI_SSGI_DEFAULT_RADIUS (constructor)
  double SSGIBias;     // MRGI_SSGI_DEFAULT_BIAS (constructor)
  int SSGIResolution = ResolutionFull;
  int ScreenSpacePreset = -1;
  bool SSGIFailureReported = false;
  bool StageTimingEnabled = false;
  int BufferSize[2] = { 0, 0 };
  int Viewport[4] = { 0, 0, 0, 0 };
  bool IndirectComputed = false;
  bool AreaLightsComputed = false;
  double Exposure = 0.0;
  bool AutoExposure = false;
  double AutoExposureKey; // MRGI_EXPOSURE_KEY
  double LastExposure = 0.0;
  bool ToneMapping = false;
  bool MultiSamplesReported = false; // the MSAA error is given once
  bool NestingReported = false;      // so is the unsupported-delegate error
  bool OuterGBuffer = false;         // the enclosing framebuffer takes position and normal
  bool Capturing = false;            // the scene is being drawn into the G-buffer
  bool Captured = false;         // the last frame captured the G-buffer
  bool SpecularCaptured = false; // ... with its specular attachments
  int DirectShadows = DirectShadowsSoft;
  int SoftShadowKernelSize = MRGI_DIRECT_SHADOW_DEFAULT_SIDE;
  double ShadowLightRadius = 0.0;
  bool ShadowsCaptured = false; // the last frame captured the light terms
  bool ShadowsComputed = false; // ... and applied its shadows
  double LastViewToWorld[16];

  vtkMRGIReflectiveShadowMapPass* RSMPass = nullptr;
  vtkMRGIMultiresolution* Multiresolution = nullptr;
  vtkMRGIIndirectLight* IndirectLight = nullptr;
  vtkMRGISSAO* SSAOStage = nullptr;
  vtkMRGISSGI* SSGIStage = nullptr;
  vtkMRGIAreaLightStage* AreaLightStage = nullptr;
  vtkMRGIShadowedDirectLight* DirectLight = nullptr;
  vtkNew<vtkMRGIFrameBudget> FrameBudgetTuner;
#ifndef __VTK_WRAP__
  /** The settings the tuner turns: preset, VPLs, RSM size, voxel side. */
  vtkMRGIFrameBudget::Knobs FrameBudgetKnobs();
#endif
  vtkSequencePass* OpaqueSequence = nullptr;
  vtkOpenGLFXAAFilter* FXAAFilter = nullptr;

  std::vector<std::string> StageNames;
  std::vector<double> StageTimes;

  // The window-sized buffers and the full-screen programs.
  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIPass(const vtkMRGIPass&) = delete;
  void operator=(const vtkMRGIPass&) = delete;
};

#endif
