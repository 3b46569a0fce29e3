/**
 * @class   vtkMRGIVPLSelection
 * @brief   Selects virtual point lights (VPLs) from reflective shadow maps
 *          into the VPL cache texture the gather reads.
 *
 * The VPL cache (nichols-shopf-wyman-2009 section 3.2.2) is one texture of
 * MRGI_VPL_TEXELS x count RGBA32F texels, one row per VPL, in the record
 * layout of mrgi_vpl.h, so that the gather reads VPLs coherently.
 *
 * Modes:
 * - Grid (default, the papers' choice): a regular grid over each light view;
 *   each VPL carries the flux and area of its whole block. Runs on the GPU;
 *   its C twin is mrgi_vpl_select_grid().
 * - FluxImportance: VPLs drawn with probability proportional to texel flux,
 *   weighted by 1 / (N p) so the estimate stays unbiased. The RSMs are read
 *   back and mrgi_vpl_select_importance() (C core) selects; the result is
 *   uploaded.
 *
 * With several lights, the VPL budget is split evenly among the lights that
 * have views. Nothing is recomputed while the RSMs and the settings are unchanged.
 */
#ifndef vtkMRGIVPLSelection_h
#define vtkMRGIVPLSelection_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr

class vtkMRGIReflectiveShadowMapPass;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIVPLSelection : public vtkObject
{
public:
  static vtkMRGIVPLSelection* New();
  vtkTypeMacro(vtkMRGIVPLSelection, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum SelectionMode
  {
    Grid = 0,
    FluxImportance = 1
  };

  ///@{
  /** Grid (default) or FluxImportance. */
  vtkSetClampMacro(Mode, int, Grid, FluxImportance);
  vtkGetMacro(Mode, int);
  ///@}

  ///@{
  /** VPLs requested for the whole frame, 0..MRGI_VPL_MAX_COUNT (default 256). */
  vtkSetClampMacro(NumberOfVPLs, int, 0, 4096);
  vtkGetMacro(NumberOfVPLs, int);
  ///@}

  ///@{
  /** Seed of the importance sampler; the same seed gives the same VPLs. */
  vtkSetMacro(Seed, vtkTypeUInt64);
  vtkGetMacro(Seed, vtkTypeUInt64);
  ///@}

  /**
   * Bring the VPL cache up to date for `rsm`'s current maps. Returns the
   * number of VPL rows in the cache (0: no light reaches anything, or no VPLs asked).
   */
  int Update(vtkOpenGLRenderWindow* window, vtkMRGIReflectiveShadowMapPass* rsm);

  /** The VPL cache texture (MRGI_VPL_TEXELS x GetVPLCount()), or nullptr. */
  vtkTextureObject* GetVPLTexture() const;

  /** Rows of the VPL cache after the last Update(). */
  int GetVPLCount() const;

  /** How many times the cache was recomputed. */
  vtkGetMacro(NumberOfSelections, vtkIdType);

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIVPLSelection();
  ~vtkMRGIVPLSelection() override;

  int Mode = Grid;
  int NumberOfVPLs = 256;
  vtkTypeUInt64 Seed = 1;
  vtkIdType NumberOfSelections = 0;

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIVPLSelection(const vtkMRGIVPLSelection&) = delete;
  void operator=(const vtkMRGIVPLSelection&) = delete;
};

#endif
