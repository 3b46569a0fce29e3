/**
 * @file vtkMRGIFrameContext.h
 * @brief What every MRGI stage of one frame reads: the window, the G-buffer,
 *        the viewport, the camera's transforms and projection, the timer.
 *
 * vtkMRGIPass builds one per frame, once the G-buffer is captured, and
 * passes it by const reference to the stages (vtkMRGIGather,
 * vtkMRGIUpsample, vtkMRGISpecularStencil, vtkMRGIAreaLightStage, ...).
 * Tests that drive a stage alone fill one by hand. A plain struct: the
 * stages never keep it, and nothing here is owned.
 */
#ifndef vtkMRGIFrameContext_h
#define vtkMRGIFrameContext_h

class vtkOpenGLRenderWindow;
class vtkRenderTimerLog;
class vtkRenderer;
class vtkTextureObject;

struct vtkMRGIFrameContext
{
  vtkOpenGLRenderWindow* Window = nullptr;
  vtkRenderer* Renderer = nullptr;

  ///@{
  /**
   * The G-buffer (mrgi_buffers.h): eye-space position (xyz, w = 1 where
   * geometry) and normal, albedo, and with specular capture k_s c_s and the
   * Phong exponent. Window-sized textures; the frame's pixel (0, 0) is
   * texel (Viewport[0], Viewport[1]). Specular and Shininess are null when
   * no visible prop is specular.
   */
  vtkTextureObject* Position = nullptr;
  vtkTextureObject* Normal = nullptr;
  vtkTextureObject* Albedo = nullptr;
  vtkTextureObject* Specular = nullptr;
  vtkTextureObject* Shininess = nullptr;
  ///@}

  /** The renderer's tile: x, y, width, height in pixels. */
  int Viewport[4] = { 0, 0, 0, 0 };

  /** Eye -> world, column-major (OpenGL's order), as float for uniforms and as double. */
  float ViewToWorld[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  double ViewToWorldDouble[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };

  /** The camera's projection: true for parallel (the view vector is -z everywhere). */
  bool Parallel = false;

  /**
   * Pixel size at eye-space depth d: max(a |d| + b, tiny)
   * (mrgi_multires_pixel_size_coefficients()); {a, b}.
   */
  double PixelSize[2] = { 0.0, 0.0 };

  /** GPU timer for the stages' events; null: nothing is timed. Not owned. */
  vtkRenderTimerLog* Timer = nullptr;
};

#endif
