/**
 * @file vtkMRGIAreaLightUtilities.h
 * @brief Internal helpers of vtkMRGIAreaLight that hold no light state: the
 *        conversions of its picture between VTK, the C core and OpenGL (a
 *        texture image to the core's float image, the core's image to the
 *        emitter's 8-bit display picture, the core's pyramid and samples to
 *        GL textures) and the wording of the core's messages for VTK users.
 *        Not wrapped, not installed.
 */
#ifndef vtkMRGIAreaLightUtilities_h
#define vtkMRGIAreaLightUtilities_h

#include <string> // For std::string

class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
struct mrgi_area_light_sample;
struct mrgi_area_light_texture_pyramid;
struct mrgi_image;

namespace vtkMRGIAreaLightUtilities
{
/**
 * `message` with the core's field names (center, edge_u, edge_v, color,
 * intensity; whole words only) replaced by the properties a VTK user
 * knows (Center, EdgeU, EdgeV, Color, Intensity).
 */
std::string WithPropertyNames(std::string message);

/**
 * `value`, or 0 when it is not finite and > 0. For display only: requests
 * report such values as errors.
 */
double Sanitized(double value);

/**
 * The core's float RGB image (3 channels, row 0 = top) of a VTK texture
 * image (row 0 = bottom): a 2D image with unsigned char scalars (v / 255,
 * sRGB-decoded when `srgb`) or float scalars (radiances, finite and >= 0),
 * 1 (gray, replicated), 2 (gray + alpha), 3 (RGB) or 4 (RGBA) components;
 * alpha is ignored. False with the reason in `why` (and nothing left
 * allocated in `out`) for an image it cannot convert.
 */
bool ConvertTexture(vtkImageData* image, bool srgb, mrgi_image* out, std::string& why);

/**
 * The emitter's display picture of `picture` (the core's float RGB image,
 * row 0 = top) as 8-bit sRGB RGB, rows bottom-up as VTK stores images,
 * into `rgb` (3 * width * height bytes): Intensity * Color * T, divided by
 * the peak P = Intensity * max(Color) * max(1, max texel) when P > 1 (see
 * vtkMRGIAreaLight::GetGeometryActor()). Non-finite or negative
 * `intensity` and `color` values count as 0. The max texel counts only
 * above 1 (float HDR pictures): a picture in [0, 1] keeps one scale from
 * frame to frame (no exposure flicker).
 */
void EncodeDisplayPicture(
  const mrgi_image* picture, double intensity, const double color[3], unsigned char* rgb);

/**
 * Upload `pyramid` into `texture` (in `window`'s context) as one GL
 * texture: mip level k holds pyramid level k (GL_RGB32F, CLAMP_TO_EDGE,
 * LINEAR_MIPMAP_LINEAR, MAX_LEVEL = levels - 1; the upload of
 * mrgi_area_light.h "The texture pyramid"). False when GL cannot create it.
 */
bool UploadPyramid(vtkTextureObject* texture, vtkOpenGLRenderWindow* window,
  const mrgi_area_light_texture_pyramid* pyramid);

/**
 * Upload `count` light samples into `texture` (in `window`'s context) as
 * the GPU sample texture: RGBA32F, MRGI_AREA_LIGHT_SAMPLE_TEXELS wide, one
 * row per sample, NEAREST, CLAMP_TO_EDGE. False when GL cannot create it.
 */
bool UploadSamples(vtkTextureObject* texture, vtkOpenGLRenderWindow* window,
  const mrgi_area_light_sample* samples, int count);
}

#endif
