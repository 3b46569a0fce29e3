/**
 * @file    vtkMRGIOutput.h
 * @brief   Internal: vtkMRGIPass's "output" step: the HDR colour exposed,
 *          tone mapped and written with the scene's depth to the
 *          framebuffer VTK was drawing into (through FXAA when asked), and
 *          the automatic exposure measured on it. Not wrapped, not installed.
 *
 * Inputs are arguments: the window, the pass's program cache and buffers
 * (vtkMRGIGBuffer), the renderer's viewport in those window-sized buffers.
 * The exposure and the tone curve are mrgi_exposure.h's; the shader is
 * vtkMRGICompositeFS.glsl.
 */
#ifndef vtkMRGIOutput_h
#define vtkMRGIOutput_h

#include <string> // For std::string

class vtkMRGIGBuffer;
class vtkMRGIProgramCache;
class vtkOpenGLFXAAFilter;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkTextureObject;

namespace vtkMRGIOutput
{
/** What Write() writes besides the colour. */
enum DepthMode
{
  NoDepth = 0, ///< colour only, depth test and writes off
  Depth = 1,   ///< the scene's depth too (depth function GL_ALWAYS)
  /**
   * The depth, and the G-buffer's eye-space position and normal into draw
   * buffers 1 and 2: an enclosing pass reading VTK's G-buffer convention
   * (vtkSSAOPass) finds them there.
   */
  DepthAndGBuffer = 2
};

/**
 * Writes `source` (window-sized) into the framebuffer bound now, over
 * `viewport` (x, y, w, h): RGB x `scale` (2^EV), through mrgi_tone_curve
 * when `toneMap`, with what `depth` says. False when the output program
 * cannot be built (nothing written).
 */
bool Write(vtkOpenGLRenderWindow* window, vtkMRGIProgramCache& programs, const vtkMRGIGBuffer& g,
  const int viewport[4], vtkTextureObject* source, float scale, bool toneMap, DepthMode depth);

/**
 * The output with FXAA: g.Color is exposed and tone mapped into
 * g.Display (which Prepare() made with `display`), FXAA runs on it
 * (vtkMRGIRenderSteps::RenderFXAA, `fxaa` created on first use, owned by
 * the caller), and the display image is written as it is with `depth`
 * into the framebuffer bound when this was called. False when a program
 * cannot be built.
 */
bool WriteWithFXAA(vtkRenderer* renderer, vtkOpenGLRenderWindow* window,
  vtkMRGIProgramCache& programs, vtkMRGIGBuffer& g, const int viewport[4], float scale,
  bool toneMap, DepthMode depth, vtkOpenGLFXAAFilter*& fxaa);

/**
 * The automatic EV of g.Color over `viewport`, foreground pixels only
 * (depth < 1): mrgi_exposure_auto_ev of the log-average luminance and the
 * MRGI_EXPOSURE_HIGHLIGHT_FRACTION quantile, for `key`. Reads the colour
 * and the depth back. False (`ev` 0, `problem` says why) when the read-back
 * or the measurement fails.
 */
bool MeasureExposure(vtkOpenGLRenderWindow* window, const vtkMRGIGBuffer& g,
  const int viewport[4], double key, double& ev, std::string& problem);
}

#endif
