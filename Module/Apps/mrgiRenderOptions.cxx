#include "mrgiRenderOptions.h"
#include "mrgiRenderOptionTable.h"

#include "mrgi_direct_shadow.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIEGLRenderWindow.h"
#include "vtkMRGIImageIO.h"
#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkProperty.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIAreaLightStage.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIUpsample.h"
#include "vtkMRGIVisibilityPyramid.h"
#include "vtkMRGIVoxelization.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReferenceRenderer.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMRGIRenderWindowFactory.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMRGIStaging.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkRenderStepsPass.h"
#include "vtkToneMappingPass.h"
#include "vtkDataArray.h"
#include "vtkRenderTimerLog.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkPointData.h"
#include "mrgi_ssao.h"
#include "mrgi_screen_space_preset.h"
#include "mrgi_ssgi.h"
#include "mrgi_error.h"
#include "mrgi_area_light.h"
#include "mrgi_box_filter.h"
#include "mrgi_exposure.h"
#include "mrgi_voxel.h"
#include "mrgi_multires.h"
#include "mrgi_parse.h"
#include "mrgi_vpl_tree_gather.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <strings.h>
#include <utility>
#include <vector>
#ifndef MRGI_VERSION_STRING
#define MRGI_VERSION_STRING "unknown"
#endif

// A default defined once in the core, spelled into help text: "0.02".
#define MRGI_OPTIONS_TEXT_(x) #x
#define MRGI_OPTIONS_TEXT(x) MRGI_OPTIONS_TEXT_(x)

namespace mrgirender
{
// Parses "on"/"off" (and "full"/"off" for --gi); false for anything else.
bool ParseSwitch(const char* text, const char* on, bool& value)
{
  if (std::strcmp(text, on) == 0)
  {
    value = true;
    return true;
  }
  if (std::strcmp(text, "off") == 0)
  {
    value = false;
    return true;
  }
  return false;
}

int Fail(const std::string& message)
{
  std::fprintf(stderr, "mrgi-render: error: %s\n", message.c_str());
  return 2;
}

bool EndsWith(const std::string& s, const char* extension)
{
  const size_t e = std::strlen(extension);
  return s.size() > e && strcasecmp(s.c_str() + s.size() - e, extension) == 0;
}


// Splits "a:b:c" on ':'.
std::vector<std::string> SplitColon(const std::string& text)
{
  std::vector<std::string> parts;
  size_t start = 0;
  while (true)
  {
    const size_t colon = text.find(':', start);
    parts.push_back(text.substr(start, colon == std::string::npos ? std::string::npos : colon - start));
    if (colon == std::string::npos)
    {
      break;
    }
    start = colon + 1;
  }
  return parts;
}

// X,Y,Z, each finite and within the float range: the GPU takes floats, so a
// larger double would become infinite there (and NaN pixels downstream).
bool ParseVec3(const std::string& option, const char* text, double out[3], std::string& why)
{
  mrgi_error err;
  double v[3];
  if (mrgi_parse_vec3(text, v, &err) != MRGI_OK)
  {
    why = option + ": " + err.message;
    return false;
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!(std::fabs(v[c]) <= MaxFloatValue))
    {
      why = option + " '" + text + "': each number must be within the float range (|x| <= 3.4e38)";
      return false;
    }
  }
  std::copy(v, v + 3, out);
  return true;
}

// --area-light CX,CY,CZ:UX,UY,UZ:VX,VY,VZ[:R,G,B[:I]]; the light checks the
// geometry itself (perpendicular, non-zero edges) when it is used.
bool ParseAreaLight(const std::string& spec, vtkMRGIAreaLight* light, std::string& why)
{
  const std::vector<std::string> parts = SplitColon(spec);
  const std::string option = "--area-light '" + spec + "'";
  if (parts.size() < 3 || parts.size() > 5)
  {
    why = option + ": expected CX,CY,CZ:UX,UY,UZ:VX,VY,VZ[:R,G,B[:I]]";
    return false;
  }
  double c[3], u[3], v[3], rgb[3] = { 1.0, 1.0, 1.0 }, intensity = 1.0;
  if (!ParseVec3(option + " centre", parts[0].c_str(), c, why) ||
    !ParseVec3(option + " edge u", parts[1].c_str(), u, why) ||
    !ParseVec3(option + " edge v", parts[2].c_str(), v, why) ||
    (parts.size() > 3 && !ParseVec3(option + " colour", parts[3].c_str(), rgb, why)))
  {
    return false;
  }
  mrgi_error err;
  if (parts.size() > 4 &&
    (mrgi_parse_double(parts[4].c_str(), &intensity, &err) != MRGI_OK || !(intensity >= 0) ||
      !(intensity <= 1e6)))
  {
    why = option + ": the intensity must be a number in [0, 1e6]";
    return false;
  }
  const double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2], vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const double uv = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  if (!(uu > 0) || !(vv > 0) || std::fabs(uv) > MRGI_AREA_LIGHT_PERPENDICULAR_TOLERANCE * std::sqrt(uu * vv))
  {
    why = option + ": the edges must be non-zero and perpendicular";
    return false;
  }
  if (rgb[0] < 0 || rgb[1] < 0 || rgb[2] < 0)
  {
    why = option + ": the colour must be >= 0";
    return false;
  }
  // The light's own check (finite float area, radiance in float range, ...),
  // now rather than as a VTK error at the first frame.
  mrgi_area_light core = {};
  std::copy(c, c + 3, core.center);
  std::copy(u, u + 3, core.edge_u);
  std::copy(v, v + 3, core.edge_v);
  std::copy(rgb, rgb + 3, core.color);
  core.intensity = intensity;
  if (mrgi_area_light_check(&core, &err) != MRGI_OK)
  {
    why = option + ": " + err.message;
    return false;
  }
  light->SetCenter(c);
  light->SetEdgeU(u);
  light->SetEdgeV(v);
  light->SetColor(rgb);
  light->SetIntensity(intensity);
  return true;
}

bool ParseLight(const std::string& spec, vtkSmartPointer<vtkLight>& light, std::string& why)
{
  const std::vector<std::string> parts = SplitColon(spec);
  light = vtkSmartPointer<vtkLight>::New();
  const std::string option = "--light '" + spec + "'";
  const std::string& kind = parts[0];
  if (kind == "headlight" && parts.size() == 1)
  {
    light->SetLightTypeToHeadlight();
    return true;
  }
  light->SetLightTypeToSceneLight();
  double a[3], b[3];
  if (kind == "positional" && parts.size() == 2)
  {
    if (!ParseVec3(option, parts[1].c_str(), a, why))
    {
      return false;
    }
    light->SetPositional(true);
    light->SetConeAngle(90.0);
    light->SetPosition(a);
    light->SetFocalPoint(a[0], a[1] - 1.0, a[2]);
    return true;
  }
  if (kind == "spot" && parts.size() == 4)
  {
    double cone = 0;
    mrgi_error err;
    if (!ParseVec3(option, parts[1].c_str(), a, why) || !ParseVec3(option, parts[2].c_str(), b, why))
    {
      return false;
    }
    if (mrgi_parse_double(parts[3].c_str(), &cone, &err) != MRGI_OK || cone <= 0 || cone >= 90)
    {
      why = option + ": the cone half angle must be a number in (0, 90) degrees";
      return false;
    }
    if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2])
    {
      why = option + ": the spot light's position and focal point coincide";
      return false;
    }
    light->SetPositional(true);
    light->SetPosition(a);
    light->SetFocalPoint(b);
    light->SetConeAngle(cone);
    return true;
  }
  if (kind == "directional" && parts.size() == 2)
  {
    if (!ParseVec3(option, parts[1].c_str(), a, why))
    {
      return false;
    }
    if (a[0] == 0 && a[1] == 0 && a[2] == 0)
    {
      why = option + ": the direction is the zero vector";
      return false;
    }
    // vtkLight: light travels from Position towards FocalPoint.
    light->SetPositional(false);
    light->SetPosition(0, 0, 0);
    light->SetFocalPoint(a);
    return true;
  }
  why = option + ": expected positional:X,Y,Z | spot:X,Y,Z:FX,FY,FZ:CONE | "
                 "directional:DX,DY,DZ | headlight";
  return false;
}

// Splits help text into lines ('\n'); none for "".
std::vector<std::string> SplitLines(const char* text)
{
  std::vector<std::string> lines;
  std::string line;
  for (const char* c = text; *c; ++c)
  {
    if (*c == '\n')
    {
      lines.push_back(line);
      line.clear();
    }
    else
    {
      line += *c;
    }
  }
  if (!line.empty())
  {
    lines.push_back(line);
  }
  return lines;
}

// ---- Options: one table (mrgiRenderOptionTable.cxx). -----------------------
//
// The parser (ParseArguments) and the usage text (PrintUsage) are both made
// from the rows, so an option cannot be accepted and undocumented, or the
// reverse.

const char* const UsageHead = R"(usage: mrgi-render SCENE -o OUT.png|OUT.exr [options]

Renders SCENE headless (no X server, no GPU needed) and writes the image.

SCENE   a built-in scene: cornell, cornell-spot, cornell-area, living-room, scaling,
        corridor, corridor-large, corner, u-shape
        or a data file: .vtp .vtu .vti .vts .vtr .vtm .vtk .ply .obj .stl .gltf .glb,
        point clouds .las (uncompressed LAS 1.0-1.4) .pcd (with MRGI's PCL module)
)";

// The usage text: the head, then each section's rows. A row's help starts in
// column 25, on the row's own line when its names and value leave a space.
void PrintUsage(FILE* out)
{
  const size_t helpColumn = 25;
  std::string text = UsageHead;
  for (const OptionSection& section : OptionTable())
  {
    text += std::string("\n") + section.Title + "\n";
    for (const OptionRow& row : section.Rows)
    {
      std::string left = "  ";
      for (size_t n = 0; n < row.Names.size(); ++n)
      {
        left += (n ? ", " : "") + row.Names[n];
      }
      if (row.Value)
      {
        left += std::string(" ") + row.Value;
      }
      std::vector<std::string> help = SplitLines(row.Help);
      if (help.empty())
      {
        text += left + "\n";
        continue;
      }
      if (left.size() < helpColumn)
      {
        text += left + std::string(helpColumn - left.size(), ' ') + help[0] + "\n";
        help.erase(help.begin());
      }
      else
      {
        text += left + "\n";
      }
      for (const std::string& line : help)
      {
        text += std::string(helpColumn, ' ') + line + "\n";
      }
    }
  }
  std::fputs(text.c_str(), out);
}

// The row of `name`, or nullptr.
const OptionRow* FindOption(const std::string& name)
{
  for (const OptionSection& section : OptionTable())
  {
    for (const OptionRow& row : section.Rows)
    {
      if (std::find(row.Names.begin(), row.Names.end(), name) != row.Names.end())
      {
        return &row;
      }
    }
  }
  return nullptr;
}

// Parses argv into `o`; returns -1 to go on, else the exit code.
int ParseArguments(int argc, char* argv[], Options& o)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (const OptionRow* row = FindOption(arg))
    {
      const char* value = nullptr;
      if (row->Value)
      {
        if (i + 1 >= argc)
        {
          return Fail(arg + " needs a value");
        }
        value = argv[++i];
      }
      const int code = row->Handle(o, arg, value);
      if (code >= 0)
      {
        return code;
      }
    }
    else if (!arg.empty() && arg[0] == '-')
    {
      return Fail("unknown option '" + arg + "' (see mrgi-render --help)");
    }
    else if (o.Scene.empty())
    {
      o.Scene = arg;
    }
    else
    {
      return Fail("more than one scene given ('" + o.Scene + "' and '" + arg + "')");
    }
  }
  if (o.Scene.empty())
  {
    return Fail("no scene given (see mrgi-render --help)");
  }
  if (o.AntiAliasing == Options::AASSAA &&
    (static_cast<int64_t>(o.Width) * o.SSAAFactor > MRGI_SSAA_MAX_SIDE ||
      static_cast<int64_t>(o.Height) * o.SSAAFactor > MRGI_SSAA_MAX_SIDE))
  {
    return Fail("--aa ssaa:" + std::to_string(o.SSAAFactor) + " with --size " +
      std::to_string(o.Width) + "x" + std::to_string(o.Height) + " renders " +
      std::to_string(static_cast<int64_t>(o.Width) * o.SSAAFactor) + "x" +
      std::to_string(static_cast<int64_t>(o.Height) * o.SSAAFactor) + " pixels, more than the " +
      std::to_string(MRGI_SSAA_MAX_SIDE) +
      " per side OpenGL windows take: use a smaller N or size");
  }
  if (o.Outputs.empty() && !o.Interactive && !o.Timings)
  {
    return Fail("no output given: use -o OUT.png or -o OUT.exr (or --timings / --interactive)");
  }
  // A camera VTK cannot make a view from: NaN pixels or VTK's own warnings.
  if (o.HasUp && o.Up[0] == 0 && o.Up[1] == 0 && o.Up[2] == 0)
  {
    return Fail("--camera-view-up: the view-up vector is the zero vector");
  }
  if (o.HasPosition && o.HasFocal && o.Position[0] == o.Focal[0] && o.Position[1] == o.Focal[1] &&
    o.Position[2] == o.Focal[2])
  {
    return Fail("--camera-position and --camera-focal-point coincide: no view direction");
  }
  return -1;
}
}
