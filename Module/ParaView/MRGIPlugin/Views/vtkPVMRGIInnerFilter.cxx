#include "vtkPVMRGIInnerFilter.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkPolyDataAlgorithm.h"

namespace vtkPVMRGIInnerFilter
{
//------------------------------------------------------------------------------
void Run(vtkPolyDataAlgorithm* inner, vtkPolyData* input, vtkPolyData* output)
{
  vtkNew<vtkPolyData> copy;
  copy->ShallowCopy(input);
  inner->SetInputData(copy);
  vtkNew<vtkCallbackCommand> quiet;
  const unsigned long tag = inner->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, quiet);
  inner->Update();
  inner->GetExecutive()->RemoveObserver(tag);
  output->ShallowCopy(inner->GetOutput());
}
}
