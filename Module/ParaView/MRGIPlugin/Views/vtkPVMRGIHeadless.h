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

#endif
