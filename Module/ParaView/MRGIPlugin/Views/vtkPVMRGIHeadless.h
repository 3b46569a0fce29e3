/**
 * @file    vtkPVMRGIHeadless.h
 * @brief   The MRGI plugin's load-time step: headless windows for ParaView.
 *
 * Debian's ParaView 5.11 is built for X only: pvbatch without an X server
 * aborts in vtkXOpenGLRenderWindow at its first render. ParaView makes the
 * batch process's window with vtkRenderWindow::New(), i.e. through VTK's
 * object factories (vtkPVProcessWindow::NewWindow). When the plugin is
 * loaded, vtkPVMRGIInitializePlugin() registers a factory override of
 * vtkRenderWindow with MRGI's headless windows (EGL, else OSMesa; see
 * vtkMRGIRenderWindowFactory) if and only if X cannot be had: MRGI_BACKEND
 * names egl or osmesa, or no X display opens. With a working display
 * nothing changes. The plugin must be loaded before the first view is
 * created: through PV_PLUGIN_PATH, `--plugins`, or LoadPlugin() before
 * CreateView()/Show().
 */
#ifndef vtkPVMRGIHeadless_h
#define vtkPVMRGIHeadless_h

#include "MRGIParaViewModule.h" // For export macro

/** Called by the plugin when it loads (paraview_add_plugin INITIALIZERS). */
MRGIPARAVIEW_EXPORT void vtkPVMRGIInitializePlugin();

/**
 * The backend ParaView's new render windows get: "x" (untouched), "egl" or
 * "osmesa" (MRGI's override), as decided when the plugin loaded.
 */
MRGIPARAVIEW_EXPORT const char* vtkPVMRGIHeadlessBackend();

class vtkOpenGLRenderWindow;

/**
 * Makes a view's window ready to draw with MRGI's headless process window's
 * context: once, when the plugin supplied the windows and `window` is not
 * initialised yet, makes the context current, loads the GL functions
 * (vtkMRGIEGLRenderWindow::LoadOpenGLFunctions) and marks the window
 * initialised (its GL state is the process window's, already set up). ParaView's own path (vtkOpenGLRenderWindow::OpenGLInit)
 * asks GLEW for a GLX display, which an EGL context has not, and so fails,
 * with an error, on every frame. Does nothing with X or a null window.
 */
MRGIPARAVIEW_EXPORT void vtkPVMRGIPrepareHeadlessView(vtkOpenGLRenderWindow* window);

#endif
