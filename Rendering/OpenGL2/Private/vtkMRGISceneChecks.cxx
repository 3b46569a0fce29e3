#include "vtkMRGISceneChecks.h"

#include "vtkActor.h"
#include "vtkDataArray.h"
#include "vtkObject.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProp.h"
#include "vtkProp3D.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cmath>

namespace
{
// Points of an actor's polydata input that is a point cloud (vertex cells
// only, or no cells at all), or 0.
vtkIdType PointCloudPoints(vtkActor* actor)
{
  vtkPolyDataMapper* mapper = vtkPolyDataMapper::SafeDownCast(actor->GetMapper());
  vtkPolyData* data = mapper ? mapper->GetInput() : nullptr;
  if (!data || data->GetNumberOfPoints() == 0)
  {
    return 0;
  }
  const bool surfaceless = data->GetNumberOfPolys() == 0 && data->GetNumberOfStrips() == 0 &&
    data->GetNumberOfLines() == 0;
  return surfaceless ? data->GetNumberOfPoints() : 0;
}
}

//------------------------------------------------------------------------------
bool vtkMRGISceneChecks::AnySpecularProp(vtkRenderer* renderer)
{
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (!prop->GetVisibility() || !vtkProp3D::SafeDownCast(prop))
    {
      continue;
    }
    vtkActor* actor = vtkActor::SafeDownCast(prop);
    if (!actor || actor->GetProperty()->GetSpecular() > 0.0)
    {
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
void vtkMRGISceneChecks::WarnPointClouds(
  vtkObject* caller, vtkRenderer* renderer, std::vector<vtkWeakPointer<vtkProp>>& reported)
{
  reported.erase(std::remove_if(reported.begin(), reported.end(),
                   [](const vtkWeakPointer<vtkProp>& p) { return p == nullptr; }),
    reported.end());
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    vtkActor* actor = vtkActor::SafeDownCast(prop);
    if (!actor || !actor->GetVisibility())
    {
      continue;
    }
    const vtkIdType points = PointCloudPoints(actor);
    if (points == 0 ||
      std::find(reported.begin(), reported.end(), vtkWeakPointer<vtkProp>(prop)) != reported.end())
    {
      continue;
    }
    reported.emplace_back(prop);
    vtkWarningWithObjectMacro(caller,
      "actor " << actor << " draws " << points
               << " points as pixels: the indirect light sees no surface; put "
                  "vtkMRGISurfels (after vtkMRGIPointCloudNormals) before its mapper "
                  "(Documentation/PointClouds-Surfels.md)");
  }
}

//------------------------------------------------------------------------------
vtkIdType vtkMRGISceneChecks::CountNonFiniteTuples(vtkDataArray* array)
{
  vtkIdType bad = 0;
  const int nc = array ? array->GetNumberOfComponents() : 0;
  for (vtkIdType i = 0; array && i < array->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < nc; ++c)
    {
      if (!std::isfinite(array->GetComponent(i, c)))
      {
        ++bad;
        break;
      }
    }
  }
  return bad;
}
