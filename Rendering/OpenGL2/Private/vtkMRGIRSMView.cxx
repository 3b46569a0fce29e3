#include "vtkMRGIRSMView.h"

#include "vtkMath.h"

#include <algorithm>
#include <cmath>

//------------------------------------------------------------------------------
void vtkMRGIRSMView::PickUp(const double dir[3], double up[3])
{
  const double candidates[2][3] = { { 0, 1, 0 }, { 1, 0, 0 } };
  const double* c = std::fabs(vtkMath::Dot(dir, candidates[0])) < 0.9 ? candidates[0] : candidates[1];
  up[0] = c[0];
  up[1] = c[1];
  up[2] = c[2];
}

//------------------------------------------------------------------------------
void vtkMRGIRSMView::SetPerspective(const double eye[3], const double dir[3], double fovDeg,
  const double center[3], double radius, double texelsPerSide)
{
  if (!this->Camera)
  {
    this->Camera = vtkSmartPointer<vtkCamera>::New();
  }
  double up[3];
  vtkMRGIRSMView::PickUp(dir, up);
  this->Camera->SetPosition(const_cast<double*>(eye));
  this->Camera->SetFocalPoint(eye[0] + dir[0], eye[1] + dir[1], eye[2] + dir[2]);
  this->Camera->SetViewUp(up);
  const double distance = vtkMath::Distance2BetweenPoints(eye, center);
  const double farPlane = std::sqrt(distance) + radius;
  const double nearPlane = std::max(farPlane * 1e-3, std::sqrt(distance) - radius);
  const double f = 1.0 / std::tan(vtkMath::RadiansFromDegrees(0.5 * fovDeg));
  vtkNew<vtkMatrix4x4> proj;
  proj->Zero();
  proj->SetElement(0, 0, f);
  proj->SetElement(1, 1, f);
  proj->SetElement(2, 2, (farPlane + nearPlane) / (nearPlane - farPlane));
  proj->SetElement(2, 3, 2.0 * farPlane * nearPlane / (nearPlane - farPlane));
  proj->SetElement(3, 2, -1.0);
  this->Camera->SetExplicitProjectionTransformMatrix(proj);
  this->Camera->SetUseExplicitProjectionTransformMatrix(true);
  this->Perspective = true;
  this->TexelSize = 2.0 / (f * texelsPerSide);
}
