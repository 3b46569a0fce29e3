// Fuzzes mrgi-render's command line (mrgiRenderOptions.cxx): the input,
// split at NUL bytes, is argv after the program name. Checked: the parser
// returns -1 (go on) with a scene, a size in range and an output, or an exit
// code of 0 (--help, --version) or 2 (error); then every --light and
// --area-light value goes through the parsers mrgi-render calls with it
// (an accepted area light's geometry is checked when it is used, by
// mrgi_area_light_check(), not here).
#include "mrgiRenderOptions.h"

#include "vtkLight.h"
#include "vtkMRGIAreaLight.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include "mrgi_fuzz.h"
#include "mrgi_parse.h"

#include <string>
#include <vector>

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  // Under libFuzzer only: the parser's error lines and --help would fill the
  // log at thousands of runs a second. Reports (sanitizers, MRGI_FUZZ_REQUIRE)
  // write to file descriptor 2 directly and still show.
  if (FILE* null = std::fopen("/dev/null", "w"))
  {
    stdout = null;
    stderr = null;
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  std::vector<std::string> words(1, "mrgi-render");
  std::string word;
  for (size_t i = 0; i < size && words.size() < 64; ++i)
  {
    if (data[i] == '\0')
    {
      words.push_back(word);
      word.clear();
    }
    else
    {
      word.push_back(static_cast<char>(data[i]));
    }
  }
  if (!word.empty() && words.size() < 64)
  {
    words.push_back(word);
  }
  std::vector<char*> argv;
  for (std::string& w : words)
  {
    argv.push_back(&w[0]);
  }
  argv.push_back(nullptr);

  mrgirender::Options o;
  const int code = mrgirender::ParseArguments(static_cast<int>(words.size()), argv.data(), o);
  MRGI_FUZZ_REQUIRE(code == -1 || code == 0 || code == 2);
  if (code != -1)
  {
    return 0;
  }
  MRGI_FUZZ_REQUIRE(!o.Scene.empty());
  MRGI_FUZZ_REQUIRE(o.Width >= 1 && o.Width <= MRGI_PARSE_MAX_SIZE);
  MRGI_FUZZ_REQUIRE(o.Height >= 1 && o.Height <= MRGI_PARSE_MAX_SIZE);
  MRGI_FUZZ_REQUIRE(!o.Outputs.empty() || o.Interactive || o.Timings);
  for (const std::string& spec : o.Lights)
  {
    vtkSmartPointer<vtkLight> light;
    std::string why;
    const bool ok = mrgirender::ParseLight(spec, light, why);
    MRGI_FUZZ_REQUIRE(ok ? light != nullptr : !why.empty());
  }
  for (const std::string& spec : o.AreaLights)
  {
    vtkNew<vtkMRGIAreaLight> light;
    std::string why;
    const bool ok = mrgirender::ParseAreaLight(spec, light, why);
    MRGI_FUZZ_REQUIRE(ok || !why.empty());
  }
  return 0;
}
