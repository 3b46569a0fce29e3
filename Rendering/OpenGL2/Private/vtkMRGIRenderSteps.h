/**
 * @file    vtkMRGIRenderSteps.h
 * @brief   Internal: how vtkMRGIPass drives VTK's own render steps around
 *          its buffers: the G-buffer clear, hardware selection (picking),
 *          a camera pass with another delegate, the forward steps
 *          (translucency, volumes) over the lit scene, FXAA on the
 *          display image and the overlays over the output.
 *          Not wrapped, not installed.
 */
#ifndef vtkMRGIRenderSteps_h
#define vtkMRGIRenderSteps_h

#include "vtkSmartPointer.h" // For vtkSmartPointer

class vtkCameraPass;
class vtkOpenGLFXAAFilter;
class vtkOpenGLFramebufferObject;
class vtkRenderPass;
class vtkRenderState;
class vtkRenderStepsPass;
class vtkRenderer;
class vtkTextureObject;

namespace vtkMRGIRenderSteps
{
/**
 * First step of the opaque sequence: VTK's camera pass has just cleared
 * every draw buffer to the background colour; the G-buffer attachments
 * must say "no geometry" (0) instead. Respects the renderer's scissor.
 */
vtkSmartPointer<vtkRenderPass> NewClearGBufferPass();

/**
 * Hardware selection (vtkHardwareSelector, vtkPropPicker,
 * vtkRenderer::PickProp) through a vtkRenderStepsPass: hands the props to
 * the selector as the renderer would (VTK 9.1's opaque pass does not).
 */
vtkSmartPointer<vtkRenderPass> NewSelectionPass();

/**
 * Runs `camera` (a vtkRenderStepsPass's camera pass) with `delegate` in
 * place of its usual delegate, then puts the usual one back: the same
 * vtkRenderStepsPass may also be installed on its own (a GI on/off switch).
 */
void RenderCameraWith(vtkCameraPass* camera, vtkRenderPass* delegate, const vtkRenderState* s);

/**
 * Translucent props and volumes of `steps`, drawn over `color` (with
 * `depth`) through `fbo` in `viewport`, as the renderer draws them without
 * passes (depth peeling). Returns the number of props drawn.
 */
int RenderForward(const vtkRenderState* s, vtkRenderStepsPass* steps,
  vtkOpenGLFramebufferObject* fbo, vtkTextureObject* color, vtkTextureObject* depth,
  const int viewport[4]);

/**
 * The 2D overlays of `steps` (text, scalar bars), drawn into the
 * framebuffer bound now (VTK's, after MRGI's output) in `viewport`: after
 * exposure, tone mapping and FXAA, so their colours are exactly the ones
 * the application chose and text is not blurred, as VTK draws them
 * without passes. Returns the number of props drawn.
 */
int RenderOverlays(const vtkRenderState* s, vtkRenderStepsPass* steps, const int viewport[4]);

/**
 * FXAA (vtkOpenGLFXAAFilter, `fxaa` created on first use and owned by the
 * caller, configured from the renderer's vtkFXAAOptions) on `display`,
 * in place, in `viewport`, drawn through `fbo`: MRGI's own single-sample
 * buffer, so the window's multisampling (which makes VTK 9.1's filter
 * copy from a multisampled framebuffer and give black) plays no part.
 */
void RenderFXAA(vtkRenderer* renderer, vtkOpenGLFramebufferObject* fbo, vtkTextureObject* display,
  const int viewport[4], vtkOpenGLFXAAFilter*& fxaa);
}

#endif
