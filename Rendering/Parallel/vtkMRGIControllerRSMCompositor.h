/**
 * @class   vtkMRGIControllerRSMCompositor
 * @brief   Composites MRGI's reflective shadow maps across the processes
 *          of a vtkMultiProcessController (MPI ranks).
 *
 * Give it to vtkMRGIPass::SetRSMCompositor() on every process, with the
 * same controller (in ParaView: vtkMultiProcessController::GetGlobalController()):
 *
 * @code
 * vtkNew<vtkMRGIControllerRSMCompositor> compositor;
 * compositor->SetController(vtkMultiProcessController::GetGlobalController());
 * mrgiPass->SetRSMCompositor(compositor);
 * @endcode
 *
 * The maps are reduced with the core's mrgi_rsm_composite() along a binomial
 * tree to process 0 and sent back down a binomial tree: each process sends
 * the maps at most twice (once up, and once per child down; 2 (P - 1)
 * messages in all), over 2 ceil(log2 P) rounds. Point to point rather than
 * MPI's Allreduce with a user operation: MPI may hand a user operation any
 * sub-range of the floats, splitting a texel's record; here every call of
 * the operation sees whole views.
 *
 * Without a controller, or with one process, GetNumberOfProcesses() is 1
 * and nothing is sent.
 */
#ifndef vtkMRGIControllerRSMCompositor_h
#define vtkMRGIControllerRSMCompositor_h

#include "MRGIRenderingParallelModule.h" // For export macro
#include "vtkMRGIRSMCompositor.h"

class vtkMultiProcessController;

class MRGIRENDERINGPARALLEL_EXPORT vtkMRGIControllerRSMCompositor : public vtkMRGIRSMCompositor
{
public:
  static vtkMRGIControllerRSMCompositor* New();
  vtkTypeMacro(vtkMRGIControllerRSMCompositor, vtkMRGIRSMCompositor);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The processes to composite across (null: this process alone). */
  virtual void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /** Message tag of the maps' point-to-point messages (default 31013; MPI allows up to 32767
   * everywhere). */
  vtkSetClampMacro(Tag, int, 0, 32767);
  vtkGetMacro(Tag, int);
  ///@}

  int GetNumberOfProcesses() override;

#ifndef __VTK_WRAP__
  bool AllReduceMax(double* values, int count) override;
  bool CompositeViews(
    float* views, size_t texels, int count, const mrgi_rsm_view_key* keys) override;
  bool AllReduceBitwiseOr(vtkTypeUInt32* values, vtkIdType count) override;
#endif

protected:
  vtkMRGIControllerRSMCompositor() = default;
  ~vtkMRGIControllerRSMCompositor() override;

  vtkMultiProcessController* Controller = nullptr;
  int Tag = 31013;

private:
  vtkMRGIControllerRSMCompositor(const vtkMRGIControllerRSMCompositor&) = delete;
  void operator=(const vtkMRGIControllerRSMCompositor&) = delete;
};

#endif
