#include "mrgiRenderOutputWindow.h"

#include "vtkCommand.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"

#include <cstdio>
#include <cstring>

vtkStandardNewMacro(mrgiRenderOutputWindow);

//------------------------------------------------------------------------------
mrgiRenderOutputWindow* mrgiRenderOutputWindow::Install(bool quiet)
{
  vtkNew<mrgiRenderOutputWindow> window;
  window->SetQuiet(quiet);
  vtkOutputWindow::SetInstance(window);
  // vtkErrorMacro also logs through vtkLogger, whose stderr lines (colour
  // codes, uptime, thread id) would repeat each message; the output window
  // above receives every one of them in full.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  return window; // the singleton keeps a reference
}

//------------------------------------------------------------------------------
std::string mrgiRenderOutputWindow::Plain(const char* text)
{
  std::string s = text ? text : "";
  // "ERROR: In /path/file.cxx, line 193\n" / "Warning: In ...": where in
  // VTK's sources says nothing to a user of the command line.
  if (s.compare(0, 10, "ERROR: In ") == 0 || s.compare(0, 12, "Warning: In ") == 0 ||
    s.compare(0, 20, "Generic Warning: In ") == 0)
  {
    const size_t eol = s.find('\n');
    s = eol == std::string::npos ? std::string() : s.substr(eol + 1);
  }
  // "vtkClass (0x55d0...): message" -> "vtkClass: message".
  const size_t open = s.find(" (0x");
  if (open != std::string::npos)
  {
    const size_t close = s.find("): ", open);
    if (close != std::string::npos && s.find_first_of(" \n", open + 1) > close)
    {
      s.erase(open, close + 1 - open);
    }
  }
  std::string out;
  for (char c : s)
  {
    if (c == '\n' || c == '\r' || c == '\t')
    {
      c = ' ';
    }
    if (c == ' ' && (out.empty() || out.back() == ' '))
    {
      continue;
    }
    // No terminal control sequences in a one-line report.
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
    {
      continue;
    }
    out += c;
  }
  while (!out.empty() && out.back() == ' ')
  {
    out.pop_back();
  }
  return out;
}

//------------------------------------------------------------------------------
void mrgiRenderOutputWindow::Report(bool error, const char* text)
{
  const std::string line = Plain(text);
  if (line.empty())
  {
    return;
  }
  if (error && this->NumberOfErrors++ == 0)
  {
    this->FirstError = line;
  }
  if (!this->Quiet)
  {
    std::fprintf(stderr, "mrgi-render: VTK %s: %s\n", error ? "error" : "warning", line.c_str());
  }
}

//------------------------------------------------------------------------------
void mrgiRenderOutputWindow::DisplayText(const char* text)
{
  // Plain text that is neither an error nor a warning (e.g. PrintSelf to
  // the window): only when not quiet.
  if (!this->Quiet && text)
  {
    std::fputs(text, stderr);
  }
}

//------------------------------------------------------------------------------
void mrgiRenderOutputWindow::DisplayErrorText(const char* text)
{
  this->Report(true, text);
  this->InvokeEvent(vtkCommand::ErrorEvent, const_cast<char*>(text));
}

//------------------------------------------------------------------------------
void mrgiRenderOutputWindow::DisplayWarningText(const char* text)
{
  this->Report(false, text);
  this->InvokeEvent(vtkCommand::WarningEvent, const_cast<char*>(text));
}

//------------------------------------------------------------------------------
void mrgiRenderOutputWindow::DisplayGenericWarningText(const char* text)
{
  this->DisplayWarningText(text);
}

//------------------------------------------------------------------------------
void mrgiRenderOutputWindow::DisplayDebugText(const char*)
{
  // Debug output (SetDebug(1)) is for developers running VTK, not this tool.
}

//------------------------------------------------------------------------------
void mrgiRenderOutputWindow::ResetErrors()
{
  this->NumberOfErrors = 0;
  this->FirstError.clear();
}

//------------------------------------------------------------------------------
void mrgiRenderOutputWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Quiet: " << this->Quiet << "\n";
  os << indent << "NumberOfErrors: " << this->NumberOfErrors << "\n";
  os << indent << "FirstError: " << this->FirstError << "\n";
}
