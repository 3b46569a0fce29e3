// mrgiRenderOptionTable: the rows of mrgi-render's command line (internal to
// mrgi-render; not installed).
//
// Every option is one row of OptionTable(): its names, the form of its value
// (none for a switch), its help text and what it does with the value. The
// parser (ParseArguments) and the usage text (PrintUsage) in
// mrgiRenderOptions.cxx are both made from the rows, so an option cannot be
// accepted and undocumented, or the reverse.
#ifndef mrgiRenderOptionTable_h
#define mrgiRenderOptionTable_h

#include "mrgiRenderOptions.h" // For Options

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace mrgirender
{
// What an option does with its value (nullptr for options without one),
// `option` being the name as typed. Returns -1 to go on, or the exit code
// (after Fail() for bad values).
using OptionHandler = std::function<int(Options& o, const std::string& option, const char* value)>;

struct OptionRow
{
  std::vector<std::string> Names; // "-o", "--output"
  const char* Value;              // what follows, e.g. "WxH"; nullptr: none
  const char* Help;               // '\n' starts a new help line
  OptionHandler Handle;
};

struct OptionSection
{
  const char* Title; // '\n' starts a new line
  std::vector<OptionRow> Rows;
};

// Every section of options, in --help order; built once.
const std::vector<OptionSection>& OptionTable();

// The usage text (head, then each section's rows) on `out`.
void PrintUsage(FILE* out);

// The largest magnitude a float holds; values sent to the GPU stay below it.
constexpr double MaxFloatValue = 3.4028234663852886e38;

// --voxel-size's documented range ends here; the core takes up to
// MRGI_VOXEL_MAX_SIZE, but a 16384^2 buffer of RGBA32UI texels is 4 GiB.
constexpr long long MaxVoxelSize = 4096;

// Parses "on"/"off" (and "full"/"off" for --gi); false for anything else.
bool ParseSwitch(const char* text, const char* on, bool& value);

// Splits "a:b:c" on ':'.
std::vector<std::string> SplitColon(const std::string& text);

// X,Y,Z, each finite and within the float range; false with `why` on error.
bool ParseVec3(const std::string& option, const char* text, double out[3], std::string& why);
}

#endif
