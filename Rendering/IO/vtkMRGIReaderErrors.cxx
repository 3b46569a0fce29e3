#include "vtkMRGIReaderErrors.h"

#include "vtkCommand.h"
#include "vtkObject.h"

//------------------------------------------------------------------------------
vtkMRGIReaderErrors::vtkMRGIReaderErrors(vtkObject* watched, bool warningsToo)
  : Watched(watched)
{
  this->Callback->SetClientData(this);
  this->Callback->SetCallback(&vtkMRGIReaderErrors::OnError);
  this->ErrorTag = watched->AddObserver(vtkCommand::ErrorEvent, this->Callback);
  if (warningsToo)
  {
    this->WarningTag = watched->AddObserver(vtkCommand::WarningEvent, this->Callback);
  }
}

//------------------------------------------------------------------------------
vtkMRGIReaderErrors::~vtkMRGIReaderErrors()
{
  this->Watched->RemoveObserver(this->ErrorTag);
  if (this->WarningTag)
  {
    this->Watched->RemoveObserver(this->WarningTag);
  }
}

//------------------------------------------------------------------------------
void vtkMRGIReaderErrors::OnError(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* self = static_cast<vtkMRGIReaderErrors*>(clientData);
  if (self->Message.empty() && callData)
  {
    std::string text = static_cast<const char*>(callData);
    // VTK prefixes "ERROR: In file, line N\nClass (0x...): "; keep the reason.
    const size_t colon = text.rfind("): ");
    if (colon != std::string::npos)
    {
      text = text.substr(colon + 3);
    }
    while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
    {
      text.pop_back();
    }
    self->Message = text.empty() ? "the reader failed" : text;
  }
}
