// mrgiRenderImageLimits: mrgi-render's check of --size against what this
// OpenGL and this machine can hold (internal to mrgi-render; not installed).
//
// Checked before anything is rendered: the window size (--size, times N with
// --aa ssaa:N) against GL_MAX_VIEWPORT_DIMS, GL_MAX_TEXTURE_SIZE and
// GL_MAX_RENDERBUFFER_SIZE; the multiresolution buffer's side-by-side layout
// (mrgi_multires.h) against GL_MAX_TEXTURE_SIZE when it is used (multires
// gather or any area light); and, on a software OpenGL (llvmpipe, softpipe,
// swrast), the host memory a frame takes against /proc/meminfo's
// MemAvailable. Without this, buffers GL cannot make fail inside the frame.
#ifndef mrgiRenderImageLimits_h
#define mrgiRenderImageLimits_h

#include "mrgiRenderOptions.h" // For Options

#include <string>

class vtkMRGIPass;
class vtkRenderWindow;

namespace mrgirender
{
// True when the image fits (or `window` is not an OpenGL window: nothing to
// check). Otherwise false with `why` naming --size, the limit and what to
// do. Makes the window's context current (initializing it if needed).
bool CheckImageLimits(
  vtkRenderWindow* window, const Options& o, vtkMRGIPass* mrgi, std::string& why);
}

#endif
