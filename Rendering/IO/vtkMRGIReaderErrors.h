/**
 * @class   vtkMRGIReaderErrors
 * @brief   Internal (MRGI::RenderingIO): collects the text of the VTK
 *          errors (and warnings) an algorithm raises while it lives, so
 *          that vtkMRGISceneBuilder reports them as its own one-line error
 *          instead of letting them scroll by.
 *
 * Observes the object from construction to destruction (RAII); keeps the
 * first message, without VTK's "ERROR: In file, line N / Class (0x...): "
 * prefix. Not wrapped, not installed.
 */
#ifndef vtkMRGIReaderErrors_h
#define vtkMRGIReaderErrors_h

#include "vtkCallbackCommand.h" // For vtkCallbackCommand
#include "vtkNew.h"             // For vtkNew

#include <string> // For std::string

class vtkObject;

class vtkMRGIReaderErrors
{
public:
  /**
   * Observe `watched` (not null). Warnings count as errors unless
   * `warningsToo` is false (then VTK prints them as usual).
   */
  explicit vtkMRGIReaderErrors(vtkObject* watched, bool warningsToo = true);
  ~vtkMRGIReaderErrors();

  bool HasError() const { return !this->Message.empty(); }
  const std::string& GetMessage() const { return this->Message; }

private:
  vtkMRGIReaderErrors(const vtkMRGIReaderErrors&) = delete;
  void operator=(const vtkMRGIReaderErrors&) = delete;

  static void OnError(vtkObject*, unsigned long, void* clientData, void* callData);

  vtkObject* Watched;
  vtkNew<vtkCallbackCommand> Callback;
  unsigned long ErrorTag = 0;
  unsigned long WarningTag = 0;
  std::string Message;
};

#endif
