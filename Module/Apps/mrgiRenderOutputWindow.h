/**
 * @class   mrgiRenderOutputWindow
 * @brief   mrgi-render's route for VTK's messages: plain lines, counted errors.
 *
 * VTK reports problems through two channels: vtkOutputWindow (vtkErrorMacro,
 * vtkWarningMacro) and vtkLogger (loguru), whose stderr lines carry colour
 * codes, times and thread ids. Install() takes over both: vtkLogger's stderr
 * output is switched off and its warnings and errors arrive here through a
 * callback, as do the output window's. Each message is printed as one plain
 * line, "mrgi-render: VTK error: TEXT" (or "VTK warning:"), unless Quiet is
 * on; errors are counted and the first kept either way, so that the program
 * can refuse to write an image VTK reported a failure for, in its own single
 * error line.
 */
#ifndef mrgiRenderOutputWindow_h
#define mrgiRenderOutputWindow_h

#include "vtkOutputWindow.h"

#include <string>

class mrgiRenderOutputWindow : public vtkOutputWindow
{
public:
  static mrgiRenderOutputWindow* New();
  vtkTypeMacro(mrgiRenderOutputWindow, vtkOutputWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Make a new instance VTK's output window and route vtkLogger's warnings
   * and errors to it; returns it (owned by vtkOutputWindow's singleton).
   */
  static mrgiRenderOutputWindow* Install(bool quiet);

  void DisplayText(const char* text) override;
  void DisplayErrorText(const char* text) override;
  void DisplayWarningText(const char* text) override;
  void DisplayGenericWarningText(const char* text) override;
  void DisplayDebugText(const char* text) override;

  ///@{
  /** Quiet: print nothing (errors are still counted). */
  vtkSetMacro(Quiet, bool);
  vtkGetMacro(Quiet, bool);
  ///@}

  /** Errors reported since the last ResetErrors(). */
  vtkGetMacro(NumberOfErrors, int);

  /** The first of them, in plain form ("" when none). */
  const std::string& GetFirstError() const { return this->FirstError; }

  void ResetErrors();

  /**
   * A VTK message in plain form: the "ERROR: In FILE, line N" head and the
   * object's address dropped, lines joined, blanks trimmed.
   */
  static std::string Plain(const char* text);

protected:
  mrgiRenderOutputWindow() = default;
  ~mrgiRenderOutputWindow() override = default;

private:
  mrgiRenderOutputWindow(const mrgiRenderOutputWindow&) = delete;
  void operator=(const mrgiRenderOutputWindow&) = delete;

  void Report(bool error, const char* text);

  bool Quiet = false;
  int NumberOfErrors = 0;
  std::string FirstError;
};

#endif
