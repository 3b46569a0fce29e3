/**
 * @class   vtkMRGIFrameBudget
 * @brief   The frame-budget tuner of vtkMRGIPass (issue 17 part 4): chooses
 *          the multiresolution preset, VPL count, RSM size and voxel size
 *          of each frame to meet a frame time, or an error, from a cost
 *          model this machine measured once.
 *
 * The model, the error proxy, the choice and the hysteresis are the C core's
 * (mrgi_frame_budget.h); this class holds the state, hands the choice to
 * its owner's Knobs before the frame renders and times the frame after it
 * (wall time up to a glFinish, so that a GPU running behind is counted). It
 * knows no pass: vtkMRGIPass owns it and supplies the Knobs.
 *
 * - SetFrameBudget(ms) > 0: the setting of least predicted error whose
 *   predicted time fits; then, during interaction, a controller follows
 *   the measured times: it corrects the model by a load factor every frame
 *   (what a frame costs changes with the view) and chooses again only when
 *   the expected time stays outside the band around the budget (Margin) for
 *   Patience frames in a row, so that a noisy constant load does not switch.
 * - SetErrorBudget(e) > 0 (and no frame budget): the cheapest setting whose
 *   predicted relative RMS error against the dense reference is at most e.
 *   With both set, the frame budget decides.
 * - 0 (the default for both): the tuner does nothing and the pass's own
 *   settings hold. While it is on, it overrides SetNumberOfVPLs,
 *   SetRSMResolution, the multiresolution preset and (when the indirect
 *   light uses voxels) the voxel side every frame.
 *
 * Calibration: Calibrate(window, knobs) (vtkMRGIPass::Calibrate) renders 8 settings (one warm-up and
 * two timed frames each, the faster counts), fits the model (least squares,
 * non-negative) and stores it in CacheDirectory (default
 * $XDG_CACHE_HOME/mrgi, else ~/.cache/mrgi) under a file named after the GL
 * renderer string. Later frames load it once; a missing file gives the
 * built-in llvmpipe defaults, a corrupt one a warning naming the problem and
 * the defaults. Calibrate() again to refresh.
 */
#ifndef vtkMRGIFrameBudget_h
#define vtkMRGIFrameBudget_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include "mrgi_frame_budget.h" // For mrgi_frame_setting

#include <functional> // For std::function
#include <memory>     // For std::unique_ptr
#include <string>     // For std::string

class vtkRenderer;
class vtkRenderWindow;

class MRGIRENDERING_EXPORT vtkMRGIFrameBudget : public vtkObject
{
public:
  static vtkMRGIFrameBudget* New();
  vtkTypeMacro(vtkMRGIFrameBudget, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Target frame time in ms; 0 (default) = off. Negative or non-finite:
   * refused (error). A new budget, also after the tuner was off, starts from
   * the load and shape factors learnt so far
   * (mrgi_frame_budget_controller_retarget()); a new calibration, window
   * size, Margin or Patience starts over from the calibration.
   */
  void SetFrameBudget(double ms);
  vtkGetMacro(FrameBudget, double);
  ///@}

  ///@{
  /** Target relative RMS error; 0 (default) = off. Outside [0, 1e3] or non-finite: refused. */
  void SetErrorBudget(double error);
  vtkGetMacro(ErrorBudget, double);
  ///@}

  /** True when a frame or error budget is set. */
  bool IsActive() const { return this->FrameBudget > 0 || this->ErrorBudget > 0; }

  ///@{
  /** Hysteresis: relative miss that counts (default 0.05), misses in a row that switch (default 3). */
  vtkSetClampMacro(Margin, double, 0.01, 10.0);
  vtkGetMacro(Margin, double);
  vtkSetClampMacro(Patience, int, 1, 1000);
  vtkGetMacro(Patience, int);
  ///@}

  ///@{
  /** Where calibrations are stored; empty (default): $XDG_CACHE_HOME/mrgi or ~/.cache/mrgi. */
  void SetCacheDirectory(const std::string& directory);
  std::string GetCacheDirectory() const;
  ///@}

  /** The calibration file for a GL renderer string (in GetCacheDirectory()). */
  std::string GetCalibrationFile(const std::string& renderer) const;

#ifndef __VTK_WRAP__
  /** What the tuner turns, supplied by its owner (vtkMRGIPass). */
  struct Knobs
  {
    /** The indirect light uses voxel visibility, so the voxel side is a knob. */
    bool Voxels = false;
    /** Applies a setting: preset, VPL count, RSM size, and the voxel side when > 0. */
    std::function<void(const mrgi_frame_setting&)> Apply;
    /** The last frame's gathered texels over valid pixels (the share of the
     *  full gather's work it did); not > 0 when unknown. May be empty. */
    std::function<double()> WorkShare;
  };

  /**
   * Measure this machine: renders `window` with 8 settings applied through
   * `knobs` (3 frames each), fits the cost model and writes the calibration
   * file. The caller restores its own settings (vtkMRGIPass::Calibrate does).
   * False (with an error naming why) when a frame fails or the file cannot
   * be written; the fit is still used.
   */
  bool Calibrate(vtkRenderWindow* window, const Knobs& knobs);

  ///@{
  /**
   * Called by the owner's render around each frame: BeginFrame applies the
   * chosen setting through `knobs` (when a budget is set), EndFrame times the
   * frame and feeds the controller.
   */
  void BeginFrame(vtkRenderer* renderer, const Knobs& knobs);
  void EndFrame(const Knobs& knobs);
  ///@}
#endif

  ///@{
  /** The last chosen setting (-1 / 0 before a budgeted frame). Voxel side 0: no voxels. */
  int GetPreset() const;
  int GetNumberOfVPLs() const;
  int GetRSMResolution() const;
  int GetVoxelSide() const;
  ///@}

  ///@{
  /** The model's predicted ms (under the controller's load and shape factors) and error of the chosen setting. */
  double GetPredictedMilliseconds() const;
  double GetPredictedError() const;
  ///@}
  /** Whether the chosen setting is predicted to fit the budget (false: the cheapest / most accurate). */
  bool GetWithinBudget() const;
  /** measured / predicted time, as the controller holds it (1 at start). */
  double GetLoadFactor() const;
  /** Measured / modelled cost of the setting-dependent terms, as the controller learnt it (1 at start). */
  double GetShapeFactor() const;
  /** Times the controller changed the setting since the budget was set. */
  int GetNumberOfSwitches() const;
  /** Wall time of the last frame (ms, glFinish included); -1 before one. */
  vtkGetMacro(LastFrameMilliseconds, double);
  /** Frames the calibration in use was fitted from; 0 for the built-in defaults. */
  int GetCalibrationFrames() const;
  /** The GL renderer the calibration in use is for (empty before a frame). */
  std::string GetRenderer() const;
  /** The core's error proxy (mrgi_frame_budget_error) for any setting; -1 for a bad one. */
  static double PredictError(int preset, int vpls, int rsmSize, int voxelSide);
  /** One line: the chosen setting, prediction, load, switches, calibration. */
  std::string GetSummary() const;

#ifndef __VTK_WRAP__
  /** Calls BeginFrame on construction and EndFrame on destruction (every return path of Render). */
  class FrameScope
  {
  public:
    FrameScope(vtkMRGIFrameBudget* tuner, vtkRenderer* renderer, const Knobs& knobs)
      : Tuner(tuner)
      , FrameKnobs(knobs)
    {
      this->Tuner->BeginFrame(renderer, this->FrameKnobs);
    }
    ~FrameScope() { this->Tuner->EndFrame(this->FrameKnobs); }
    FrameScope(const FrameScope&) = delete;
    FrameScope& operator=(const FrameScope&) = delete;

  private:
    vtkMRGIFrameBudget* Tuner;
    Knobs FrameKnobs;
  };
#endif

protected:
  vtkMRGIFrameBudget();
  ~vtkMRGIFrameBudget() override;

  double FrameBudget = 0.0;
  double ErrorBudget = 0.0;
  double Margin;
  int Patience;
  double LastFrameMilliseconds = -1.0;

private:
  vtkMRGIFrameBudget(const vtkMRGIFrameBudget&) = delete;
  void operator=(const vtkMRGIFrameBudget&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
