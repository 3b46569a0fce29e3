#include "mrgiRenderOutputWindow.h"

#include "vtkCommand.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"

#include <cctype>
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
  // "vtkClass (0x55d0...): message" -> "vtkClass: message": addresses
  // differ from run to run and mean nothing outside a debugger.
  for (size_t open = s.find("(0x"); open != std::string::npos; open = s.find("(0x", open))
  {
    size_t close = open + 3;
    while (close < s.size() && std::isxdigit(static_cast<unsigned char>(s[close])))
    {
      ++close;
    }
    if (close < s.size() && s[close] == ')')
    {
      const size_t from = open > 0 && s[open - 1] == ' ' ? open - 1 : open;
      s.erase(from, close + 1 - from);
      open = from;
    }
    else
    {
      open = close;
    }
  }
  // The executive's "returned failure for request: vtkInformation ..." is
  // followed by a dump of the request: keep the sentence only.
  const size_t request = s.find("for request: vtkInformation");
  if (request != std::string::npos)
  {
    s.erase(request + std::strlen("for request"));
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
