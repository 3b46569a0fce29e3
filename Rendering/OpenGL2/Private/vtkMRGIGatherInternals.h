/**
 * @file vtkMRGIGatherInternals.h
 * @brief Internal: vtkMRGIGather's GL resources and statistics (its pimpl),
 *        kept apart so that the stage's .cxx holds the gathers only. Not
 *        wrapped, not installed.
 */
#ifndef vtkMRGIGatherInternals_h
#define vtkMRGIGatherInternals_h

#include "vtkMRGIStageResources.h"

#include <functional> // For std::function
#include <vector>     // For std::vector

struct mrgi_multires_layout;
struct vtkMRGIIndirectVisibility;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

struct vtkMRGIGatherInternals
{
  // The flattened irradiance (the gathers' output), sized to the buffer's layout.
  vtkTextureObject* FlatIrradiance = nullptr;
  vtkMRGIStageResources GL; // framebuffer and programs
  // The VPL gathers' visibility term of the current call (never kept).
  const vtkMRGIIndirectVisibility* Visibility = nullptr;
  // GatherVPLsIncremental()'s step before each level (levels then run
  // coarse to fine); null otherwise (never kept).
  const std::function<bool(int)>* BeforeLevel = nullptr;
  // Statistics of the last gather (occlusion queries, one per level).
  std::vector<unsigned int> Queries;
  std::vector<long long> GatheredTexels;
  long long ValidPixels = -1;
  // The tree gathers' VPLs per gathered texel (-1: not counted) and their
  // count target (RGBA32F: nodes used, 0, 0, 1 where gathered).
  double MeanVPLs = -1.0;
  double MaxVPLs = -1.0;
  vtkTextureObject* TreeCounts = nullptr;
  int TreeCountsSize[2] = { 0, 0 };
  // Multiresolution splatting: the subsplat list (the selected texels,
  // sorted by level; host copy kept so that its capacity is reused from
  // frame to frame) in a vertex buffer with its vertex array.
  std::vector<int> SplatTexels;
  std::vector<long long> SplatFirst;
  std::vector<long long> SplatCount;
  unsigned int SplatArray = 0;
  unsigned int SplatBuffer = 0;

  // The output texture and framebuffer for `layout`; false when they cannot be allocated.
  bool Prepare(vtkOpenGLRenderWindow* window, const mrgi_multires_layout& layout);

  // One occlusion query per level (texels gathered).
  void AllocateQueries(vtkWindow* w, int levels);

  // The queries' counts into GatheredTexels (0 below `finest`). Blocking
  // reads, which is why statistics are opt-in.
  void ReadQueries(int finest, int levels);

  // Occlusion queries need the context: only with a window.
  void ReleaseQueries(vtkWindow* w);

  // Vertex array and buffer need the context: only with a window.
  void ReleaseSplats(vtkWindow* w);
};

#endif
