// vtkMRGIPass's per-stage GPU timings: reading the timer queries its stages
// logged (vtkMRGIShaderUtilities::ScopedStage) back after a frame. The class
// is documented in vtkMRGIPass.h.
#include "vtk_glew.h"

#include "vtkMRGIPass.h"

#include "vtkMRGIShaderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderTimerLog.h"
#include "vtkRenderWindow.h"

//------------------------------------------------------------------------------
int vtkMRGIPass::FetchStageTimings(vtkRenderWindow* window, bool wait)
{
  vtkRenderTimerLog* timer = window ? window->GetRenderTimer() : nullptr;
  if (!timer || !this->StageTimingEnabled || !timer->IsSupported())
  {
    return 0;
  }
  if (!timer->GetLoggingEnabled())
  {
    // Between frames is the safe moment to switch logging on; the next frame
    // is the first one timed.
    timer->SetLoggingEnabled(true);
    return 0;
  }
  if (wait)
  {
    // Close the frame just rendered and drain the GPU so its queries are done.
    window->MakeCurrent();
    timer->MarkFrame();
    if (vtkOpenGLRenderWindow::SafeDownCast(window))
    {
      glFinish();
    }
  }
  return vtkMRGIShaderUtilities::CollectStageTimes(timer, this->StageNames, this->StageTimes)
    ? this->GetNumberOfStages()
    : 0;
}

//------------------------------------------------------------------------------
const char* vtkMRGIPass::GetStageName(int stage) const
{
  if (stage < 0 || stage >= this->GetNumberOfStages())
  {
    return nullptr;
  }
  return this->StageNames[static_cast<size_t>(stage)].c_str();
}

//------------------------------------------------------------------------------
double vtkMRGIPass::GetStageTimeMilliseconds(int stage) const
{
  if (stage < 0 || stage >= this->GetNumberOfStages())
  {
    return -1.0;
  }
  return this->StageTimes[static_cast<size_t>(stage)];
}

