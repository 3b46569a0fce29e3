/**
 * @class   vtkMRGIGBuffer
 * @brief   Internal: vtkMRGIPass's window-sized buffers (HDR colour, depth,
 *          the captured G-buffer, the indirect light's targets) and the
 *          framebuffer that draws into them, created and released in one
 *          place.
 *
 * Layout and meaning of the attachments: mrgi_buffers.h. Colour is float
 * (VTK's lighting is unclamped and the HDR result is what EXR output
 * reads); positions need float range; normals, albedo and the specular
 * attachments are bounded, half floats suffice. Not wrapped, not installed.
 */
#ifndef vtkMRGIGBuffer_h
#define vtkMRGIGBuffer_h

#include "mrgi_buffers.h" // For MRGI_SHADOW_SLOTS

class vtkImageData;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class vtkMRGIGBuffer
{
public:
  vtkMRGIGBuffer() = default;
  ~vtkMRGIGBuffer() { this->Release(nullptr); }

  /**
   * Make every buffer a frame of w x h needs: colour and depth always; with
   * `capture` the G-buffer and the indirect targets; with `specular` also
   * the specular attachments; with `shadows` the light terms, the shadow
   * factors and the shadowed colour; with `display` the display image
   * (FXAA's input and output). Buffers are created once and resized.
   */
  void Prepare(vtkOpenGLRenderWindow* window, int w, int h, bool capture, bool specular,
    bool shadows, bool display);

  /** Free every buffer (their GL objects too when `w` is given). */
  void Release(vtkWindow* w);

  /**
   * Read `viewport` (x, y, w, h) of a window-sized `texture` into `image`
   * (float, bottom-up rows, the first `components` of RGBA). False when
   * the read-back fails.
   */
  static bool ReadViewport(vtkOpenGLRenderWindow* window, vtkTextureObject* texture,
    const int viewport[4], int components, vtkImageData* image);

  /** Whether any GL object is held. */
  bool HoldsResources() const;

  vtkOpenGLFramebufferObject* FrameBuffer = nullptr;
  vtkTextureObject* Color = nullptr;
  vtkTextureObject* Depth = nullptr;
  vtkTextureObject* Position = nullptr;
  vtkTextureObject* Normal = nullptr;
  vtkTextureObject* Albedo = nullptr;
  vtkTextureObject* Specular = nullptr;
  vtkTextureObject* Shininess = nullptr;
  vtkTextureObject* Irradiance = nullptr; // E of the indirect gather
  vtkTextureObject* Indirect = nullptr;   // strength x albedo x E
  vtkTextureObject* Display = nullptr;    // exposed, tone-mapped colour (FXAA runs on it)
  // Direct shadows: VTK's per-light terms (MRGI_GBUFFER_LIGHT0..), the
  // factors of each slot, and the colour they are applied into (swapped
  // with Color once applied, so Color is always the frame's colour).
  vtkTextureObject* LightTerms[MRGI_SHADOW_SLOTS] = {};
  vtkTextureObject* ShadowFactors = nullptr;
  vtkTextureObject* Shadowed = nullptr;

private:
  vtkMRGIGBuffer(const vtkMRGIGBuffer&) = delete;
  void operator=(const vtkMRGIGBuffer&) = delete;
};

#endif
