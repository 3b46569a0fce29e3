// mrgiRenderFrameBudget: mrgi-render's --frame-budget, --error-budget and
// --calibrate (internal to mrgi-render; not installed). The tuner itself is
// vtkMRGIFrameBudget; this file only checks the options against the rest of
// the command line, calibrates when asked (or when no calibration is stored
// for this GL renderer) and sets the budgets on the pass.
#ifndef mrgiRenderFrameBudget_h
#define mrgiRenderFrameBudget_h

#include "mrgiRenderOptions.h" // For Options

#include <string>

class vtkMRGIPass;
class vtkRenderWindow;

namespace mrgirender
{
// Before the frames are rendered, with the pass installed. True when nothing
// was asked or all went well; `note` then says what was done (empty: nothing).
// False with `why` naming the option and the problem.
bool SetUpFrameBudget(const Options& o, vtkRenderWindow* window, vtkMRGIPass* mrgi,
  std::string& note, std::string& why);
}

#endif
