// mrgiRenderImages: the images mrgi-render reads back and checks: the
// window's 8-bit colour, whether a run needs that display image at all,
// whether an image shows only the background (and why, as far as the
// renderer can tell), and the supersampling's block average.
#ifndef mrgiRenderImages_h
#define mrgiRenderImages_h

#include "vtkType.h" // For vtkIdType

#include <string>

class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;

namespace mrgirender
{
struct Options;

// The window's 8-bit colour as an RGB image (what the window shows).
bool ReadWindowRGB(vtkRenderWindow* window, int width, int height, vtkImageData* image);

// Whether a result of this run is the display image (the colour exposed,
// tone mapped and anti-aliased into the window): a PNG of the GPU image, the
// interactive window, or a run without outputs (it times the frame a viewer
// sees). EXR, --indirect-only and --reference outputs are HDR buffers that
// exposure, tone mapping and FXAA never touch, so those steps are not run
// for them (automatic exposure alone reads the whole HDR image back).
bool ShowsDisplayImage(const Options& o);

// Whether every pixel of `image` (3 or 4 components) is the background
// colour: within one 8-bit step for the window's 8-bit image, exactly for
// the HDR colour buffer (its background is the clear colour, untouched).
bool OnlyBackground(vtkImageData* image, const double background[3]);

// Why a picture that shows only the background is empty, as far as the
// renderer can tell.
std::string WhyEmpty(vtkRenderer* renderer, vtkIdType triangles);

// --aa ssaa:N: the N x N blocks of `image` (any scalar type, rows in
// either order) averaged into one pixel each (mrgi_box_downsample); 8-bit
// images are rounded back to 8 bits. False with `why` on failure.
bool Downsample(vtkImageData* image, int factor, std::string& why);
}

#endif
