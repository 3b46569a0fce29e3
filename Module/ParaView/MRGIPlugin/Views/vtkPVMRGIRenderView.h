/**
 * @class   vtkPVMRGIRenderView
 * @brief   ParaView's render view with MRGI's indirect light and area lights.
 *
 * A vtkPVRenderView whose scene is drawn through a vtkMRGIPass (with a
 * vtkRenderStepsPass as its delegate). The pass is installed as the
 * synchronized renderers' *render pass*, not as their image-processing
 * pass: in a parallel (IceT) render, each rank then lights its own piece
 * with its own G-buffer and writes colour and depth, which IceT composites
 * by depth as it does for any render; an image-processing pass would run
 * after compositing, on a G-buffer that holds only the local piece.
 * ParaView swaps its render pass out for value passes and ray tracing and
 * back afterwards, so those keep working.
 *
 * With MPI (pvbatch under mpirun, pvserver), every frame that all ranks
 * render composites the reflective shadow maps across the ranks
 * (vtkMRGIControllerRSMCompositor), so that every rank gathers from the
 * same VPLs.
 *
 * The properties forward to the pass (vtkMRGIPass, vtkMRGIMultiresolution);
 * GetMRGIPass() gives the pass itself.
 *
 * Area lights: every visible representation of a vtkMRGIAreaLightSource
 * ("MRGI Area Light", "MRGI Textured Area Light") lights the scene as a
 * vtkMRGIAreaLight of the pass; hiding or deleting it removes the light
 * (vtkPVMRGIAreaLights.h). The server-manager proxy is
 * "MRGIRenderView" (label "MRGI Render View", MRGIRenderView.xml).
 *
 * @sa vtkMRGIPass vtkPVRenderView
 */
#ifndef vtkPVMRGIRenderView_h
#define vtkPVMRGIRenderView_h

#include "MRGIParaViewModule.h" // For export macro
#include "vtkPVRenderView.h"

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class vtkMRGIControllerRSMCompositor;
class vtkMRGIFrameBudget;
class vtkMRGIPass;
class vtkPVMRGIAreaLights;
class vtkRenderStepsPass;

class MRGIPARAVIEW_EXPORT vtkPVMRGIRenderView : public vtkPVRenderView
{
public:
  static vtkPVMRGIRenderView* New();
  vtkTypeMacro(vtkPVMRGIRenderView, vtkPVRenderView);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Global illumination on (default) or off. Off removes the pass: the view
   * renders exactly as ParaView's own render view.
   */
  void SetGlobalIllumination(bool enabled);
  vtkGetMacro(GlobalIllumination, bool);
  ///@}

  ///@{
  /** vtkMRGIPass::IndirectModes: 0 off, 1 full resolution, 2 multiresolution (default). */
  void SetIndirectMode(int mode);
  int GetIndirectMode();
  ///@}

  /** vtkMRGIMultiresolution::Presets: 0 Fast, 1 Balanced (default), 2 Accurate. */
  void SetMultiresolutionPreset(int preset);

  ///@{
  /** Forwarded to vtkMRGIPass (see there for ranges and defaults). */
  void SetNumberOfVPLs(int count);
  void SetVPLSelectionMode(int mode);
  void SetIndirectVisibility(int mode);
  void SetRSMResolution(int resolution);
  void SetIndirectStrength(double strength);
  void SetSurfaceDetail(double alpha);
  void SetDirectShadows(int mode);
  void SetUpsampleMode(int mode);
  void SetExposure(double ev);
  void SetAutoExposure(bool automatic);
  void SetToneMapping(bool enabled);
  ///@}

  /**
   * Area lights in the last render: one per visible representation of an
   * "MRGI Area Light" / "MRGI Textured Area Light" (vtkMRGIAreaLightSource;
   * see vtkPVMRGIAreaLights.h for how the view finds them).
   */
  int GetNumberOfAreaLights();

  /**
   * Area-light updates so far: a light made, or its parameters and picture
   * read again because its data changed. A render of unchanged data adds
   * none (its picture is not copied nor its texture rebuilt). Saturates
   * at VTK_INT_MAX (an int for ParaView's information property).
   */
  int GetNumberOfAreaLightUpdates();

  ///@{
  /**
   * The area lights' shadows and bounce, forwarded to vtkMRGIPass:
   * AreaLightVisibility (vtkMRGIPass::AreaLightVisibilityModes: 0 off,
   * 1 naive, 2 incremental, the default), AreaLightSpecular (Phong
   * highlights, default on) and AreaLightIndirect (the lights bounce,
   * default on).
   */
  void SetAreaLightVisibility(int mode);
  void SetAreaLightSpecular(bool specular);
  void SetAreaLightIndirect(bool indirect);
  ///@}

  ///@{
  /**
   * The area lights' voxel buffer (vtkMRGIPass::GetVoxelization(),
   * nichols-penmatsa-wyman-2010 3.3): depth slices per voxel pixel (128,
   * 256, 384 or 512; others are rounded up and clamped, as
   * vtkMRGIVoxelization::SetNumberOfSlices does) and the buffer's side in
   * voxel pixels, where 0 (the default) chooses it from the camera
   * (vtkMRGIVoxelization::AutomaticVoxelSize).
   */
  void SetAreaLightVoxelSlices(int slices);
  void SetAreaLightVoxelSide(int side);
  ///@}

  ///@{
  /**
   * What the last area-light frame used: its depth slices and voxel buffer
   * size (0 before any frame with area-light shadows). With an automatic
   * side these show what the camera chose.
   */
  int GetLastAreaLightVoxelSlices();
  int GetLastAreaLightVoxelWidth();
  int GetLastAreaLightVoxelHeight();
  ///@}

  ///@{
  /**
   * The frame-budget tuner (vtkMRGIPass::SetFrameBudget, SetErrorBudget;
   * Documentation/FrameBudget.md): with a frame budget in ms (0, the
   * default, is off) or else an error budget (relative RMS against the
   * dense reference; 0 off), every frame the tuner chooses the
   * multiresolution preset, the number of VPLs and the RSM resolution,
   * overriding the view's own properties for them. Back to 0, the view's
   * properties hold again.
   */
  void SetFrameBudget(double ms);
  void SetErrorBudget(double error);
  ///@}

  /**
   * The tuner's last choice in one line (setting, prediction, load, number
   * of switches, calibration), or "off" without a budget.
   */
  const char* GetFrameBudgetSetting();

  /**
   * Measure this machine for the tuner: renders the view 24 times (8
   * settings) and stores the fit in the tuner's cache directory
   * (vtkMRGIFrameBudget; $XDG_CACHE_HOME/mrgi or ~/.cache/mrgi). The view's
   * own settings come back afterwards. Errors name what failed.
   */
  void CalibrateFrameBudget();

  /** The pass, for scripts that set what the view's properties do not cover. */
  vtkMRGIPass* GetMRGIPass() { return this->MRGIPass; }

  /**
   * Bytes this rank sent compositing the reflective shadow maps across MPI
   * ranks in the last frame (0 with one process; a small decision message
   * when the maps did not change). See Documentation/ParaView-MPI.md.
   */
  double GetRSMCompositeBytes();

  /**
   * The backend of the render windows ParaView makes in this process: "x",
   * or "egl"/"osmesa" when the plugin supplied its headless windows.
   */
  static const char* GetHeadlessBackend();

protected:
  vtkPVMRGIRenderView();
  ~vtkPVMRGIRenderView() override;

  /**
   * Before the first render of a view that draws with MRGI's headless
   * process window's context, loads the GL functions for it (see
   * vtkPVMRGIHeadless.h): ParaView's own initialisation asks GLEW for a
   * GLX display, which an EGL context has not, and fails on every frame.
   */
  void Render(bool interactive, bool skip_rendering) override;

  /** Renderer StartEvent: brings the pass's area lights in step with the data shown. */
  static void SynchronizeAreaLights(vtkObject*, unsigned long, void* view, void*);

  bool GlobalIllumination = true;
  vtkMRGIPass* MRGIPass = nullptr;
  vtkMRGIControllerRSMCompositor* Compositor = nullptr;
  vtkRenderStepsPass* Steps = nullptr;
  std::unique_ptr<vtkPVMRGIAreaLights> AreaLights;
  unsigned long AreaLightObserver = 0;
  // The view's own preset, VPL count and RSM resolution, put back on the
  // pass when the frame and error budgets are both off again (the tuner
  // leaves its last choice on the pass).
  int UserPreset = 1;
  int UserVPLs = 256;
  int UserRSMResolution = 256;
  std::string FrameBudgetSetting;
  void RestoreUserSettings();
  // Sets the frame or error budget through `set`; restores the view's own
  // settings when that turns the tuner off.
  void SetBudget(void (vtkMRGIFrameBudget::*set)(double), double value);

private:
  vtkPVMRGIRenderView(const vtkPVMRGIRenderView&) = delete;
  void operator=(const vtkPVMRGIRenderView&) = delete;
};

#endif
