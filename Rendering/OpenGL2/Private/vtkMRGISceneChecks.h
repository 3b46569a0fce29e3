/**
 * @file    vtkMRGISceneChecks.h
 * @brief   Internal: what vtkMRGIPass asks of the renderer's props before
 *          and after the scene pass: whether any may reflect specularly
 *          (the specular G-buffer is captured only then), and which actors
 *          are point clouds drawn as pixels (warned about once each),
 *          how many tuples of an array are not finite.
 *          Not wrapped, not installed.
 */
#ifndef vtkMRGISceneChecks_h
#define vtkMRGISceneChecks_h

#include "vtkType.h"        // For vtkIdType
#include "vtkWeakPointer.h" // For vtkWeakPointer

#include <vector> // For std::vector

class vtkDataArray;
class vtkObject;
class vtkProp;
class vtkRenderer;

namespace vtkMRGISceneChecks
{
/**
 * Whether some visible prop of `renderer` may reflect specularly: an actor
 * with Specular > 0; other 3D props (assemblies, volumes) are not looked
 * into and count as possibly specular; 2D props (text, overlays) never
 * reach the G-buffer.
 */
bool AnySpecularProp(vtkRenderer* renderer);

/**
 * Warns (as `caller`) once per visible actor whose polydata input is a
 * point cloud (vertex cells only, or no cells): drawn as pixels, it gives
 * the G-buffer and the RSMs no surface and no usable normal. `reported`
 * holds the actors already warned about; deleted ones are dropped from it,
 * so it stays as short as the scene. Call after the scene pass (the
 * mappers' inputs are up to date then).
 */
void WarnPointClouds(
  vtkObject* caller, vtkRenderer* renderer, std::vector<vtkWeakPointer<vtkProp>>& reported);

/** The tuples of `array` with a NaN or infinite component; 0 for no array. */
vtkIdType CountNonFiniteTuples(vtkDataArray* array);
}

#endif
