/**
 * @class   vtkMRGIBRSMInversion
 * @brief   GPU inversion of the BRSM 2-D CDF (ritschel-et-al-2011 section
 *          4.1): texel VPLs written straight into the VPL cache.
 *
 * Input: the float CDF and the N sample values that the C core builds
 * (mrgi_brsm_cdf_float.h: mrgi_brsm_cdf_to_float(), mrgi_brsm_sample_values()),
 * uploaded unchanged as R32F / RG32F textures, and the light's RSM view
 * textures. One fragment pass per view (vtkMRGIBRSMInvertFS.glsl) draws one
 * fragment per VPL texel (MRGI_VPL_TEXELS per VPL): it binary-searches the
 * column-sum CDF, then the column, computes the fractions and p, and writes
 * the texel VPL record (Phi_t / (N p), A_t / (N p)) of the picks that fall in
 * that view into rows FirstRow..FirstRow+N-1 of the target (mrgi_vpl.h).
 * C twin: mrgi_brsm_cdf_float_invert() + mrgi_brsm_float_vpl(); the picks
 * (texels and fractions) match bit for bit on an IEEE GPU (cxx.TestMRGIBRSM).
 *
 * WritePicks (tests): write (x, r, fx, fy) to texel 0 and (p, picked, 0, 0)
 * to texel 1 of each row instead of the records.
 */
#ifndef vtkMRGIBRSMInversion_h
#define vtkMRGIBRSMInversion_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <string> // For std::string
#include <vector> // For std::vector

class vtkOpenGLFramebufferObject;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIBRSMInversion : public vtkObject
{
public:
  static vtkMRGIBRSMInversion* New();
  vtkTypeMacro(vtkMRGIBRSMInversion, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** One RSM view's textures (RGBA32F, size x size). */
  struct View
  {
    vtkTextureObject* Position = nullptr;
    vtkTextureObject* Normal = nullptr;
    vtkTextureObject* Flux = nullptr;
  };

  ///@{
  /** Write the picks instead of the records (tests). Default off. */
  vtkSetMacro(WritePicks, bool);
  vtkGetMacro(WritePicks, bool);
  vtkBooleanMacro(WritePicks, bool);
  ///@}

  /**
   * Invert `count` samples (2 * count floats, (u1, u2) interleaved) through
   * `cdf` (mrgi_brsm_cdf_float_count() floats for `views.size()` views of
   * `size`^2) into rows firstRow.. of `target` (RGBA32F, MRGI_VPL_TEXELS
   * wide). False, with `error` naming the problem, on bad arguments or a
   * shader that does not build; nothing is drawn then.
   */
  bool Invert(vtkOpenGLRenderWindow* window, int size, const std::vector<View>& views,
    const std::vector<float>& cdf, const std::vector<float>& samples, int count,
    vtkTextureObject* target, int firstRow, std::string& error);

  /** Free the GL resources. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIBRSMInversion();
  ~vtkMRGIBRSMInversion() override;

  bool WritePicks = false;

private:
  vtkMRGIBRSMInversion(const vtkMRGIBRSMInversion&) = delete;
  void operator=(const vtkMRGIBRSMInversion&) = delete;

  vtkOpenGLQuadHelper* Quad = nullptr;
  bool QuadPicks = false; // the WritePicks the quad was built with
  vtkOpenGLFramebufferObject* FrameBuffer = nullptr;
  vtkTextureObject* CDF = nullptr;
  vtkTextureObject* Samples = nullptr;
};

#endif
