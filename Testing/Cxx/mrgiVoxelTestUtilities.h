/**
 * @file mrgiVoxelTestUtilities.h
 * @brief What the voxel tests (TestMRGIVoxelization, TestMRGIVoxelMarch)
 *        share: the eye-space triangles of a renderer's scene found
 *        independently of vtkMRGIVoxelization, their depth range, and a
 *        one-line actor.
 */
#ifndef mrgiVoxelTestUtilities_h
#define mrgiVoxelTestUtilities_h

#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkAssembly.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkMatrix4x4.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProp3DCollection.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkTriangleFilter.h"
#include "vtkTypeUInt32Array.h"
#include "vtkMRGIVoxelization.h"

#include "mrgi_voxel_march.h"

#include <algorithm>
#include <array>
#include <vector>

namespace mrgitest
{
using Triangle = std::array<double, 9>; // three eye-space points

// Row-major 4x4 product.
inline void Multiply(const double a[16], const double b[16], double out[16])
{
  double r[16];
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      double s = 0;
      for (int k = 0; k < 4; ++k)
      {
        s += a[4 * i + k] * b[4 * k + j];
      }
      r[4 * i + j] = s;
    }
  }
  std::copy(r, r + 16, out);
}

inline void AddActorTriangles(vtkActor* actor, const double objectToWorld[16], const double worldToEye[16],
  std::vector<Triangle>& out)
{
  vtkPolyDataMapper* mapper = vtkPolyDataMapper::SafeDownCast(actor->GetMapper());
  MRGI_TEST_CHECK(mapper);
  mapper->Update();
  vtkPolyData* data = vtkPolyData::SafeDownCast(mapper->GetInputDataObject(0, 0));
  MRGI_TEST_CHECK(data);
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputData(data);
  tri->PassVertsOff();
  tri->PassLinesOff();
  tri->Update();
  vtkPolyData* t = tri->GetOutput();
  double m[16];
  Multiply(worldToEye, objectToWorld, m);
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = t->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    if (n != 3)
    {
      continue;
    }
    Triangle tr;
    for (int k = 0; k < 3; ++k)
    {
      double p[3];
      t->GetPoint(ids[k], p);
      for (int r = 0; r < 3; ++r)
      {
        tr[3 * k + r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
      }
    }
    out.push_back(tr);
  }
}

// The eye-space triangles the voxelization must see, found independently of
// the class: visible actors with opacity 1 and assembly parts (assembly
// matrix x part matrix).
inline std::vector<Triangle> SceneTriangles(vtkRenderer* ren)
{
  std::vector<Triangle> out;
  vtkMatrix4x4* view = ren->GetActiveCamera()->GetModelViewTransformMatrix();
  double worldToEye[16];
  std::copy(view->GetData(), view->GetData() + 16, worldToEye);
  vtkPropCollection* props = ren->GetViewProps();
  props->InitTraversal();
  while (vtkProp* prop = props->GetNextProp())
  {
    if (!prop->GetVisibility())
    {
      continue;
    }
    if (vtkActor* actor = vtkActor::SafeDownCast(prop))
    {
      if (actor->GetProperty()->GetOpacity() < 1.0)
      {
        continue;
      }
      AddActorTriangles(actor, actor->GetMatrix()->GetData(), worldToEye, out);
    }
    else if (vtkAssembly* assembly = vtkAssembly::SafeDownCast(prop))
    {
      vtkProp3DCollection* parts = assembly->GetParts();
      parts->InitTraversal();
      while (vtkProp3D* part = parts->GetNextProp3D())
      {
        vtkActor* partActor = vtkActor::SafeDownCast(part);
        if (!partActor || !partActor->GetVisibility() ||
          partActor->GetProperty()->GetOpacity() < 1.0)
        {
          continue;
        }
        double m[16];
        Multiply(assembly->GetMatrix()->GetData(), partActor->GetMatrix()->GetData(), m);
        AddActorTriangles(partActor, m, worldToEye, out);
      }
    }
  }
  return out;
}

inline void DepthRange(const std::vector<Triangle>& tris, double range[2])
{
  range[0] = VTK_DOUBLE_MAX;
  range[1] = -VTK_DOUBLE_MAX;
  for (const Triangle& t : tris)
  {
    for (int k = 0; k < 3; ++k)
    {
      range[0] = std::min(range[0], -t[3 * k + 2]);
      range[1] = std::max(range[1], -t[3 * k + 2]);
    }
  }
}

inline vtkSmartPointer<vtkActor> MakeActor(vtkAlgorithm* source)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}


/**
 * The voxels of `vox`'s last Voxelize() read back into `words` and described
 * for the C twins (grid, projection, march parameters), checked with
 * mrgi_voxel_view_check(); `worldToView` gets the voxelized frame's world ->
 * view matrix. Fails the test when a read-back or the check fails.
 */
inline mrgi_voxel_view ReadVoxelView(vtkMRGIVoxelization* vox, vtkRenderWindow* window,
  vtkTypeUInt32Array* words, double worldToView[16])
{
  mrgi_voxel_view view{};
  MRGI_TEST_CHECK(vox->ReadVoxels(window, words));
  MRGI_TEST_CHECK(vox->GetGrid(&view.grid, &view.projection));
  vox->GetMarchParams(&view.params);
  view.voxels = words->GetPointer(0);
  view.voxel_words = static_cast<size_t>(words->GetNumberOfValues());
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_voxel_view_check(&view, &err) == MRGI_OK);
  MRGI_TEST_CHECK(vox->GetLastWorldToView(worldToView));
  return view;
}
}

#endif
