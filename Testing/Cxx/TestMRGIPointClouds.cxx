// Point clouds from any reader: vtkMRGIPointCloud::IsPointCloud and
// NewFiniteCloud, and vtkMRGISceneBuilder's point-cloud path for LAS,
// vertex-only PLY, legacy VTK and XML files: NaN points left out, an
// all-NaN cloud a clear error (not an empty image), one point, LAZ and PCD
// messages. A LAS cloud rendered with vtkMRGIPass shows its colours, with
// no NaN pixel.
#include "mrgiLASTestUtilities.h"
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkMRGIPass.h"
#include "vtkMapper.h"
#include "vtkMRGIPointCloud.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkPLYWriter.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataWriter.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkXMLUnstructuredGridWriter.h"

#include <cstring>
#include <limits>

namespace
{
const double NaN = std::numeric_limits<double>::quiet_NaN();

// `n` points on a 10 x 10 x (n/100) grid; every `nanEvery`-th one NaN (0: none).
vtkSmartPointer<vtkPolyData> Cloud(vtkIdType n, vtkIdType nanEvery, bool withVerts)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> value;
  value->SetName("Value");
  for (vtkIdType i = 0; i < n; ++i)
  {
    const bool bad = nanEvery > 0 && i % nanEvery == 0;
    points->InsertNextPoint(bad ? NaN : double(i % 10), double((i / 10) % 10), double(i / 100));
    value->InsertNextValue(static_cast<float>(i));
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  cloud->GetPointData()->AddArray(value);
  if (withVerts)
  {
    vtkNew<vtkCellArray> verts;
    for (vtkIdType i = 0; i < n; ++i)
    {
      verts->InsertNextCell(1, &i);
    }
    cloud->SetVerts(verts);
  }
  return cloud;
}

struct Built
{
  bool Ok = false;
  std::string Error;
  vtkIdType Points = 0;
  vtkIdType Surfels = 0; // polygons the cloud's actor draws
  int Actors = 0;
};

Built Build(const std::string& scene)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene(scene.c_str());
  Built b;
  b.Ok = builder->Build(renderer);
  b.Error = builder->GetLastErrorMessage();
  b.Points = builder->GetBuiltPointCount();
  b.Actors = renderer->GetActors()->GetNumberOfItems();
  if (b.Ok && b.Points > 0)
  {
    // The cloud's actor is the first one (staging, when on, adds a ground).
    vtkActor* actor = vtkActor::SafeDownCast(renderer->GetActors()->GetItemAsObject(0));
    auto* drawn = vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0));
    b.Surfels = drawn ? drawn->GetNumberOfPolys() : 0;
  }
  std::printf("%s: %s\n", scene.c_str(),
    b.Ok ? ("ok, " + std::to_string(b.Points) + " points").c_str() : b.Error.c_str());
  if (!b.Ok)
  {
    MRGI_TEST_CHECK(b.Actors == 0);
    MRGI_TEST_CHECK(b.Error.find("'" + scene + "'") != std::string::npos);
  }
  return b;
}

void TestIsPointCloud()
{
  MRGI_TEST_CHECK(!vtkMRGIPointCloud::IsPointCloud(nullptr));
  vtkNew<vtkPolyData> empty;
  MRGI_TEST_CHECK(!vtkMRGIPointCloud::IsPointCloud(empty));
  MRGI_TEST_CHECK(vtkMRGIPointCloud::IsPointCloud(Cloud(5, 0, false)));
  MRGI_TEST_CHECK(vtkMRGIPointCloud::IsPointCloud(Cloud(5, 0, true)));
  vtkNew<vtkSphereSource> sphere;
  sphere->Update();
  MRGI_TEST_CHECK(!vtkMRGIPointCloud::IsPointCloud(sphere->GetOutput()));
  // Vertices and one line: not a cloud.
  auto mixed = Cloud(5, 0, true);
  vtkNew<vtkCellArray> lines;
  const vtkIdType line[2] = { 0, 1 };
  lines->InsertNextCell(2, line);
  mixed->SetLines(lines);
  MRGI_TEST_CHECK(!vtkMRGIPointCloud::IsPointCloud(mixed));
  vtkNew<vtkUnstructuredGrid> grid;
  MRGI_TEST_CHECK(!vtkMRGIPointCloud::IsPointCloud(grid));
}

void TestNewFiniteCloud()
{
  MRGI_TEST_CHECK(vtkMRGIPointCloud::NewFiniteCloud(nullptr) == nullptr);
  vtkNew<vtkSphereSource> sphere;
  sphere->Update();
  MRGI_TEST_CHECK(vtkMRGIPointCloud::NewFiniteCloud(sphere->GetOutput()) == nullptr);

  // 1000 points, every 7th NaN, no cells: the 857 finite ones with their values.
  auto cloud = Cloud(1000, 7, false);
  cloud->GetFieldData()->AddArray(cloud->GetPointData()->GetArray("Value"));
  MRGI_TEST_CHECK(vtkMRGIPointCloud::CountFinitePoints(cloud) == 1000 - 143);
  vtkSmartPointer<vtkPolyData> finite;
  finite.TakeReference(vtkMRGIPointCloud::NewFiniteCloud(cloud));
  MRGI_TEST_CHECK(finite && finite->GetNumberOfPoints() == 857);
  MRGI_TEST_CHECK(finite->GetNumberOfVerts() == 857 && finite->GetNumberOfCells() == 857);
  MRGI_TEST_CHECK(finite->GetFieldData()->GetArray("Value") != nullptr);
  vtkDataArray* value = finite->GetPointData()->GetArray("Value");
  MRGI_TEST_CHECK(value && value->GetNumberOfTuples() == 857);
  vtkIdType k = 0;
  for (vtkIdType i = 0; i < 1000; ++i)
  {
    if (i % 7 == 0)
    {
      continue;
    }
    double p[3];
    finite->GetPoint(k, p);
    MRGI_TEST_CHECK(p[0] == double(i % 10) && p[2] == double(i / 100));
    MRGI_TEST_CHECK(value->GetTuple1(k) == double(i));
    ++k;
  }

  // Already drawable: the arrays are shared.
  auto drawable = Cloud(50, 0, true);
  vtkSmartPointer<vtkPolyData> same;
  same.TakeReference(vtkMRGIPointCloud::NewFiniteCloud(drawable));
  MRGI_TEST_CHECK(same->GetPoints()->GetData() == drawable->GetPoints()->GetData());
  MRGI_TEST_CHECK(same->GetNumberOfVerts() == 50);

  // All NaN: an empty result.
  auto nan = Cloud(20, 1, true);
  vtkSmartPointer<vtkPolyData> none;
  none.TakeReference(vtkMRGIPointCloud::NewFiniteCloud(nan));
  MRGI_TEST_CHECK(none && none->GetNumberOfPoints() == 0);
}

void WritePLY(const std::string& path, vtkPolyData* cloud)
{
  vtkNew<vtkPLYWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(cloud);
  writer->SetFileTypeToBinary();
  MRGI_TEST_CHECK(writer->Write() == 1);
}

void WriteLegacy(const std::string& path, vtkPolyData* cloud)
{
  vtkNew<vtkPolyDataWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(cloud);
  writer->SetFileTypeToBinary();
  MRGI_TEST_CHECK(writer->Write() == 1);
}

void TestBuilderFiles()
{
  // Vertex-only PLY (no faces): the point-cloud path, every point.
  const std::string ply = mrgitest::TempPath("clouds_vertices.ply");
  WritePLY(ply, Cloud(300, 0, true));
  Built b = Build(ply);
  MRGI_TEST_CHECK(b.Ok && b.Points == 300 && b.Actors == 1);
  // Some NaN points (every 10th): left out.
  const std::string somePly = mrgitest::TempPath("clouds_some_nan.ply");
  WritePLY(somePly, Cloud(300, 10, true));
  b = Build(somePly);
  MRGI_TEST_CHECK(b.Ok && b.Points == 270);
  // All NaN: PLY, binary legacy VTK and XML all say so.
  const std::string nanPly = mrgitest::TempPath("clouds_all_nan.ply");
  WritePLY(nanPly, Cloud(64, 1, true));
  b = Build(nanPly);
  MRGI_TEST_CHECK(
    !b.Ok && b.Error.find("none of its 64 points has finite coordinates") != std::string::npos);
  const std::string nanVtk = mrgitest::TempPath("clouds_all_nan.vtk");
  WriteLegacy(nanVtk, Cloud(64, 1, true));
  b = Build(nanVtk);
  MRGI_TEST_CHECK(
    !b.Ok && b.Error.find("none of its 64 points has finite coordinates") != std::string::npos);
  const std::string nanVtp = mrgitest::TempPath("clouds_all_nan.vtp");
  {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetFileName(nanVtp.c_str());
    writer->SetInputData(Cloud(64, 1, false));
    MRGI_TEST_CHECK(writer->Write() == 1);
  }
  b = Build(nanVtp);
  MRGI_TEST_CHECK(!b.Ok && b.Error.find("finite") != std::string::npos);
  // One point, legacy VTK.
  const std::string oneVtk = mrgitest::TempPath("clouds_one.vtk");
  WriteLegacy(oneVtk, Cloud(1, 0, true));
  b = Build(oneVtk);
  MRGI_TEST_CHECK(b.Ok && b.Points == 1);
  // A lone point has no spacing to estimate a splat radius from; it still
  // draws (one surfel), as do duplicated points.
  MRGI_TEST_CHECK(b.Surfels == 1);
  const std::string twice = mrgitest::TempPath("clouds_duplicates.vtk");
  {
    auto cloud = Cloud(100, 0, false);
    vtkNew<vtkPoints> doubled;
    for (int copy = 0; copy < 2; ++copy)
    {
      for (vtkIdType i = 0; i < 100; ++i)
      {
        doubled->InsertNextPoint(cloud->GetPoint(i));
      }
    }
    vtkNew<vtkPolyData> both;
    both->SetPoints(doubled);
    WriteLegacy(twice, both);
  }
  b = Build(twice);
  MRGI_TEST_CHECK(b.Ok && b.Points == 200 && b.Surfels == 200);
  // An unstructured grid of vertex cells: its surface is a cloud.
  const std::string vtu = mrgitest::TempPath("clouds_vertices.vtu");
  {
    auto cloud = Cloud(100, 0, false);
    vtkNew<vtkUnstructuredGrid> grid;
    grid->SetPoints(cloud->GetPoints());
    for (vtkIdType i = 0; i < 100; ++i)
    {
      grid->InsertNextCell(VTK_VERTEX, 1, &i);
    }
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetFileName(vtu.c_str());
    writer->SetInputData(grid);
    MRGI_TEST_CHECK(writer->Write() == 1);
  }
  b = Build(vtu);
  MRGI_TEST_CHECK(b.Ok && b.Points == 100);
  // The same grid with every 10th point NaN: the NaN points are left out,
  // as for every other reader (not "point 0 is not finite").
  const std::string nanVtu = mrgitest::TempPath("clouds_some_nan.vtu");
  {
    auto cloud = Cloud(100, 10, false);
    vtkNew<vtkUnstructuredGrid> grid;
    grid->SetPoints(cloud->GetPoints());
    for (vtkIdType i = 0; i < 100; ++i)
    {
      grid->InsertNextCell(VTK_VERTEX, 1, &i);
    }
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetFileName(nanVtu.c_str());
    writer->SetInputData(grid);
    MRGI_TEST_CHECK(writer->Write() == 1);
  }
  b = Build(nanVtu);
  MRGI_TEST_CHECK(b.Ok && b.Points == 90);
  // A mesh is not a cloud.
  const std::string mesh = mrgitest::TempPath("clouds_mesh.ply");
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->Update();
    WritePLY(mesh, sphere->GetOutput());
  }
  b = Build(mesh);
  MRGI_TEST_CHECK(b.Ok && b.Points == 0);

  // LAS: read, every point; LAZ and PCD refused with their messages.
  mrgitest::LASFile f;
  f.Minor = 4;
  f.Format = 6;
  f.Offset[0] = 500000;
  f.Offset[1] = 5400000;
  std::vector<mrgitest::LASPoint> points(500);
  for (size_t i = 0; i < points.size(); ++i)
  {
    points[i].X = 512000 + 0.05 * double(i % 25);
    points[i].Y = 5432000 + 0.05 * double(i / 25);
    points[i].Z = 300;
    points[i].Classification = static_cast<uint8_t>(i % 2 ? 2 : 5);
  }
  const std::string las = mrgitest::TempPath("clouds_tile.las");
  mrgitest::WriteBytes(las, mrgitest::LASBytes(f, points));
  b = Build(las);
  MRGI_TEST_CHECK(b.Ok && b.Points == 500);
  std::vector<unsigned char> laz = mrgitest::LASBytes(f, points);
  laz[104] |= 0x80;
  const std::string lazPath = mrgitest::TempPath("clouds_tile.laz");
  mrgitest::WriteBytes(lazPath, laz);
  b = Build(lazPath);
  MRGI_TEST_CHECK(!b.Ok && b.Error.find("compressed LAZ is not supported") != std::string::npos);
  const std::string truncated = mrgitest::TempPath("clouds_truncated.las");
  std::vector<unsigned char> cut = mrgitest::LASBytes(f, points);
  cut.resize(cut.size() / 2);
  mrgitest::WriteBytes(truncated, cut);
  b = Build(truncated);
  MRGI_TEST_CHECK(!b.Ok && b.Error.find("truncated") != std::string::npos);
  const std::string pcd = mrgitest::TempPath("clouds_cloud.pcd");
  mrgitest::WriteBytes(pcd, { 'x' });
  b = Build(pcd);
  // Without MRGI's PCL module: its message; with it, PCL's verdict on a bad file.
  MRGI_TEST_CHECK(!b.Ok);
  const std::string unknown = mrgitest::TempPath("clouds_cloud.xyz");
  mrgitest::WriteBytes(unknown, { 'x' });
  b = Build(unknown);
  MRGI_TEST_CHECK(!b.Ok && b.Error.find(".las") != std::string::npos &&
    b.Error.find(".pcd") != std::string::npos);
}

// A classified LAS tile (ground brown, vegetation green) seen from above
// with MRGI's pass: the image shows the class colours and no NaN.
void TestRenderLAS()
{
  mrgitest::LASFile f;
  f.Minor = 4;
  f.Format = 6;
  f.Offset[0] = 500000;
  f.Offset[1] = 5400000;
  std::vector<mrgitest::LASPoint> points;
  for (int j = 0; j < 80; ++j)
  {
    for (int i = 0; i < 80; ++i)
    {
      mrgitest::LASPoint p;
      p.X = 512000 + 0.25 * i;
      p.Y = 5432000 + 0.25 * j;
      p.Z = 300 + (i >= 40 ? 2.0 : 0.0);
      p.Classification = static_cast<uint8_t>(i >= 40 ? 5 : 2); // right half trees
      points.push_back(p);
    }
  }
  const std::string las = mrgitest::TempPath("clouds_render.las");
  mrgitest::WriteBytes(las, mrgitest::LASBytes(f, points));
  auto window = mrgitest::HeadlessWindow(160, 120);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene(las.c_str());
  MRGI_TEST_CHECK(builder->Build(renderer));
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> gi;
  gi->SetDelegatePass(steps);
  renderer->SetPass(gi);
  // Straight down (the tile is flat in x-y), x to the right.
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, 0, 50);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCamera();
  window->Render();
  auto image = mrgitest::GrabRGB(window);
  double left[3], right[3];
  mrgitest::MeanColor(image, 40, 50, 70, 70, left);
  mrgitest::MeanColor(image, 90, 50, 120, 70, right);
  std::printf("left (ground) %.0f %.0f %.0f, right (high vegetation) %.0f %.0f %.0f\n", left[0],
    left[1], left[2], right[0], right[1], right[2]);
  MRGI_TEST_CHECK(left[0] > 20 && left[0] > left[2]);    // brown, lit
  MRGI_TEST_CHECK(right[1] > 10 && right[1] > right[0]); // green, lit
  vtkNew<vtkFloatArray> rgba;
  window->GetRGBAPixelData(0, 0, 159, 119, 0, rgba);
  for (vtkIdType i = 0; i < rgba->GetNumberOfValues(); ++i)
  {
    MRGI_TEST_CHECK(std::isfinite(rgba->GetValue(i)));
  }
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestIsPointCloud), MRGI_TEST_CASE(TestNewFiniteCloud),
      MRGI_TEST_CASE(TestBuilderFiles), MRGI_TEST_CASE(TestRenderLAS) });
}
