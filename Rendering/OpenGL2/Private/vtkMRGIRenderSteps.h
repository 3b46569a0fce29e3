/**
 * @file    vtkMRGIRenderSteps.h
 * @brief   Internal: how vtkMRGIPass drives VTK's own render steps around
 *          its buffers: the G-buffer clear, hardware selection (picking),
 *          a camera pass with another delegate, and the forward steps
 *          (translucency, FXAA, volumes, overlays) over the lit scene.
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
 * Translucent props, volumes and overlays of `steps`, drawn over `color`
 * (with `depth`) through `fbo` in `viewport`, as the renderer draws them
 * without passes (depth peeling, FXAA with the filter `fxaa`, created on
 * first use and owned by the caller). Returns the number of props drawn.
 */
int RenderForward(const vtkRenderState* s, vtkRenderStepsPass* steps,
  vtkOpenGLFramebufferObject* fbo, vtkTextureObject* color, vtkTextureObject* depth,
  const int viewport[4], vtkOpenGLFXAAFilter*& fxaa);
}

#endif
