#include "vtkMRGIControllerRSMCompositor.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"

#include "mrgi_rsm_composite.h"

#include <vector>

vtkStandardNewMacro(vtkMRGIControllerRSMCompositor);
vtkCxxSetObjectMacro(vtkMRGIControllerRSMCompositor, Controller, vtkMultiProcessController);

//------------------------------------------------------------------------------
vtkMRGIControllerRSMCompositor::~vtkMRGIControllerRSMCompositor()
{
  this->SetController(nullptr);
}

//------------------------------------------------------------------------------
int vtkMRGIControllerRSMCompositor::GetNumberOfProcesses()
{
  return this->Controller ? this->Controller->GetNumberOfProcesses() : 1;
}

//------------------------------------------------------------------------------
bool vtkMRGIControllerRSMCompositor::AllReduceMax(double* values, int count)
{
  if (this->GetNumberOfProcesses() < 2 || count < 1)
  {
    return true;
  }
  std::vector<double> local(values, values + count);
  if (!this->Controller->AllReduce(local.data(), values, count, vtkCommunicator::MAX_OP))
  {
    vtkErrorMacro("AllReduce of " << count << " values failed");
    return false;
  }
  // What this process hands to the reduction; MPI's algorithm decides the rest.
  this->BytesSent += static_cast<vtkTypeInt64>(count) * static_cast<vtkTypeInt64>(sizeof(double));
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIControllerRSMCompositor::AllReduceBitwiseOr(vtkTypeUInt32* values, vtkIdType count)
{
  if (this->GetNumberOfProcesses() < 2 || count < 1)
  {
    return true;
  }
  // Element-wise and a standard operation: MPI may split the buffer anywhere.
  std::vector<vtkTypeUInt32> local(values, values + count);
  if (!this->Controller->AllReduce(local.data(), values, count, vtkCommunicator::BITWISE_OR_OP))
  {
    vtkErrorMacro("bitwise-OR AllReduce of " << count << " words failed");
    return false;
  }
  this->BytesSent += count * static_cast<vtkIdType>(sizeof(vtkTypeUInt32));
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIControllerRSMCompositor::CompositeViews(
  float* views, size_t texels, int count, const mrgi_rsm_view_key* keys)
{
  const int size = this->GetNumberOfProcesses();
  if (size < 2 || count < 1 || texels == 0)
  {
    return true;
  }
  vtkMultiProcessController* c = this->Controller;
  const int rank = c->GetLocalProcessId();
  const size_t viewFloats = texels * MRGI_RSM_COMPOSITE_RECORD_FLOATS;
  const size_t total = viewFloats * static_cast<size_t>(count);
  const vtkIdType length = static_cast<vtkIdType>(total);
  const vtkTypeInt64 bytes = static_cast<vtkTypeInt64>(total * sizeof(float));
  bool ok = true;

  // Up: after round k, a process whose low k bits are zero holds the
  // composite of itself and the 2^k - 1 processes above it.
  std::vector<float> theirs;
  int mask = 1;
  for (; mask < size; mask <<= 1)
  {
    if (rank & mask)
    {
      ok = c->Send(views, length, rank - mask, this->Tag) != 0 && ok;
      this->BytesSent += bytes;
      break;
    }
    if (rank + mask < size)
    {
      theirs.resize(total);
      ok = c->Receive(theirs.data(), length, rank + mask, this->Tag) != 0 && ok;
      for (int v = 0; v < count; ++v)
      {
        mrgi_error err;
        const size_t offset = static_cast<size_t>(v) * viewFloats;
        if (mrgi_rsm_composite(theirs.data() + offset, views + offset, texels, &keys[v], &err) !=
          MRGI_OK)
        {
          vtkErrorMacro(<< "reflective shadow map composite: " << err.message);
          ok = false;
        }
      }
    }
  }
  // Down: the same tree, from process 0 (mask is now this process's lowest
  // set bit, or the first power of two >= size on process 0).
  if (rank != 0)
  {
    ok = c->Receive(views, length, rank - mask, this->Tag) != 0 && ok;
  }
  for (mask >>= 1; mask > 0; mask >>= 1)
  {
    if (rank + mask < size)
    {
      ok = c->Send(views, length, rank + mask, this->Tag) != 0 && ok;
      this->BytesSent += bytes;
    }
  }
  return ok;
}

//------------------------------------------------------------------------------
void vtkMRGIControllerRSMCompositor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "Tag: " << this->Tag << "\n";
}
