/**
 * @class   vtkMRGIFullScreenStep
 * @brief   Internal: the GL state of one full-screen step of an MRGI stage,
 *          and the small routines every stage shares (inputs, mask writes,
 *          read-backs of the flattened multiresolution layout).
 *
 * A step draws full-screen quads into the stage's own framebuffer: for its
 * lifetime blending, depth, scissor and stencil tests are off, the viewport
 * and clear colour are saved, and the framebuffer is bound; everything is
 * restored when it ends (RAII, like vtkOpenGLState's Scoped savers).
 * Not wrapped, not installed.
 */
#ifndef vtkMRGIFullScreenStep_h
#define vtkMRGIFullScreenStep_h

#include "vtkOpenGLState.h" // For the scoped state savers

#include <functional>       // For std::function
#include <initializer_list> // For std::initializer_list
#include <vector>           // For std::vector

struct mrgi_multires_layout;
class vtkMRGIProgramCache;
class vtkOpenGLQuadHelper;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkUnsignedCharArray;

class vtkMRGIFullScreenStep
{
public:
  vtkMRGIFullScreenStep(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* fbo);
  ~vtkMRGIFullScreenStep();

  /** Draw into `a` (and `b` when given) over the viewport (x, y, w, h). */
  void Target(vtkTextureObject* a, vtkTextureObject* b, int x, int y, int w, int h);

  /** Draw into every texture of `targets` (attachments 0, 1, ...) over (0, 0, w, h). */
  void Targets(std::initializer_list<vtkTextureObject*> targets, int w, int h);

  vtkOpenGLState* GetState() const { return this->State; }

  /**
   * Write a flattened mask as colour and stencil (the selection, the
   * incremental and the specular stencils): the colour target already set
   * and `depthStencil` are cleared to 0, and every fragment that passes sets
   * its stencil to 1. EndMaskWrite() restores the stencil state and
   * detaches the depth-stencil texture. With `clear` false nothing is
   * cleared (a mask written one level at a time).
   */
  void BeginMaskWrite(vtkTextureObject* depthStencil, bool clear = true);
  void EndMaskWrite();

  /**
   * Read only the texels whose stencil in `depthStencil` is 1 (a gather's
   * early stencil culling; the stencil itself is left unchanged).
   * EndStencilRead() restores the stencil state and detaches it. The
   * colour target is cleared to 0 unless `clear` is false.
   */
  void BeginStencilRead(vtkTextureObject* depthStencil, bool clear = true);
  void EndStencilRead();

  /**
   * Add `source`'s RGB to `target`'s over `viewport` (additive blending,
   * target alpha kept), drawing through `fbo` with the "add" program of
   * `programs` (vtkMRGIAddIndirectFS.glsl). False when the program fails.
   */
  static bool AddRGB(vtkOpenGLRenderWindow* window, vtkMRGIProgramCache& programs,
    vtkOpenGLFramebufferObject* fbo, const int viewport[4], vtkTextureObject* source,
    vtkTextureObject* target);

  /**
   * Draw `quad` over `viewport` of `colour` through `fbo` with the blending
   * colour.rgb = quad.rgb * srcRGB + colour.rgb * dstRGB (GL blend factors;
   * alpha kept): the apply step of the screen-space effects (SSAO
   * multiplies, GL_ZERO / GL_SRC_COLOR; SSGI adds, GL_ONE / GL_ONE).
   * `input` is bound as mrgiInput0, mrgiOrigin and mrgiSize are the
   * viewport's origin and size; `uniforms` (may be empty) sets the rest.
   * False on a GL error (the caller names its stage).
   */
  static bool BlendInto(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* fbo,
    vtkOpenGLQuadHelper* quad, const int viewport[4], vtkTextureObject* input,
    unsigned int srcRGB, unsigned int dstRGB, vtkTextureObject* colour,
    const std::function<void(vtkShaderProgram*)>& uniforms);

  /** Activate `textures` and bind them to the samplers mrgiInput0, mrgiInput1, ... of `program`. */
  static void BindInputs(vtkShaderProgram* program, std::initializer_list<vtkTextureObject*> textures);
  static void UnbindInputs(std::initializer_list<vtkTextureObject*> textures);

  /**
   * Read every level's texture back into the flattened layout (rows
   * bottom-up, the first `components` of each texel's RGBA; 0 outside the
   * levels). `levels[i]` is level i's texture.
   */
  static bool ReadFlattened(vtkOpenGLRenderWindow* window, const mrgi_multires_layout& layout,
    int components, const std::vector<vtkTextureObject*>& levels, std::vector<float>& flat);

  /**
   * One byte per texel of a flattened mask: the red channel of `colour`
   * (> 0.5 -> 1) or, with fromStencil, the stencil of `stencil` as it is
   * (read through `fbo`).
   */
  static bool ReadMask(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* fbo,
    const mrgi_multires_layout& layout, vtkTextureObject* colour, vtkTextureObject* stencil,
    bool fromStencil, vtkUnsignedCharArray* mask);

private:
  vtkMRGIFullScreenStep(const vtkMRGIFullScreenStep&) = delete;
  void operator=(const vtkMRGIFullScreenStep&) = delete;

  vtkOpenGLState* State;
  vtkOpenGLState::ScopedglEnableDisable Blend, DepthTest, Scissor, StencilTest;
  vtkOpenGLState::ScopedglViewport Viewport;
  vtkOpenGLState::ScopedglClearColor ClearColor;
  vtkOpenGLFramebufferObject* Fbo;
};

/**
 * The GL state of a full-screen step over a renderer's viewport (the pass's
 * composites): blending and depth test off (steps turn on what they need),
 * viewport and scissor on the renderer's tile; everything restored when the
 * step ends. Binds nothing: the caller's framebuffer is drawn into.
 */
class vtkMRGIViewportStep
{
public:
  vtkMRGIViewportStep(vtkOpenGLState* ostate, const int viewport[4])
    : Blend(ostate, GL_BLEND)
    , DepthTest(ostate, GL_DEPTH_TEST)
    , Viewport(ostate)
    , Scissor(ostate)
  {
    ostate->vtkglDisable(GL_BLEND);
    ostate->vtkglDisable(GL_DEPTH_TEST);
    ostate->vtkglViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    ostate->vtkglScissor(viewport[0], viewport[1], viewport[2], viewport[3]);
  }

private:
  vtkOpenGLState::ScopedglEnableDisable Blend;
  vtkOpenGLState::ScopedglEnableDisable DepthTest;
  vtkOpenGLState::ScopedglViewport Viewport;
  vtkOpenGLState::ScopedglScissor Scissor;
};

#endif
