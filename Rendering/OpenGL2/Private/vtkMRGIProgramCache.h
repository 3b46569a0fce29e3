/**
 * @class   vtkMRGIProgramCache
 * @brief   Internal: a stage's full-screen programs, keyed by (stage,
 *          defines), built on first use and readied on every later one.
 *
 * Each MRGI stage owns one cache instead of a member per program variant.
 * The program's fragment shader is vtkMRGIShaderUtilities::FullScreenShader()
 * of `defines` followed by the stage's source (its GLSL libraries and main);
 * the vertex shader is VTK's full-screen quad's. Not wrapped, not installed.
 */
#ifndef vtkMRGIProgramCache_h
#define vtkMRGIProgramCache_h

#include <functional> // For std::function
#include <map>        // For std::map
#include <string>     // For std::string

class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkWindow;

class vtkMRGIProgramCache
{
public:
  vtkMRGIProgramCache() = default;
  ~vtkMRGIProgramCache();

  /**
   * The quad of (stage, defines), bound and ready to take uniforms; built
   * from `defines` + `source()` the first time. Null when it does not
   * compile (VTK's shader cache has reported why).
   */
  vtkOpenGLQuadHelper* Ready(vtkOpenGLRenderWindow* window, const std::string& stage,
    const std::string& defines, const std::function<std::string()>& source);

  /** Forget every program, freeing its GL resources when `w` is given. */
  void ReleaseGraphicsResources(vtkWindow* w);

private:
  vtkMRGIProgramCache(const vtkMRGIProgramCache&) = delete;
  void operator=(const vtkMRGIProgramCache&) = delete;

  std::map<std::string, vtkOpenGLQuadHelper*> Quads;
};

#endif
