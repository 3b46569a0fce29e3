/**
 * @class   vtkMRGIReferenceRenderer
 * @brief   Ground truth for a VTK renderer: direct light and one diffuse
 *          bounce with exact visibility, computed on the CPU (Embree).
 *
 * The renderer's visible opaque actors (vtkPolyDataMapper and
 * vtkCompositePolyDataMapper2 inputs, triangulated, with their actor
 * transforms), its lights (as placed for the last frame, so camera lights
 * and headlights work) and its camera are handed to the C core's Monte Carlo
 * renderer (mrgi_reference.h), which uses VTK's own light model (no distance
 * attenuation, spot cones and exponents, two-sided Lambertian surfaces).
 *
 * Albedo per actor: the property's diffuse colour times Diffuse; actors
 * coloured by scalars use the mean mapped colour (the ground truth has one
 * albedo per mesh). An actor with Ambient > 0 emits Ambient x AmbientColor.
 * Positional-light attenuation other than VTK's default (1, 0, 0) is ignored.
 *
 * Images are float RGB vtkImageData with VTK's bottom-up rows, the size of
 * the renderer's viewport unless Width/Height are set.
 *
 * Progress and cancel: Render() fires StartEvent, then after each pass
 * vtkCommand::ProgressEvent (call data: a double, the fraction done; also
 * GetProgress()), with GetProgressPasses(), GetProgressPixelError() (the
 * stopping statistic), GetProgressRelativeError() and
 * GetProgressSecondsLeft() up to date, then EndEvent. An observer (or another
 * thread) that sets AbortRender stops the render after the current pass:
 * Render() then returns true with the images of the passes done (consistent:
 * every pixel has the same number of passes) and GetCancelled() is true.
 * Render() clears AbortRender when it starts.
 */
#ifndef vtkMRGIReferenceRenderer_h
#define vtkMRGIReferenceRenderer_h

#include "MRGIRenderingValidationModule.h" // For export macro
#include "vtkObject.h"

#include "vtkSmartPointer.h" // For vtkSmartPointer
#include <string>             // For std::string
#include <vector>             // For std::vector

class vtkImageData;
class vtkMRGIAreaLight;
class vtkRenderer;
struct mrgi_scene;
struct mrgi_reference_progress;

class MRGIRENDERINGVALIDATION_EXPORT vtkMRGIReferenceRenderer : public vtkObject
{
public:
  static vtkMRGIReferenceRenderer* New();
  vtkTypeMacro(vtkMRGIReferenceRenderer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Image size; 0 (default) takes the renderer's viewport size. */
  vtkSetClampMacro(Width, int, 0, 16384);
  vtkGetMacro(Width, int);
  vtkSetClampMacro(Height, int, 0, 16384);
  vtkGetMacro(Height, int);
  ///@}

  ///@{
  /** Bounce rays per pixel per pass (default 16). */
  vtkSetClampMacro(IndirectSamples, int, 0, 4096);
  vtkGetMacro(IndirectSamples, int);
  ///@}

  ///@{
  /**
   * The stopping rule (mrgi_reference.h, mrgi_reference_noise.h): stop once
   * the TargetPercentile quantile of the per-pixel relative standard error
   * (each pixel's standard error over max(its value, the image's mean
   * pixel value)) is at or below TargetRelativeError, in the indirect image
   * and, with area lights, in the direct image. 0 = run MaxPasses.
   * Defaults: the core's, 0.02 at the 95th percentile, a converged image
   * (Documentation/Fidelity.md).
   */
  vtkSetClampMacro(TargetRelativeError, double, 0.0, 1.0);
  vtkGetMacro(TargetRelativeError, double);
  vtkSetClampMacro(TargetPercentile, double, 0.001, 1.0);
  vtkGetMacro(TargetPercentile, double);
  ///@}

  ///@{
  /** Most progressive passes (default the core's, 4096). */
  vtkSetClampMacro(MaxPasses, int, 1, 100000);
  vtkGetMacro(MaxPasses, int);
  ///@}

  ///@{
  /** Exact visibility between bounce points (default on); off = the RSM assumption. */
  vtkSetMacro(SecondaryVisibility, bool);
  vtkGetMacro(SecondaryVisibility, bool);
  vtkBooleanMacro(SecondaryVisibility, bool);
  ///@}

  ///@{
  /** Shadows in the direct image (default on; VTK's own direct light has none). */
  vtkSetMacro(Shadows, bool);
  vtkGetMacro(Shadows, bool);
  vtkBooleanMacro(Shadows, bool);
  ///@}

  /** Where a pixel's primary rays cross it (mrgi_reference.h, MRGI_REFERENCE_PIXEL_*). */
  enum PixelFilterType
  {
    PixelBox = 0,   ///< jittered over the pixel square: the pixel's mean (default)
    PixelCenter = 1 ///< through the pixel's centre, as a rasterizer samples it
  };

  ///@{
  /**
   * PixelBox (default) averages each pixel over its area; PixelCenter
   * samples its centre, the truth of a GPU image without multisampling:
   * against it, silhouettes and shadow edges differ only where the light is
   * wrong, not because a box-filtered edge pixel is partly covered.
   */
  vtkSetClampMacro(PixelFilter, int, PixelBox, PixelCenter);
  vtkGetMacro(PixelFilter, int);
  void SetPixelFilterToBox() { this->SetPixelFilter(PixelBox); }
  void SetPixelFilterToCenter() { this->SetPixelFilter(PixelCenter); }
  ///@}

  ///@{
  /** Random seed (default 1) and worker threads (0 = all CPUs). */
  vtkSetMacro(Seed, vtkTypeUInt64);
  vtkGetMacro(Seed, vtkTypeUInt64);
  vtkSetClampMacro(Threads, int, 0, 1024);
  vtkGetMacro(Threads, int);
  ///@}

  /**
   * Render the ground truth of `renderer`; false with GetLastErrorMessage()
   * on error. A cancelled render (AbortRender) returns true: see GetCancelled().
   */
  bool Render(vtkRenderer* renderer);

  ///@{
  /**
   * Set (e.g. from a ProgressEvent observer) to stop after the current pass.
   * Render() sets it to false when it starts.
   */
  vtkSetMacro(AbortRender, bool);
  vtkGetMacro(AbortRender, bool);
  vtkBooleanMacro(AbortRender, bool);
  ///@}

  /** Whether the last Render() was stopped by AbortRender (its images hold GetPasses() passes). */
  vtkGetMacro(Cancelled, bool);

  ///@{
  /**
   * The render in progress (after the pass last reported; ProgressEvent):
   * fraction done in [0, 1] (passes done over the passes expected, fewer
   * than MaxPasses when the error falls to the target sooner), passes done,
   * the stopping statistic so far (the per-pixel error, as GetPixelError();
   * +inf after one pass), the relative error of the image mean (as
   * GetRelativeError()) and the estimated seconds left (the statistic falls
   * as 1/sqrt(passes)).
   */
  vtkGetMacro(Progress, double);
  vtkGetMacro(ProgressPasses, int);
  vtkGetMacro(ProgressPixelError, double);
  vtkGetMacro(ProgressRelativeError, double);
  vtkGetMacro(ProgressSecondsLeft, double);
  ///@}

  ///@{
  /**
   * Area lights (vtkMRGIAreaLight) lighting the direct image, diffuse, with
   * exact visibility when Shadows is on (mrgi_reference_render_area_lights):
   * the ground truth of vtkMRGIPass's area lights. They light nothing
   * unless added here (they are not VTK lights).
   */
  void AddAreaLight(vtkMRGIAreaLight* light);
  void RemoveAllAreaLights();
  int GetNumberOfAreaLights() const { return static_cast<int>(this->AreaLights.size()); }
  ///@}

  ///@{
  /** Shadow rays per area light per pixel per pass (default 16). */
  vtkSetClampMacro(AreaLightSamples, int, 1, 4096);
  vtkGetMacro(AreaLightSamples, int);
  ///@}

  /** Results of the last Render(). */
  vtkImageData* GetDirectImage() { return this->DirectImage; }
  vtkImageData* GetIndirectImage() { return this->IndirectImage; }
  /** Relative standard error of the indirect image's mean (reported, not the stopping rule). */
  vtkGetMacro(RelativeError, double);
  /** The stopping statistic reached: the larger of the indirect's and (area lights) the direct's per-pixel error. */
  vtkGetMacro(PixelError, double);
  vtkGetMacro(Passes, int);
  vtkGetMacro(Seconds, double);
  vtkGetMacro(TriangleCount, vtkIdType);
  const char* GetLastErrorMessage() { return this->LastErrorMessage.c_str(); }

#ifndef __VTK_WRAP__
  /**
   * The renderer's scene as the core sees it (meshes, lights, camera).
   * `out` is created by the call and owned by the caller (mrgi_scene_destroy).
   */
  static bool ExportScene(vtkRenderer* renderer, mrgi_scene* out, std::string& why);
#endif

protected:
  vtkMRGIReferenceRenderer();
  ~vtkMRGIReferenceRenderer() override;

  int Width = 0;
  int Height = 0;
  int IndirectSamples = 16;
  double TargetRelativeError; // the core's default, set by the constructor
  double TargetPercentile;
  int MaxPasses;
  bool SecondaryVisibility = true;
  bool Shadows = true;
  int PixelFilter = PixelBox;
  vtkTypeUInt64 Seed = 1;
  int Threads = 0;

  vtkImageData* DirectImage;
  vtkImageData* IndirectImage;
  double RelativeError = 0;
  double PixelError = 0;
  int Passes = 0;
  double Seconds = 0;
  vtkIdType TriangleCount = 0;
  std::string LastErrorMessage;
  std::vector<vtkSmartPointer<vtkMRGIAreaLight>> AreaLights;
  int AreaLightSamples = 16;
  bool AbortRender = false;
  bool Cancelled = false;
  double Progress = 0;
  int ProgressPasses = 0;
  double ProgressRelativeError = 0;
  double ProgressPixelError = 0;
  double ProgressSecondsLeft = 0;

private:
  static int ReportProgress(void* self, const struct mrgi_reference_progress* progress);

  vtkMRGIReferenceRenderer(const vtkMRGIReferenceRenderer&) = delete;
  void operator=(const vtkMRGIReferenceRenderer&) = delete;
};

#endif
