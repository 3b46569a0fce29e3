/**
 * @class   vtkMRGIBMRLevels
 * @brief   The passive buffer of BMR multiresolution screen-space effects
 *          (besenthal-maisch-ropinski 3.2, 4.1): per level k = 0..3 (full,
 *          1/2, 1/4, 1/8 resolution) the effect's colour target, the mask
 *          texture and a depth-stencil texture whose stencil holds S_k.
 *
 * Level k is ceil(W / 2^k) x ceil(H / 2^k) texels for a W x H frame
 * (mrgi_bmr_mask.h). vtkMRGIBMRMask writes the masks and stencils;
 * an effect renders each level under its stencil through
 * vtkMRGIBMRLevels::LevelStep; vtkMRGIBMRBlend reads colours and masks. Only its
 * owner calls Prepare(); stages take it as an argument.
 *
 * Mask texture texel (RGBA32F): (a_k, E_k, R_k + 2 S_k, NE_k), the
 * quantities of mrgi_bmr_mask.h. Colour targets are RGBA32F.
 */
#ifndef vtkMRGIBMRLevels_h
#define vtkMRGIBMRLevels_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <functional> // For std::function
#include <memory>     // For std::unique_ptr

struct vtkMRGIFrameContext;
class vtkFloatArray;
class vtkMRGIFullScreenStep;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkRenderWindow;
class vtkTextureObject;
class vtkUnsignedCharArray;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIBMRLevels : public vtkObject
{
public:
  static vtkMRGIBMRLevels* New();
  vtkTypeMacro(vtkMRGIBMRLevels, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The four levels (MRGI_BMR_LEVELS). */
  static int GetNumberOfLevels();

  /**
   * Allocate the levels for a width x height frame (nothing happens when
   * the size is unchanged). False when a texture cannot be allocated.
   */
  bool Prepare(vtkOpenGLRenderWindow* window, int width, int height);

  ///@{
  /** The frame size of the last Prepare() (0 before). */
  int GetWidth() const { return this->Size[0]; }
  int GetHeight() const { return this->Size[1]; }
  ///@}

  /** Level k's size, ceil(W / 2^k) x ceil(H / 2^k); false for k out of range or before Prepare().
   */
  bool GetLevelSize(int level, int size[2]) const;

  ///@{
  /** Level k's textures; null out of range or before Prepare(). */
  vtkTextureObject* GetColorTexture(int level) const;
  vtkTextureObject* GetMaskTexture(int level) const;
  vtkTextureObject* GetDepthStencilTexture(int level) const;
  ///@}

  ///@{
  /**
   * Read level k back: colour or mask RGBA (4 floats per texel, rows
   * bottom-up), or the stencil (one byte per texel, 0 or 1).
   */
  bool ReadColor(vtkRenderWindow* window, int level, vtkFloatArray* rgba);
  bool ReadMask(vtkRenderWindow* window, int level, vtkFloatArray* rgba);
  bool ReadStencil(vtkRenderWindow* window, int level, vtkUnsignedCharArray* stencil);
  ///@}

  /** The framebuffer the masks and the level steps draw through. */
  vtkOpenGLFramebufferObject* GetFramebuffer() const;

#ifndef __VTK_WRAP__
  /**
   * How an effect renders one level under its stencil: for its lifetime the
   * levels' framebuffer is bound with level k's colour target (cleared to
   * 0) and depth-stencil, the viewport is the level's rectangle and only
   * fragments with S_k = 1 pass (stencil test EQUAL 1, stencil unchanged);
   * blending, depth and scissor tests are off. The caller draws one
   * full-screen step (fragment (x, y) is level-k texel (x, y)). Everything
   * is restored when it ends.
   *
   *     { vtkMRGIBMRLevels::LevelStep step(window, levels, k); quad->Render(); }
   */
  class LevelStep
  {
  public:
    LevelStep(vtkOpenGLRenderWindow* window, vtkMRGIBMRLevels* levels, int level);
    ~LevelStep();
    /** False when the levels were not prepared or the level is out of range (nothing bound). */
    bool IsValid() const { return this->Step != nullptr; }

  private:
    LevelStep(const LevelStep&) = delete;
    void operator=(const LevelStep&) = delete;
    std::unique_ptr<vtkMRGIFullScreenStep> Step;
  };

  /**
   * The size of level `level` (0..`maxLevel`) of a `width` x `height`
   * viewport, ceil(size / 2^level), into `levelSize`, checking that
   * `target` holds it. False, with an error from `reporter` naming
   * `effect`, for a null target, a level out of range or a target that is
   * too small. The one check the effects' single-level Compute() share.
   */
  static bool CheckLevelTarget(vtkObject* reporter, const char* effect, int level, int maxLevel,
    int width, int height, vtkTextureObject* target, int levelSize[2]);

  /**
   * An effect at every level of `levels` under the level's stencil: for
   * k = 0..3, `renderLevel(k)` draws one full-screen step (binding its own
   * program and inputs) while a LevelStep for k is active. A skipped level
   * has an empty stencil: its colour is cleared and nothing passes. False,
   * with an error, when a level cannot be bound, `renderLevel` fails or GL
   * reports an error.
   */
  static bool RenderLevels(vtkOpenGLRenderWindow* window, vtkMRGIBMRLevels* levels,
    const std::function<bool(int level)>& renderLevel);
#endif

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIBMRLevels();
  ~vtkMRGIBMRLevels() override;

  struct Internals;
  std::unique_ptr<Internals> Internal;
  int Size[2] = { 0, 0 };

private:
  vtkMRGIBMRLevels(const vtkMRGIBMRLevels&) = delete;
  void operator=(const vtkMRGIBMRLevels&) = delete;
};

#endif
