/**
 * @class   vtkMRGIVoxelGeometry
 * @brief   Internal: what vtkMRGIVoxelization draws: the triangles of a
 *          renderer's opaque polygonal props in vertex buffers, cached per
 *          polydata, and the draw of them with one model-view per actor.
 *
 * Collect() walks the renderer's props as the class notes of
 * vtkMRGIVoxelization say (visible, opaque vtkActors with a
 * vtkPolyDataMapper and vtkPolyData input, or a vtkCompositePolyDataMapper2
 * and the visible opaque polydata leaves of its composite input, assembly
 * parts included; others counted as skipped) and uploads each polydata's triangles (polygons and
 * strips, through vtkTriangleFilter where they are not triangles already)
 * once, again only when its MTime changes, as float xyz relative to the
 * data's centre so that data far from the origin keeps float precision.
 * Actors that share data share its buffer; buffers of data no longer drawn
 * are freed. Draw() draws every collected actor with the model-view
 * view x actor x centre shift computed in double, so moving an actor or the
 * camera uploads nothing.
 *
 * GL objects live in the context current at Collect() and Draw(); the
 * owner releases them there (Release(true)) or forgets them when that
 * context is gone (Release(false)). Not wrapped, not installed.
 */
#ifndef vtkMRGIVoxelGeometry_h
#define vtkMRGIVoxelGeometry_h

#include "vtkType.h" // For vtkIdType

#include <cstddef> // For size_t
#include <memory>  // For std::unique_ptr

class vtkRenderer;
class vtkShaderProgram;

class vtkMRGIVoxelGeometry
{
public:
  vtkMRGIVoxelGeometry();
  /** Forgets the GL objects without GL calls: release them first. */
  ~vtkMRGIVoxelGeometry();

  /**
   * Gather what `ren` shows for the next Draw() and bring the vertex
   * buffers up to date (in the current context): uploads data that is new
   * or modified, frees the buffers of data no longer shown.
   */
  void Collect(vtkRenderer* ren);

  /**
   * Draw the collected actors as GL_TRIANGLES with `program` bound (its
   * attribute vertexMC, its uniform mrgiModelView set per actor to
   * worldToView x object -> world x centre shift; `worldToView` row-major,
   * as vtkMatrix4x4 stores it). Returns the triangles drawn.
   */
  vtkIdType Draw(vtkShaderProgram* program, const double worldToView[16]);

  /**
   * Actors (assembly parts and the leaves of a composite input count one
   * each) the last Collect() will draw.
   */
  int GetNumberOfDrawnProps() const;

  /** Visible props the last Collect() left out (translucent, not polygonal). */
  int GetNumberOfSkippedProps() const;

  /** Polydata with a vertex buffer. */
  size_t GetNumberOfCachedGeometries() const;

  /** Whether any GL object (vertex buffer, vertex array) is held. */
  bool HoldsResources() const;

  /**
   * Free the vertex buffers and the vertex array (with GL calls only when
   * `haveContext`: the context they live in is current) and forget what
   * was collected.
   */
  void Release(bool haveContext);

private:
  vtkMRGIVoxelGeometry(const vtkMRGIVoxelGeometry&) = delete;
  void operator=(const vtkMRGIVoxelGeometry&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
