/**
 * @class   vtkMRGIRSMCompositor
 * @brief   How reflective shadow maps are composited across processes.
 *
 * vtkMRGIReflectiveShadowMapPass calls a compositor, when it has one of more
 * than one process, to agree with the other processes on whether and what
 * to render, and to composite its rendered views with theirs texel by texel
 * (mrgi_rsm_composite.h: the record nearest the light), so that every
 * process ends with the same maps. Both calls are collective: every process
 * makes them in the same order with the same sizes.
 *
 * This is the interface MRGI's render passes see; it keeps them free of
 * VTK's parallel modules (which load VTK's IO libraries).
 * vtkMRGIControllerRSMCompositor (module MRGI::RenderingParallel) implements
 * it over a vtkMultiProcessController, e.g. ParaView's MPI controller.
 */
#ifndef vtkMRGIRSMCompositor_h
#define vtkMRGIRSMCompositor_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <cstddef> // For size_t

#ifndef __VTK_WRAP__
struct mrgi_rsm_view_key;
#endif

class MRGIRENDERING_EXPORT vtkMRGIRSMCompositor : public vtkObject
{
public:
  vtkTypeMacro(vtkMRGIRSMCompositor, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Processes taking part (1 or more); the maps are composited only when more than one. */
  virtual int GetNumberOfProcesses() = 0;

  /** Bytes this process has sent through this compositor since its creation. */
  vtkGetMacro(BytesSent, vtkTypeInt64);

#ifndef __VTK_WRAP__
  /**
   * Collective: values[i] becomes the maximum of values[i] over the
   * processes, for 0 <= i < count (the same count on every process).
   * False on a failure (values then unspecified).
   */
  virtual bool AllReduceMax(double* values, int count) = 0;

  /**
   * Collective: `views` holds `count` planar views of `texels` texels each
   * (MRGI_RSM_COMPOSITE_RECORD_FLOATS x texels floats per view, laid out as
   * mrgi_rsm_composite.h says); each becomes the composite of that view
   * over the processes, with keys[v] saying what is near in view v. Every
   * process passes the same count, texels and keys and gets the same result.
   * False when this process's part failed (it still took part).
   */
  virtual bool CompositeViews(
    float* views, size_t texels, int count, const mrgi_rsm_view_key* keys) = 0;

  /**
   * Collective: values[i] becomes the bitwise OR of values[i] over the
   * processes (the same count on every process). The area lights use it to
   * merge the processes' voxelizations, so that every process's geometry
   * casts area-light shadows on every process. False on a failure.
   */
  virtual bool AllReduceBitwiseOr(vtkTypeUInt32* values, vtkIdType count) = 0;
#endif

protected:
  vtkMRGIRSMCompositor() = default;
  ~vtkMRGIRSMCompositor() override = default;

  vtkTypeInt64 BytesSent = 0;

private:
  vtkMRGIRSMCompositor(const vtkMRGIRSMCompositor&) = delete;
  void operator=(const vtkMRGIRSMCompositor&) = delete;
};

#endif
