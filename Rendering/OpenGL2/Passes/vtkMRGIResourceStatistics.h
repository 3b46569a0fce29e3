/**
 * @class   vtkMRGIResourceStatistics
 * @brief   How many texture storages MRGI's passes and stages have
 *          allocated in this process, and how many bytes.
 *
 * Every MRGI texture allocation is counted here: a new texture, or an
 * existing one given storage of a new size (the G-buffer's resize). Uploads
 * into storage that already exists are not counted. The counts are
 * process-wide and only grow; to see what a frame allocates, read them
 * before and after it (a second frame of unchanged settings should add
 * nothing). They explain a first frame's cost on software OpenGL, where
 * llvmpipe zero-fills every new texture in host memory (Documentation/
 * Multiresolution.md, "Cold start"). Thread-safe; the counters are atomic.
 */
#ifndef vtkMRGIResourceStatistics_h
#define vtkMRGIResourceStatistics_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

class MRGIRENDERING_EXPORT vtkMRGIResourceStatistics : public vtkObject
{
public:
  static vtkMRGIResourceStatistics* New();
  vtkTypeMacro(vtkMRGIResourceStatistics, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Texture storages allocated by MRGI in this process so far. */
  static vtkTypeInt64 GetNumberOfTextureAllocations();

  /** Bytes of those storages (width x height x bytes per texel, level 0 only). */
  static vtkTypeInt64 GetTextureBytesAllocated();

  /**
   * Record one allocation of w x h texels of `bytesPerTexel` bytes. MRGI's
   * stages call it where they allocate; not for applications.
   */
  static void RecordTextureAllocation(int w, int h, int bytesPerTexel);

protected:
  vtkMRGIResourceStatistics() = default;
  ~vtkMRGIResourceStatistics() override = default;

private:
  vtkMRGIResourceStatistics(const vtkMRGIResourceStatistics&) = delete;
  void operator=(const vtkMRGIResourceStatistics&) = delete;
};

#endif
