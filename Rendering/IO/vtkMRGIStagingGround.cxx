#include "vtkMRGIStagingGround.h"

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"

#include "mrgi_framing.h"

#include <algorithm>
#include <cmath>

namespace
{
// The ground: albedo, and its size around the data in horizontal sizes.
constexpr double GroundAlbedo = 0.7;
constexpr double GroundMinSizes = 3.0;
constexpr double GroundMaxSizes = 20.0;
// With an area key light, whose voxel shadows slice the camera's depth
// range into 128: a ground reaching far behind the data stretches that
// range and the data shadows itself in speckles. It ends closer (where
// the light's 1/d^2 has faded it).
constexpr double GroundMaxSizesArea = 6.0;
constexpr double GroundGap = 1e-3;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkActor> vtkMRGIStagingGround::Make(int up, const double upv[3],
  const double bounds[6], const mrgi_framing& framing, double tanHalf, double aspect,
  bool areaKeyLight)
{
  double center[3], size[3];
  for (int c = 0; c < 3; ++c)
  {
    center[c] = 0.5 * (bounds[2 * c] + bounds[2 * c + 1]);
    size[c] = bounds[2 * c + 1] - bounds[2 * c];
  }
  const int k = up / 2;
  const int a1 = (k + 1) % 3;
  const int a2 = (k + 2) % 3;
  const double sign = (up % 2) ? -1.0 : 1.0;
  double largest = std::max(size[0], std::max(size[1], size[2]));
  largest = largest > 0 ? largest : 1.0;
  // Just under the data along up.
  const double level =
    (sign > 0 ? bounds[2 * k] : bounds[2 * k + 1]) - sign * GroundGap * largest;
  double horizontal = std::max(size[a1], size[a2]);
  horizontal = horizontal > 0 ? horizontal : largest;
  // What the camera sees of the plane: where the corner rays of the view
  // hit it (a ray above the horizon reaches the largest size).
  double lo[2] = { center[a1] - 0.5 * GroundMinSizes * horizontal,
    center[a2] - 0.5 * GroundMinSizes * horizontal };
  double hi[2] = { center[a1] + 0.5 * GroundMinSizes * horizontal,
    center[a2] + 0.5 * GroundMinSizes * horizontal };
  double d[3], right[3], vup[3];
  for (int c = 0; c < 3; ++c)
  {
    d[c] = framing.focal[c] - framing.position[c];
  }
  vtkMath::Normalize(d);
  vtkMath::Cross(d, framing.view_up, right);
  vtkMath::Normalize(right);
  vtkMath::Cross(right, d, vup);
  const double reach =
    0.5 * (areaKeyLight ? GroundMaxSizesArea : GroundMaxSizes) * horizontal;
  for (int corner = 0; corner < 4; ++corner)
  {
    const double sx = (corner & 1) ? 1.0 : -1.0;
    const double sy = (corner & 2) ? 1.0 : -1.0;
    double ray[3];
    for (int c = 0; c < 3; ++c)
    {
      ray[c] = d[c] + sx * tanHalf * aspect * right[c] + sy * tanHalf * vup[c];
    }
    const double down = ray[k];
    const double height = framing.position[k] - level;
    double hit[3];
    if (down * sign < 0 && height * sign > 0)
    {
      const double t = height / -down;
      for (int c = 0; c < 3; ++c)
      {
        hit[c] = framing.position[c] + t * ray[c];
      }
    }
    else
    {
      // Towards the horizon: as far as the ground may reach.
      const double h1 = ray[a1], h2 = ray[a2];
      const double hn = std::sqrt(h1 * h1 + h2 * h2);
      hit[a1] = center[a1] + (hn > 0 ? reach * h1 / hn : 0);
      hit[a2] = center[a2] + (hn > 0 ? reach * h2 / hn : 0);
    }
    lo[0] = std::min(lo[0], hit[a1]);
    lo[1] = std::min(lo[1], hit[a2]);
    hi[0] = std::max(hi[0], hit[a1]);
    hi[1] = std::max(hi[1], hit[a2]);
  }
  lo[0] = std::max(lo[0], center[a1] - reach);
  lo[1] = std::max(lo[1], center[a2] - reach);
  hi[0] = std::min(hi[0], center[a1] + reach);
  hi[1] = std::min(hi[1], center[a2] + reach);

  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  const double uv[4][2] = { { lo[0], lo[1] }, { hi[0], lo[1] }, { hi[0], hi[1] },
    { lo[0], hi[1] } };
  for (const auto& corner : uv)
  {
    double p[3];
    p[k] = level;
    p[a1] = corner[0];
    p[a2] = corner[1];
    points->InsertNextPoint(p);
    normals->InsertNextTuple(upv);
  }
  // (a1, a2, k) is cyclic: the corners turn counter-clockwise about +k;
  // reversed for an up axis pointing to -k.
  vtkIdType quad[4] = { 0, 1, 2, 3 };
  if (sign < 0)
  {
    std::reverse(quad, quad + 4);
  }
  vtkNew<vtkCellArray> polys;
  polys->InsertNextCell(4, quad);
  vtkNew<vtkPolyData> plane;
  plane->SetPoints(points);
  plane->SetPolys(polys);
  plane->GetPointData()->SetNormals(normals);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(plane);
  mapper->ScalarVisibilityOff();
  auto ground = vtkSmartPointer<vtkActor>::New();
  ground->SetMapper(mapper);
  vtkProperty* property = ground->GetProperty();
  property->SetColor(GroundAlbedo, GroundAlbedo, GroundAlbedo);
  property->SetAmbient(0.0);
  property->SetDiffuse(1.0);
  property->SetSpecular(0.0);
  ground->PickableOff();
  return ground;
}
