#include "vtk_glew.h"
#include "vtkMRGIFrameBudget.h"

#include "vtkMRGIMultiresolution.h" // For the preset names

#include "vtkObjectFactory.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtksys/SystemTools.hxx"

#include "mrgi_frame_budget.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkMRGIFrameBudget);

namespace
{
using Clock = std::chrono::steady_clock;

// The settings Calibrate() renders: every preset, VPLs 16..1024, RSM
// 128..512, so that no two cost terms move together.
const mrgi_frame_setting CalibrationSettings[] = {
  { 0, 16, 128, 64 },
  { 0, 1024, 512, 128 },
  { 1, 64, 256, 256 },
  { 1, 256, 128, 64 },
  { 1, 1024, 256, 128 },
  { 2, 16, 512, 256 },
  { 2, 256, 512, 128 },
  { 2, 576, 128, 64 },
};

// A renderer string as a file name: letters and digits, the rest '_'.
std::string FileKey(const std::string& renderer)
{
  std::string key;
  for (char c : renderer)
  {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    key += keep ? c : '_';
  }
  key = key.substr(0, 96);
  return key.empty() ? std::string("unknown") : key;
}
}

struct vtkMRGIFrameBudget::Internals
{
  mrgi_frame_budget_calibration Calibration;
  bool CalibrationLoaded = false; // for Renderer
  std::string Renderer;
  std::string CacheDirectory;
  std::vector<mrgi_frame_setting> Candidates;
  bool Voxels = false;
  long long Pixels = 0;
  mrgi_frame_budget_controller Controller;
  bool ControllerValid = false;
  // The controller holds load and shape factors learnt under this
  // calibration, window size and candidate list: a new frame budget (also
  // after the tuner was off) starts from them (retarget), not from load 1.
  bool Learnt = false;
  int Chosen = -1;
  bool Within = false;
  // Timing of the frame in flight.
  bool Timing = false;
  Clock::time_point Start;
  // Calibrate(): frames are timed only, never tuned.
  bool Calibrating = false;
  std::string Summary;

  void UseCandidates(bool voxels)
  {
    if (!this->Candidates.empty() && voxels == this->Voxels)
    {
      return;
    }
    this->Voxels = voxels;
    this->Candidates.resize(MRGI_FRAME_BUDGET_MAX_CANDIDATES);
    const int32_t n = mrgi_frame_budget_default_candidates(
      voxels ? 1 : 0, this->Candidates.data(), MRGI_FRAME_BUDGET_MAX_CANDIDATES);
    this->Candidates.resize(static_cast<size_t>(n));
    this->ControllerValid = false;
    this->Learnt = false;
  }
};

//------------------------------------------------------------------------------
vtkMRGIFrameBudget::vtkMRGIFrameBudget()
  : Margin(MRGI_FRAME_BUDGET_DEFAULT_MARGIN)
  , Patience(MRGI_FRAME_BUDGET_DEFAULT_PATIENCE)
  , Internal(new Internals)
{
  mrgi_frame_budget_default(&this->Internal->Calibration);
}

//------------------------------------------------------------------------------
vtkMRGIFrameBudget::~vtkMRGIFrameBudget() = default;

//------------------------------------------------------------------------------
void vtkMRGIFrameBudget::SetFrameBudget(double ms)
{
  if (!(std::isfinite(ms) && ms >= 0.0 && ms <= 1e6))
  {
    vtkErrorMacro("frame budget " << ms << " ms: expected 0 (off) or a time in (0, 1e6] ms");
    return;
  }
  if (ms != this->FrameBudget)
  {
    this->FrameBudget = ms;
    this->Internal->ControllerValid = false;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkMRGIFrameBudget::SetErrorBudget(double error)
{
  if (!(std::isfinite(error) && error >= 0.0 && error <= 1e3))
  {
    vtkErrorMacro("error budget " << error << ": expected 0 (off) or a relative RMS error in (0, 1e3]");
    return;
  }
  if (error != this->ErrorBudget)
  {
    this->ErrorBudget = error;
    this->Internal->ControllerValid = false;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkMRGIFrameBudget::SetCacheDirectory(const std::string& directory)
{
  if (directory != this->Internal->CacheDirectory)
  {
    this->Internal->CacheDirectory = directory;
    this->Internal->CalibrationLoaded = false;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
std::string vtkMRGIFrameBudget::GetCacheDirectory() const
{
  if (!this->Internal->CacheDirectory.empty())
  {
    return this->Internal->CacheDirectory;
  }
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && *xdg)
  {
    return std::string(xdg) + "/mrgi";
  }
  const char* home = std::getenv("HOME");
  return std::string(home && *home ? home : ".") + "/.cache/mrgi";
}

//------------------------------------------------------------------------------
std::string vtkMRGIFrameBudget::GetCalibrationFile(const std::string& renderer) const
{
  return this->GetCacheDirectory() + "/frame-budget-" + FileKey(renderer) + ".txt";
}

//------------------------------------------------------------------------------
void vtkMRGIFrameBudget::BeginFrame(vtkRenderer* renderer, const Knobs& knobs)
{
  Internals& in = *this->Internal;
  if (in.Renderer.empty())
  {
    const char* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    in.Renderer = name ? name : "unknown";
  }
  in.Timing = in.Calibrating || this->IsActive();
  if (in.Timing)
  {
    in.Start = Clock::now();
  }
  if (in.Calibrating || !this->IsActive() || !knobs.Apply || !renderer)
  {
    return;
  }
  if (!in.CalibrationLoaded)
  {
    in.CalibrationLoaded = true;
    mrgi_frame_budget_default(&in.Calibration);
    const std::string path = this->GetCalibrationFile(in.Renderer);
    std::ifstream file(path);
    if (file)
    {
      std::stringstream text;
      text << file.rdbuf();
      mrgi_frame_budget_calibration read;
      mrgi_error err;
      if (mrgi_frame_budget_parse(text.str().c_str(), &read, &err) == MRGI_OK)
      {
        in.Calibration = read;
      }
      else
      {
        vtkWarningMacro("ignoring the frame-budget calibration '"
          << path << "': " << err.message << "; using the built-in defaults (Calibrate() to refresh)");
      }
    }
    snprintf(in.Calibration.renderer, sizeof(in.Calibration.renderer), "%s", in.Renderer.c_str());
    in.ControllerValid = false;
    in.Learnt = false;
  }
  const int* size = renderer->GetSize();
  const long long pixels = static_cast<long long>(std::max(1, size[0])) * std::max(1, size[1]);
  in.UseCandidates(knobs.Voxels);
  if (pixels != in.Pixels)
  {
    in.Pixels = pixels;
    in.ControllerValid = false;
    in.Learnt = false;
  }
  if (!in.ControllerValid)
  {
    mrgi_error err;
    int32_t index = 0;
    int within = 0;
    mrgi_status st = MRGI_OK;
    if (this->FrameBudget > 0)
    {
      st = in.Learnt && in.Controller.margin == this->Margin &&
          in.Controller.patience == this->Patience
        ? mrgi_frame_budget_controller_retarget(&in.Controller, &in.Calibration,
            in.Candidates.data(), static_cast<int32_t>(in.Candidates.size()), pixels,
            this->FrameBudget, nullptr, &err)
        : mrgi_frame_budget_controller_init(&in.Controller, &in.Calibration, in.Candidates.data(),
            static_cast<int32_t>(in.Candidates.size()), pixels, this->FrameBudget, this->Margin,
            this->Patience, &err);
      in.Learnt = st == MRGI_OK;
      index = in.Controller.current;
      within = st == MRGI_OK &&
        mrgi_frame_budget_controller_expected(&in.Controller, &in.Calibration,
          in.Candidates.data(), static_cast<int32_t>(in.Candidates.size()), pixels) <=
          this->FrameBudget;
    }
    else
    {
      st = mrgi_frame_budget_choose_for_error(&in.Calibration, in.Candidates.data(),
        static_cast<int32_t>(in.Candidates.size()), pixels, this->ErrorBudget, &index, &within,
        &err);
    }
    if (st != MRGI_OK)
    {
      vtkErrorMacro("frame budget: " << err.message);
      return;
    }
    in.ControllerValid = true;
    in.Chosen = index;
    in.Within = within != 0;
  }
  // The owner's setters do not invalidate anything when a value is unchanged.
  knobs.Apply(in.Candidates[static_cast<size_t>(in.Chosen)]);
}

//------------------------------------------------------------------------------
void vtkMRGIFrameBudget::EndFrame(const Knobs& knobs)
{
  Internals& in = *this->Internal;
  if (!in.Timing)
  {
    return;
  }
  in.Timing = false;
  glFinish();
  this->LastFrameMilliseconds =
    std::chrono::duration<double, std::milli>(Clock::now() - in.Start).count();
  if (in.Calibrating || this->FrameBudget <= 0 || !in.ControllerValid)
  {
    return;
  }
  int changed = 0;
  mrgi_error err;
  if (mrgi_frame_budget_controller_update(&in.Controller, &in.Calibration, in.Candidates.data(),
        static_cast<int32_t>(in.Candidates.size()), in.Pixels,
        std::max(this->LastFrameMilliseconds, 1e-3), knobs.WorkShare ? knobs.WorkShare() : -1.0,
        &changed, &err) != MRGI_OK)
  {
    vtkErrorMacro("frame budget: " << err.message);
    return;
  }
  if (changed)
  {
    in.Chosen = in.Controller.current;
    in.Within = mrgi_frame_budget_controller_expected(&in.Controller, &in.Calibration,
                  in.Candidates.data(), static_cast<int32_t>(in.Candidates.size()), in.Pixels) <=
      this->FrameBudget;
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIFrameBudget::Calibrate(vtkRenderWindow* window, const Knobs& knobs)
{
  if (!window || !knobs.Apply)
  {
    vtkErrorMacro("Calibrate needs a render window and the settings it renders with");
    return false;
  }
  Internals& in = *this->Internal;
  const bool voxels = knobs.Voxels;

  in.Calibrating = true;
  std::vector<double> terms, ms;
  bool ok = true;
  const int* size = nullptr;
  for (const mrgi_frame_setting& c : CalibrationSettings)
  {
    mrgi_frame_setting s = c;
    s.voxel_side = voxels ? s.voxel_side : 0;
    knobs.Apply(s);
    double best = -1;
    for (int f = 0; f < 3; ++f)
    {
      window->Render(); // frame 0 warms up (allocation, programs)
      if (f > 0 && this->LastFrameMilliseconds > 0)
      {
        best = best < 0 ? this->LastFrameMilliseconds : std::min(best, this->LastFrameMilliseconds);
      }
    }
    vtkRenderer* renderer = window->GetRenderers() ? window->GetRenderers()->GetFirstRenderer() : nullptr;
    size = renderer ? renderer->GetSize() : nullptr;
    double t[MRGI_FRAME_BUDGET_TERMS];
    // The gather's own count of its work (the table's share is one view at
    // 1024 x 1024; a preset's share grows at smaller windows).
    const double share = knobs.WorkShare ? knobs.WorkShare() : -1.0;
    if (best <= 0 || !size ||
      mrgi_frame_budget_terms_at(&s,
        static_cast<int64_t>(std::max(1, size[0])) * std::max(1, size[1]), share, t,
        nullptr) != MRGI_OK)
    {
      ok = false;
      break;
    }
    terms.insert(terms.end(), t, t + MRGI_FRAME_BUDGET_TERMS);
    ms.push_back(best);
  }
  in.Calibrating = false;
  if (!ok)
  {
    vtkErrorMacro("frame budget calibration: a calibration frame was not rendered or not timed "
                  "(is the pass installed on the window's first renderer?)");
    return false;
  }
  mrgi_frame_budget_calibration cal;
  mrgi_frame_budget_default(&cal);
  snprintf(cal.renderer, sizeof(cal.renderer), "%s", in.Renderer.c_str());
  mrgi_error err;
  if (mrgi_frame_budget_fit(terms.data(), ms.data(), static_cast<int32_t>(ms.size()), &cal, &err) != MRGI_OK)
  {
    vtkErrorMacro("frame budget calibration: " << err.message);
    return false;
  }
  in.Calibration = cal;
  in.CalibrationLoaded = true;
  in.ControllerValid = false;
  in.Learnt = false;

  const std::string dir = this->GetCacheDirectory();
  const std::string path = this->GetCalibrationFile(in.Renderer);
  char text[MRGI_FRAME_BUDGET_TEXT_SIZE];
  if (mrgi_frame_budget_format(&cal, text, sizeof(text), &err) != MRGI_OK)
  {
    vtkErrorMacro("frame budget calibration: " << err.message);
    return false;
  }
  const std::string temp = path + ".tmp";
  {
    const bool made = vtksys::SystemTools::MakeDirectory(dir).IsSuccess();
    std::ofstream out(temp, std::ios::trunc);
    if (!made || !(out << text) || !(out.flush()))
    {
      vtkErrorMacro("frame budget calibration: cannot write '" << temp << "' (is " << dir
                                                               << " writable?); the fit is used "
                                                                  "for this session only");
      return false;
    }
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0)
  {
    vtkErrorMacro("frame budget calibration: cannot rename '" << temp << "' to '" << path << "'");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkMRGIFrameBudget::GetPreset() const
{
  const Internals& in = *this->Internal;
  return in.Chosen >= 0 ? in.Candidates[static_cast<size_t>(in.Chosen)].preset : -1;
}

int vtkMRGIFrameBudget::GetNumberOfVPLs() const
{
  const Internals& in = *this->Internal;
  return in.Chosen >= 0 ? in.Candidates[static_cast<size_t>(in.Chosen)].vpls : 0;
}

int vtkMRGIFrameBudget::GetRSMResolution() const
{
  const Internals& in = *this->Internal;
  return in.Chosen >= 0 ? in.Candidates[static_cast<size_t>(in.Chosen)].rsm_size : 0;
}

int vtkMRGIFrameBudget::GetVoxelSide() const
{
  const Internals& in = *this->Internal;
  return in.Chosen >= 0 ? in.Candidates[static_cast<size_t>(in.Chosen)].voxel_side : 0;
}

double vtkMRGIFrameBudget::GetPredictedMilliseconds() const
{
  const Internals& in = *this->Internal;
  if (in.Chosen < 0)
  {
    return -1;
  }
  if (this->FrameBudget > 0 && in.ControllerValid)
  {
    return mrgi_frame_budget_controller_expected(&in.Controller, &in.Calibration,
      in.Candidates.data(), static_cast<int32_t>(in.Candidates.size()), in.Pixels);
  }
  return mrgi_frame_budget_predict(
    &in.Calibration, &in.Candidates[static_cast<size_t>(in.Chosen)], in.Pixels);
}

double vtkMRGIFrameBudget::GetPredictedError() const
{
  const Internals& in = *this->Internal;
  return in.Chosen >= 0 ? mrgi_frame_budget_error(&in.Candidates[static_cast<size_t>(in.Chosen)])
                        : -1;
}

bool vtkMRGIFrameBudget::GetWithinBudget() const
{
  return this->Internal->Within;
}

double vtkMRGIFrameBudget::GetLoadFactor() const
{
  const Internals& in = *this->Internal;
  return this->FrameBudget > 0 && in.ControllerValid ? in.Controller.load : 1.0;
}

double vtkMRGIFrameBudget::GetShapeFactor() const
{
  const Internals& in = *this->Internal;
  return this->FrameBudget > 0 && in.ControllerValid ? in.Controller.shape : 1.0;
}

int vtkMRGIFrameBudget::GetNumberOfSwitches() const
{
  const Internals& in = *this->Internal;
  return this->FrameBudget > 0 && in.ControllerValid ? in.Controller.switches : 0;
}

int vtkMRGIFrameBudget::GetCalibrationFrames() const
{
  return this->Internal->Calibration.frames;
}

std::string vtkMRGIFrameBudget::GetRenderer() const
{
  return this->Internal->Renderer;
}

//------------------------------------------------------------------------------
double vtkMRGIFrameBudget::PredictError(int preset, int vpls, int rsmSize, int voxelSide)
{
  const mrgi_frame_setting s = { preset, vpls, rsmSize, voxelSide };
  return mrgi_frame_budget_error(&s);
}

//------------------------------------------------------------------------------
std::string vtkMRGIFrameBudget::GetSummary() const
{
  if (this->GetPreset() < 0)
  {
    return "frame budget: off";
  }
  char line[512];
  char voxels[32] = "-";
  if (this->GetVoxelSide() > 0)
  {
    snprintf(voxels, sizeof(voxels), "%d", this->GetVoxelSide());
  }
  snprintf(line, sizeof(line),
    "frame budget: %s %g%s: preset %s, vpls %d, rsm %d, voxels %s; predicted %.1f ms, "
    "error %.4f%s; load %.2f, shape %.2f, switches %d; calibration: %s",
    this->FrameBudget > 0 ? "time" : "error",
    this->FrameBudget > 0 ? this->FrameBudget : this->ErrorBudget,
    this->FrameBudget > 0 ? " ms" : "", vtkMRGIMultiresolution::GetPresetName(this->GetPreset()),
    this->GetNumberOfVPLs(), this->GetRSMResolution(), voxels, this->GetPredictedMilliseconds(),
    this->GetPredictedError(), this->GetWithinBudget() ? "" : " (budget not reachable)",
    this->GetLoadFactor(), this->GetShapeFactor(), this->GetNumberOfSwitches(),
    this->GetCalibrationFrames() > 0 ? "measured" : "built-in defaults");
  return line;
}

//------------------------------------------------------------------------------
void vtkMRGIFrameBudget::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FrameBudget: " << this->FrameBudget << " ms\n";
  os << indent << "ErrorBudget: " << this->ErrorBudget << "\n";
  os << indent << "Margin: " << this->Margin << "\n";
  os << indent << "Patience: " << this->Patience << "\n";
  os << indent << "CacheDirectory: " << this->GetCacheDirectory() << "\n";
  os << indent << "LastFrameMilliseconds: " << this->LastFrameMilliseconds << "\n";
  const mrgi_frame_budget_calibration& c = this->Internal->Calibration;
  os << indent << "Calibration: " << c.frames << " frames, " << c.coef[0] << " ms + " << c.coef[1]
     << " ms/Mpixel + " << c.coef[2] << " ms/G pairs + " << c.coef[3] << " ms/M RSM texels + "
     << c.coef[4] << " ms/G voxel steps\n";
  os << indent << this->GetSummary() << "\n";
}
