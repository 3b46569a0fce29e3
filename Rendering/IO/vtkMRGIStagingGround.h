/**
 * @file    vtkMRGIStagingGround.h
 * @brief   Internal (MRGI::RenderingIO): the ground vtkMRGIStaging::Stage()
 *          puts under the data.
 *
 * A Lambertian quad (albedo 0.7) just under the data along the up axis,
 * covering at least 3 horizontal sizes of the data around its centre and
 * what the framed camera sees of the plane, up to 20 sizes (6 with an area
 * key light, whose voxel shadows want a short depth range). Not wrapped,
 * not installed.
 */
#ifndef vtkMRGIStagingGround_h
#define vtkMRGIStagingGround_h

#include "vtkSmartPointer.h" // For vtkSmartPointer

class vtkActor;
struct mrgi_framing;

namespace vtkMRGIStagingGround
{
/**
 * The ground's actor (not pickable; point normals along `upv`) for the up
 * axis `up` (an mrgi_axis, `upv` its unit vector), the data's finite
 * `bounds`, the camera `framing` with tan(view angle / 2) `tanHalf` and
 * the viewport's `aspect`; `areaKeyLight` keeps it short (see above).
 */
vtkSmartPointer<vtkActor> Make(int up, const double upv[3], const double bounds[6],
  const mrgi_framing& framing, double tanHalf, double aspect, bool areaKeyLight);
}

#endif
