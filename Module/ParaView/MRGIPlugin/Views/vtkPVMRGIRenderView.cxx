#include "vtkPVMRGIRenderView.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkMRGIControllerRSMCompositor.h"
#include "vtkMRGIFrameBudget.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIVoxelization.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPVMRGIAreaLights.h"
#include "vtkPVMRGIHeadless.h"
#include "vtkPVSynchronizedRenderer.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

vtkStandardNewMacro(vtkPVMRGIRenderView);

//------------------------------------------------------------------------------
vtkPVMRGIRenderView::vtkPVMRGIRenderView()
{
  this->Steps = vtkRenderStepsPass::New();
  this->MRGIPass = vtkMRGIPass::New();
  this->Compositor = vtkMRGIControllerRSMCompositor::New();
  this->MRGIPass->SetDelegatePass(this->Steps);
  // ParaView's view exposure is MRGI's fixed EV 0 and no tone curve by
  // default: the image is the HDR result clamped, as VTK's own view shows
  // direct light. Automatic exposure would differ between MPI ranks.
  this->MRGIPass->SetAutoExposure(false);
  this->SynchronizedRenderers->SetRenderPass(this->MRGIPass);

  // The area lights are read from the data each representation delivered,
  // which ParaView sets on the mappers during Render(), before the
  // renderer draws: the renderer's StartEvent is the first moment they
  // are all there and the last before the pass runs.
  this->AreaLights.reset(new vtkPVMRGIAreaLights);
  vtkNew<vtkCallbackCommand> observer;
  observer->SetCallback(&vtkPVMRGIRenderView::SynchronizeAreaLights);
  observer->SetClientData(this);
  this->AreaLightObserver = this->GetRenderer()->AddObserver(vtkCommand::StartEvent, observer);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SynchronizeAreaLights(vtkObject*, unsigned long, void* view, void*)
{
  auto* self = static_cast<vtkPVMRGIRenderView*>(view);
  self->AreaLights->Synchronize(self->GetRenderer(), self->MRGIPass, self);
}

//------------------------------------------------------------------------------
int vtkPVMRGIRenderView::GetNumberOfAreaLights()
{
  return this->AreaLights->GetNumberOfLights();
}

//------------------------------------------------------------------------------
int vtkPVMRGIRenderView::GetNumberOfAreaLightUpdates()
{
  const vtkIdType updates = this->AreaLights->GetNumberOfUpdates();
  return updates > VTK_INT_MAX ? VTK_INT_MAX : static_cast<int>(updates);
}

//------------------------------------------------------------------------------
vtkPVMRGIRenderView::~vtkPVMRGIRenderView()
{
  if (vtkRenderer* renderer = this->GetRenderer())
  {
    renderer->RemoveObserver(this->AreaLightObserver);
  }
  if (this->SynchronizedRenderers && this->SynchronizedRenderers->GetRenderPass() == this->MRGIPass)
  {
    this->SynchronizedRenderers->SetRenderPass(nullptr);
  }
  // The window outlives the view's passes only until the superclass's
  // destructor: free the pass's GL objects while its context exists.
  if (vtkRenderWindow* window = this->GetRenderWindow())
  {
    this->MRGIPass->ReleaseGraphicsResources(window); // the area lights' textures too
  }
  this->MRGIPass->SetRSMCompositor(nullptr);
  this->AreaLights->RemoveAll(this->MRGIPass);
  this->MRGIPass->Delete();
  this->Compositor->Delete();
  this->Steps->Delete();
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::Render(bool interactive, bool skip_rendering)
{
  vtkPVMRGIPrepareHeadlessView(vtkOpenGLRenderWindow::SafeDownCast(this->GetRenderWindow()));
  // Every rank must see the same VPLs: when this frame is rendered by all
  // ranks and composited by IceT, the reflective shadow maps are composited
  // across them (collective). ParaView decided in Update(), identically on
  // every rank, whether this frame is distributed; a frame rendered on one
  // process only must not start a collective.
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const bool distributed = controller && controller->GetNumberOfProcesses() > 1 &&
    (interactive ? this->GetUseDistributedRenderingForLODRender()
                 : this->GetUseDistributedRenderingForRender());
  if (distributed)
  {
    this->Compositor->SetController(controller);
    this->MRGIPass->SetRSMCompositor(this->Compositor);
  }
  else
  {
    this->MRGIPass->SetRSMCompositor(nullptr);
  }
  this->Superclass::Render(interactive, skip_rendering);
}

//------------------------------------------------------------------------------
double vtkPVMRGIRenderView::GetRSMCompositeBytes()
{
  return static_cast<double>(this->MRGIPass->GetRSMCompositeBytes());
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetGlobalIllumination(bool enabled)
{
  if (this->GlobalIllumination == enabled)
  {
    return;
  }
  this->GlobalIllumination = enabled;
  this->SynchronizedRenderers->SetRenderPass(enabled ? this->MRGIPass : nullptr);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetIndirectMode(int mode)
{
  this->MRGIPass->SetIndirectMode(mode);
}

//------------------------------------------------------------------------------
int vtkPVMRGIRenderView::GetIndirectMode()
{
  return this->MRGIPass->GetIndirectMode();
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetMultiresolutionPreset(int preset)
{
  if (!this->MRGIPass->GetMultiresolution()->SetPreset(preset))
  {
    vtkErrorMacro("unknown multiresolution preset " << preset
                                                     << " (0 Fast, 1 Balanced, 2 Accurate)");
    return;
  }
  this->UserPreset = preset;
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetNumberOfVPLs(int count)
{
  this->MRGIPass->SetNumberOfVPLs(count);
  this->UserVPLs = this->MRGIPass->GetNumberOfVPLs();
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetVPLSelectionMode(int mode)
{
  this->MRGIPass->SetVPLSelectionMode(mode);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetIndirectVisibility(int mode)
{
  this->MRGIPass->SetIndirectVisibility(mode);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetRSMResolution(int resolution)
{
  this->MRGIPass->SetRSMResolution(resolution);
  this->UserRSMResolution = this->MRGIPass->GetRSMResolution();
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetIndirectStrength(double strength)
{
  this->MRGIPass->SetIndirectStrength(strength);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetSurfaceDetail(double alpha)
{
  this->MRGIPass->SetSurfaceDetail(alpha);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetDirectShadows(int mode)
{
  this->MRGIPass->SetDirectShadows(mode);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetUpsampleMode(int mode)
{
  this->MRGIPass->SetUpsampleMode(mode);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetExposure(double ev)
{
  this->MRGIPass->SetExposure(ev);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetAutoExposure(bool automatic)
{
  this->MRGIPass->SetAutoExposure(automatic);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetToneMapping(bool enabled)
{
  this->MRGIPass->SetToneMapping(enabled);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetAreaLightVisibility(int mode)
{
  this->MRGIPass->SetAreaLightVisibility(mode);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetAreaLightSpecular(bool specular)
{
  this->MRGIPass->SetAreaLightSpecular(specular);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetAreaLightIndirect(bool indirect)
{
  this->MRGIPass->SetAreaLightIndirect(indirect);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetAreaLightVoxelSlices(int slices)
{
  this->MRGIPass->GetVoxelization()->SetNumberOfSlices(slices);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetAreaLightVoxelSide(int side)
{
  vtkMRGIVoxelization* voxelization = this->MRGIPass->GetVoxelization();
  if (side <= 0)
  {
    voxelization->AutomaticVoxelSizeOn();
  }
  else
  {
    voxelization->SetVoxelSide(side);
  }
}

//------------------------------------------------------------------------------
int vtkPVMRGIRenderView::GetLastAreaLightVoxelSlices()
{
  return this->MRGIPass->GetVoxelization()->GetLastNumberOfSlices();
}

//------------------------------------------------------------------------------
int vtkPVMRGIRenderView::GetLastAreaLightVoxelWidth()
{
  int size[2];
  this->MRGIPass->GetVoxelization()->GetLastVoxelSize(size);
  return size[0];
}

//------------------------------------------------------------------------------
int vtkPVMRGIRenderView::GetLastAreaLightVoxelHeight()
{
  int size[2];
  this->MRGIPass->GetVoxelization()->GetLastVoxelSize(size);
  return size[1];
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::RestoreUserSettings()
{
  this->MRGIPass->GetMultiresolution()->SetPreset(this->UserPreset);
  this->MRGIPass->SetNumberOfVPLs(this->UserVPLs);
  this->MRGIPass->SetRSMResolution(this->UserRSMResolution);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetBudget(void (vtkMRGIFrameBudget::*set)(double), double value)
{
  vtkMRGIFrameBudget* tuner = this->MRGIPass->GetFrameBudgetTuner();
  const bool wasActive = tuner->IsActive();
  (tuner->*set)(value); // refuses a bad value with an error naming it
  if (wasActive && !tuner->IsActive())
  {
    this->RestoreUserSettings();
  }
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetFrameBudget(double ms)
{
  this->SetBudget(&vtkMRGIFrameBudget::SetFrameBudget, ms);
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::SetErrorBudget(double error)
{
  this->SetBudget(&vtkMRGIFrameBudget::SetErrorBudget, error);
}

//------------------------------------------------------------------------------
const char* vtkPVMRGIRenderView::GetFrameBudgetSetting()
{
  vtkMRGIFrameBudget* tuner = this->MRGIPass->GetFrameBudgetTuner();
  this->FrameBudgetSetting = !tuner->IsActive() ? std::string("off")
    : tuner->GetPreset() < 0 ? std::string("budget set; no frame rendered with it yet")
                             : tuner->GetSummary();
  return this->FrameBudgetSetting.c_str();
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::CalibrateFrameBudget()
{
  vtkRenderWindow* window = this->GetRenderWindow();
  if (!window || !this->MRGIPass->Calibrate(window))
  {
    vtkErrorMacro("frame budget calibration failed (see the error above)");
  }
}

//------------------------------------------------------------------------------
const char* vtkPVMRGIRenderView::GetHeadlessBackend()
{
  return vtkPVMRGIHeadlessBackend();
}

//------------------------------------------------------------------------------
void vtkPVMRGIRenderView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "GlobalIllumination: " << this->GlobalIllumination << "\n";
  os << indent << "HeadlessBackend: " << GetHeadlessBackend() << "\n";
  os << indent << "NumberOfAreaLights: " << this->AreaLights->GetNumberOfLights() << "\n";
  os << indent << "MRGIPass:\n";
  this->MRGIPass->PrintSelf(os, indent.GetNextIndent());
}
