/**
 * @file vtkMRGIHeadlessDepth.h
 * @brief The depth bits a headless window reports: those of the framebuffer
 *        VTK renders into, not those of framebuffer 0 (private to the
 *        headless windows).
 *
 * vtkRenderer::ResetCameraClippingRange() picks its near-plane tolerance
 * from vtkRenderWindow::GetDepthBufferSize(): 0.001 of the far distance
 * with more than 16 bits, else 0.01. VTK's vtkOpenGLRenderWindow asks
 * framebuffer 0, which a surfaceless EGL context or a depth-less OSMesa
 * buffer does not have (0 bits), so a headless window got the 16-bit
 * tolerance and, in deep scenes, a near plane ten times farther than a
 * desktop window's: the 120 m corridor lost every wall within 2.08 m of the
 * camera (8% of the pixels) while the ground truth, which does not clip,
 * kept them. Nothing draws into framebuffer 0 here: VTK renders into its own
 * framebuffers (RenderFramebuffer), whose depth attachment is what counts.
 */
#ifndef vtkMRGIHeadlessDepth_h
#define vtkMRGIHeadlessDepth_h

class vtkOpenGLRenderWindow;

namespace vtkMRGIHeadlessDepth
{
/**
 * Depth bits of `window`'s RenderFramebuffer once it exists (`initialized`:
 * the window has a current-able context); before that, and if the query
 * fails, 24: what vtkOpenGLRenderWindow reports before it has a context and
 * the least its framebuffers get.
 */
int RenderFramebufferDepthBits(vtkOpenGLRenderWindow* window, bool initialized);
}

#endif
