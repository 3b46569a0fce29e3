// mrgiRenderImageLimits: refuses an image this OpenGL or this machine
// cannot hold, before anything is rendered (see mrgiRenderImageLimits.h).
#include "mrgiRenderImageLimits.h"

#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIPass.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderWindow.h"
#include "vtk_glew.h"

#include "mrgi_error.h"
#include "mrgi_multires.h"

#include <cstdio>
#include <cstring>
#include <string>

namespace mrgirender
{
namespace
{
// Host memory a frame takes per pixel on a software OpenGL (llvmpipe keeps
// every texture in host memory): with area lights (their own gather and
// upsample buffers), with indirect light only, and with neither; measured
// with /usr/bin/time -v, see Documentation/reliability/memory.md. Rounded
// up: the check refuses only what cannot fit.
const double SoftwareBytesPerPixelAreaLights = 450;
const double SoftwareBytesPerPixelIndirect = 300;
const double SoftwareBytesPerPixelDirect = 100;

// The memory the kernel says new allocations can have, in bytes (0: unknown).
double AvailableMemory()
{
  FILE* f = std::fopen("/proc/meminfo", "r");
  if (!f)
  {
    return 0;
  }
  char key[64];
  double kib = 0, available = 0;
  char unit[16];
  while (std::fscanf(f, "%63s %lf %15s", key, &kib, unit) == 3)
  {
    if (std::strcmp(key, "MemAvailable:") == 0)
    {
      available = kib * 1024.0;
      break;
    }
  }
  std::fclose(f);
  return available;
}
}

// Refuses, before anything is rendered, an image this OpenGL or this
// machine cannot hold; false with `why` naming --size, the limit and what
// to do. Without this, buffers GL cannot make fail inside the frame.
bool CheckImageLimits(
  vtkRenderWindow* window, const Options& o, vtkMRGIPass* mrgi, std::string& why)
{
  vtkOpenGLRenderWindow* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!gl)
  {
    return true;
  }
  gl->Initialize();
  gl->MakeCurrent();
  while (glGetError() != GL_NO_ERROR)
  {
  }
  GLint maxTexture = 0, maxRenderbuffer = 0, maxViewport[2] = { 0, 0 };
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbuffer);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
  if (glGetError() != GL_NO_ERROR || maxTexture < 1 || maxRenderbuffer < 1 || maxViewport[0] < 1)
  {
    why = "no OpenGL context to check --size against (is an OpenGL 3.2 context available?)";
    return false;
  }
  const char* rendererName = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string glName = rendererName ? rendererName : "this OpenGL";
  // The window's size: --size, times N with --aa ssaa:N.
  const int w = window->GetSize()[0], h = window->GetSize()[1];
  char text[512];
  std::string size = "--size " + std::to_string(o.Width) + "x" + std::to_string(o.Height);
  if (w != o.Width || h != o.Height)
  {
    size += " (rendered at " + std::to_string(w) + "x" + std::to_string(h) + " by --aa ssaa)";
  }
  struct Limit
  {
    const char* Name;
    GLint Width, Height;
  };
  for (const Limit& limit : { Limit{ "GL_MAX_VIEWPORT_DIMS", maxViewport[0], maxViewport[1] },
         Limit{ "GL_MAX_TEXTURE_SIZE", maxTexture, maxTexture },
         Limit{ "GL_MAX_RENDERBUFFER_SIZE", maxRenderbuffer, maxRenderbuffer } })
  {
    if (w > limit.Width || h > limit.Height)
    {
      std::snprintf(text, sizeof(text), "%s: %s takes at most %d x %d pixels (%s)", size.c_str(),
        glName.c_str(), limit.Width, limit.Height, limit.Name);
      why = text;
      return false;
    }
  }
  // The multiresolution buffer lays its levels side by side (mrgi_multires.h):
  // about twice the width in one texture. It serves the multires gather and
  // every area light.
  const bool lit = o.GI && o.VPLs > 0;
  const bool multires = (lit && o.Multires) || mrgi->GetNumberOfAreaLights() > 0;
  vtkMRGIMultiresolution* mr = mrgi->GetMultiresolution();
  mrgi_multires_layout layout;
  mrgi_error err;
  if (multires &&
    (mrgi_multires_layout_init(&layout, w, h, mr->GetCoarsestSide(), &err) != MRGI_OK ||
      layout.total_width > maxTexture))
  {
    int widest = 1; // the widest image whose layout fits, by bisection
    for (int lo = 1, hi = w; lo <= hi;)
    {
      const int mid = lo + (hi - lo) / 2;
      if (mrgi_multires_layout_init(&layout, mid, h, mr->GetCoarsestSide(), &err) == MRGI_OK &&
        layout.total_width <= maxTexture)
      {
        widest = mid;
        lo = mid + 1;
      }
      else
      {
        hi = mid - 1;
      }
    }
    std::snprintf(text, sizeof(text),
      "%s: the multiresolution buffer (indirect light and area lights) puts its levels side by "
      "side, wider than %s's GL_MAX_TEXTURE_SIZE %d; at most %d pixels wide here (or --gi full "
      "or --gi off without area lights)",
      size.c_str(), glName.c_str(), maxTexture, widest);
    why = text;
    return false;
  }
  // A software OpenGL keeps every buffer in host memory: refuse what cannot fit.
  const bool software = glName.find("llvmpipe") != std::string::npos ||
    glName.find("softpipe") != std::string::npos || glName.find("swrast") != std::string::npos;
  const double available = AvailableMemory();
  if (software && available > 0)
  {
    const double perPixel = mrgi->GetNumberOfAreaLights() > 0 ? SoftwareBytesPerPixelAreaLights
      : lit                                                 ? SoftwareBytesPerPixelIndirect
                                                            : SoftwareBytesPerPixelDirect;
    const double needed = perPixel * static_cast<double>(w) * static_cast<double>(h);
    if (needed > available)
    {
      std::snprintf(text, sizeof(text),
        "%s: needs about %.1f GiB of memory on %s (%.0f bytes per pixel), %.1f GiB available",
        size.c_str(), needed / 1073741824.0, glName.c_str(), perPixel, available / 1073741824.0);
      why = text;
      return false;
    }
  }
  return true;
}
}
