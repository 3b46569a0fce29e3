/**
 * @class   vtkMRGIPass
 * @brief   The MRGI render pass: renders the scene into float buffers and
 *          composites it, timing every stage on the GPU.
 *
 * vtkMRGIPass is what an application installs, the way it installs
 * vtkSSAOPass:
 * @code
 * vtkNew<vtkRenderStepsPass> steps;
 * vtkNew<vtkMRGIPass> gi;
 * gi->SetDelegatePass(steps);
 * renderer->SetPass(gi);
 * @endcode
 *
 * Each frame it renders the delegate (VTK's own direct lighting) into an
 * RGBA32F colour target and a 32-bit depth texture owned by the pass, then
 * composites that to the framebuffer VTK was drawing into, depth included.
 * The float colour buffer is the HDR image: GetColorBuffer() reads it back
 * unclamped (VTK's window framebuffers are RGBA8, so EXR output must come from
 * here, never from vtkWindowToImageFilter).
 *
 * Stage timings: with StageTimingEnabled on, every stage is bracketed by
 * vtkRenderTimerLog events (GL timer queries) named "MRGI <stage>".
 * FetchStageTimings() collects the latest completed frame; GetStageName() and
 * GetStageTimeMilliseconds() report it. The window's timer log must be
 * logging when a frame starts: switch it on before the first render
 * (`window->GetRenderTimer()->SetLoggingEnabled(true)`), or let the first
 * FetchStageTimings() switch it on, in which case timing starts with the
 * next frame.
 */
#ifndef vtkMRGIPass_h
#define vtkMRGIPass_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkImageProcessingPass.h"

#include <string> // For std::string
#include <vector> // For std::vector

class vtkImageData;
class vtkOpenGLFramebufferObject;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkRenderTimerLog;
class vtkRenderWindow;
class vtkTextureObject;

class MRGIRENDERING_EXPORT vtkMRGIPass : public vtkImageProcessingPass
{
public:
  static vtkMRGIPass* New();
  vtkTypeMacro(vtkMRGIPass, vtkImageProcessingPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Render the delegate into the pass's buffers and composite the result. */
  void Render(const vtkRenderState* s) override;

  /** Free every GL resource the pass holds. */
  void ReleaseGraphicsResources(vtkWindow* w) override;

  ///@{
  /**
   * Bracket each stage with GPU timer queries (vtkRenderTimerLog). Off by
   * default: the queries are cheap, but they are the application's choice.
   */
  vtkSetMacro(StageTimingEnabled, bool);
  vtkGetMacro(StageTimingEnabled, bool);
  vtkBooleanMacro(StageTimingEnabled, bool);
  ///@}

  /**
   * Collect GPU stage times of the most recent frame whose timer queries have
   * completed. With wait = true the current frame is closed and the GPU is
   * drained first, so the frame just rendered is the one reported (for
   * one-shot renders; interactive applications pass false and get the latest
   * completed frame without stalling). Returns the number of stages found;
   * 0 when timing is off, unsupported, or no frame has completed yet.
   */
  int FetchStageTimings(vtkRenderWindow* window, bool wait);

  ///@{
  /** The stages collected by the last FetchStageTimings(), in render order. */
  int GetNumberOfStages() const { return static_cast<int>(this->StageNames.size()); }
  const char* GetStageName(int stage) const;
  double GetStageTimeMilliseconds(int stage) const;
  ///@}

  /**
   * Copy the last frame's HDR colour buffer (RGBA, float, unclamped, origin
   * at the bottom-left as VTK images are) into `image`. Needs the render
   * window's context; returns false (with an error) before the first render.
   */
  bool GetColorBuffer(vtkRenderWindow* window, vtkImageData* image);

  /** Width and height of the buffers of the last frame (0 before the first). */
  vtkGetVector2Macro(BufferSize, int);

protected:
  vtkMRGIPass();
  ~vtkMRGIPass() override;

  /** Create or resize the colour/depth targets for a w x h viewport. */
  void PrepareBuffers(vtkOpenGLRenderWindow* renWin, int w, int h);
  void RenderScene(const vtkRenderState* s, int w, int h);
  void RenderComposite(vtkOpenGLRenderWindow* renWin);

  bool StageTimingEnabled = false;
  int BufferSize[2] = { 0, 0 };

  vtkOpenGLFramebufferObject* FrameBuffer = nullptr;
  vtkTextureObject* ColorTexture = nullptr;
  vtkTextureObject* DepthTexture = nullptr;
  vtkOpenGLQuadHelper* CompositeQuad = nullptr;

  std::vector<std::string> StageNames;
  std::vector<double> StageTimes;

private:
  vtkMRGIPass(const vtkMRGIPass&) = delete;
  void operator=(const vtkMRGIPass&) = delete;
};

#endif
