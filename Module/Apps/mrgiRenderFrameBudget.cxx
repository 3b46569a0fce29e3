// mrgiRenderFrameBudget: see the header.
#include "mrgiRenderFrameBudget.h"

#include "vtkMRGIFrameBudget.h"
#include "vtkMRGIPass.h"
#include "vtkRenderWindow.h"

#include <cstdio>
#include <fstream>

namespace mrgirender
{
bool SetUpFrameBudget(const Options& o, vtkRenderWindow* window, vtkMRGIPass* mrgi,
  std::string& note, std::string& why)
{
  note.clear();
  const bool budget = o.FrameBudget > 0 || o.ErrorBudget > 0;
  if (!budget && !o.Calibrate)
  {
    return true;
  }
  const char* option = o.FrameBudget > 0 ? "--frame-budget"
    : o.ErrorBudget > 0                  ? "--error-budget"
                                         : "--calibrate";
  if (!o.GI || !o.Multires)
  {
    why = std::string(option) +
      " tunes the multiresolution indirect light: it needs --gi on (or multires), not " +
      (o.GI ? "--gi full" : "--gi off");
    return false;
  }
  vtkMRGIFrameBudget* tuner = mrgi->GetFrameBudgetTuner();
  bool calibrate = o.Calibrate;
  if (!calibrate)
  {
    // One frame tells the GL renderer, and so the calibration file.
    window->Render();
    const std::string path = tuner->GetCalibrationFile(tuner->GetRenderer());
    calibrate = !std::ifstream(path).good();
  }
  if (calibrate)
  {
    if (!mrgi->Calibrate(window))
    {
      why = std::string(option) + ": the calibration failed (see the error above)";
      return false;
    }
    note = "frame budget: calibrated (" + tuner->GetCalibrationFile(tuner->GetRenderer()) + ")";
  }
  mrgi->SetFrameBudget(o.FrameBudget);
  mrgi->SetErrorBudget(o.ErrorBudget);
  return true;
}
}
