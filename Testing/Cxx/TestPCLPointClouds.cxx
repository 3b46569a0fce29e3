// MRGI::RenderingPCL (VTK 9.1 build): the factory overrides are active;
// PCD files written here by PCL (ascii, binary, binary_compressed; rgb,
// normals, curvature, intensity; an organized cloud with NaN holes and a
// viewpoint) read back exactly, 10^7 points too; bad files (empty, no FIELDS, truncated
// binary and binary_compressed bodies, huge declared sizes, all NaN) are
// errors naming the file, with an empty output; the shared PCDs
// (../shared/data, when present) read with the MANIFEST's counts; PCL's
// normals agree with the core's on a sampled surface, and integral-image
// normals of an organized view of a plane are right and face the sensor.
// `TestPCLPointClouds --bench N` times core and PCL normals on N points of a
// torus, `--bench-pcd FILE` the reading of FILE and both normals on it.
#include "mrgiTestUtilities.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkMRGIPCDReader.h"
#include "vtkMRGIPCLPCDReader.h"
#include "vtkMRGIPCLPointCloudNormals.h"
#include "vtkMRGIPointCloudNormals.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTimerLog.h"

#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace
{
const double Pi = 3.14159265358979323846;

/** vtkMRGIPointCloudNormals itself (the core), whatever the factory says. */
class CoreNormals : public vtkMRGIPointCloudNormals
{
public:
  static CoreNormals* New();
  vtkTypeMacro(CoreNormals, vtkMRGIPointCloudNormals);
};
vtkStandardNewMacro(CoreNormals);

/** Reads `path` with the factory's reader; errors go to `errors`. */
vtkSmartPointer<vtkMRGIPCDReader> Read(const std::string& path, mrgitest::ErrorCatcher* errors)
{
  vtkSmartPointer<vtkMRGIPCDReader> reader =
    vtkSmartPointer<vtkMRGIPCDReader>::Take(vtkMRGIPCDReader::New());
  if (errors)
  {
    reader->AddObserver(vtkCommand::ErrorEvent, errors);
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader;
}

void TestOverridesActive()
{
  vtkSmartPointer<vtkMRGIPCDReader> reader =
    vtkSmartPointer<vtkMRGIPCDReader>::Take(vtkMRGIPCDReader::New());
  MRGI_TEST_CHECK(vtkMRGIPCLPCDReader::SafeDownCast(reader) != nullptr);
  vtkSmartPointer<vtkMRGIPointCloudNormals> normals =
    vtkSmartPointer<vtkMRGIPointCloudNormals>::Take(vtkMRGIPointCloudNormals::New());
  MRGI_TEST_CHECK(vtkMRGIPCLPointCloudNormals::SafeDownCast(normals) != nullptr);
}

/** The three encodings of one cloud with rgb, normals and curvature. */
void TestRoundTrip()
{
  pcl::PointCloud<pcl::PointXYZRGBNormal> cloud;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  for (int i = 0; i < 500; ++i)
  {
    pcl::PointXYZRGBNormal p;
    p.x = u(rng);
    p.y = u(rng);
    p.z = u(rng);
    p.r = static_cast<std::uint8_t>(i % 256);
    p.g = static_cast<std::uint8_t>((3 * i) % 256);
    p.b = static_cast<std::uint8_t>((7 * i) % 256);
    const float l = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z) + 1e-3f;
    p.normal_x = p.x / l;
    p.normal_y = p.y / l;
    p.normal_z = p.z / l;
    p.curvature = 0.001f * static_cast<float>(i);
    cloud.push_back(p);
  }
  cloud.sensor_origin_ = Eigen::Vector4f(1.0f, 2.0f, 3.0f, 0.0f);
  cloud.sensor_orientation_ = Eigen::Quaternionf(0.5f, 0.5f, -0.5f, 0.5f);
  const char* kinds[3] = { "ascii", "binary", "binary_compressed" };
  for (int kind = 0; kind < 3; ++kind)
  {
    const std::string path =
      mrgitest::TempPath(std::string("pcl_roundtrip_") + kinds[kind] + ".pcd");
    pcl::PCDWriter writer;
    const int rc = kind == 0 ? writer.writeASCII(path, cloud, 8)
      : kind == 1            ? writer.writeBinary(path, cloud)
                             : writer.writeBinaryCompressed(path, cloud);
    MRGI_TEST_CHECK(rc == 0);
    vtkNew<mrgitest::ErrorCatcher> errors;
    auto reader = Read(path, errors);
    MRGI_TEST_CHECK(errors->Count == 0);
    vtkPolyData* out = reader->GetOutput();
    MRGI_TEST_CHECK(out->GetNumberOfPoints() == 500);
    MRGI_TEST_CHECK(out->GetNumberOfVerts() == 500);
    vtkDataArray* rgb = out->GetPointData()->GetScalars();
    vtkDataArray* normals = out->GetPointData()->GetNormals();
    vtkDataArray* curvature = out->GetPointData()->GetArray("Curvature");
    MRGI_TEST_CHECK(
      rgb && std::strcmp(rgb->GetName(), "RGB") == 0 && rgb->GetNumberOfComponents() == 3);
    MRGI_TEST_CHECK(rgb->GetDataType() == VTK_UNSIGNED_CHAR);
    MRGI_TEST_CHECK(normals && curvature);
    for (vtkIdType i = 0; i < 500; ++i)
    {
      const auto& p = cloud[static_cast<std::size_t>(i)];
      double x[3];
      out->GetPoint(i, x);
      const double tol = kind == 0 ? 1e-5 : 0.0;
      MRGI_TEST_CHECK(std::fabs(x[0] - p.x) <= tol * 10 && std::fabs(x[1] - p.y) <= tol * 10 &&
        std::fabs(x[2] - p.z) <= tol * 10);
      MRGI_TEST_CHECK(rgb->GetComponent(i, 0) == p.r && rgb->GetComponent(i, 1) == p.g &&
        rgb->GetComponent(i, 2) == p.b);
      MRGI_TEST_CHECK(std::fabs(normals->GetComponent(i, 2) - p.normal_z) <= tol + 1e-7);
      MRGI_TEST_CHECK(std::fabs(curvature->GetComponent(i, 0) - p.curvature) <= tol + 1e-7);
    }
    vtkDataArray* origin = out->GetFieldData()->GetArray("SensorOrigin");
    vtkDataArray* orientation = out->GetFieldData()->GetArray("SensorOrientation");
    MRGI_TEST_CHECK(origin && origin->GetNumberOfComponents() == 3);
    MRGI_TEST_CHECK(origin->GetComponent(0, 0) == 1.0 && origin->GetComponent(0, 2) == 3.0);
    MRGI_TEST_CHECK(orientation && orientation->GetNumberOfComponents() == 4);
    MRGI_TEST_CHECK(
      orientation->GetComponent(0, 0) == 0.5 && orientation->GetComponent(0, 2) == -0.5);
    MRGI_TEST_CHECK(out->GetFieldData()->GetArray("OrganizedDimensions") == nullptr);
  }
  // Intensity (PointXYZI), binary.
  pcl::PointCloud<pcl::PointXYZI> xyzi;
  for (int i = 0; i < 10; ++i)
  {
    pcl::PointXYZI p;
    p.x = static_cast<float>(i);
    p.y = p.z = 0.0f;
    p.intensity = 100.0f + static_cast<float>(i);
    xyzi.push_back(p);
  }
  const std::string path = mrgitest::TempPath("pcl_intensity.pcd");
  MRGI_TEST_CHECK(pcl::io::savePCDFileBinary(path, xyzi) == 0);
  auto reader = Read(path, nullptr);
  vtkDataArray* intensity = reader->GetOutput()->GetPointData()->GetArray("Intensity");
  MRGI_TEST_CHECK(intensity && intensity->GetNumberOfTuples() == 10);
  MRGI_TEST_CHECK(intensity->GetComponent(9, 0) == 109.0);
  MRGI_TEST_CHECK(reader->GetOutput()->GetPointData()->GetScalars() == nullptr);
}

/** A 64 x 48 pinhole view of the plane z = 2 - 0.5 x, with NaN holes. */
pcl::PointCloud<pcl::PointXYZRGBA> OrganizedPlane(int* finite)
{
  pcl::PointCloud<pcl::PointXYZRGBA> cloud(64, 48);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  *finite = 0;
  for (int v = 0; v < 48; ++v)
  {
    for (int u = 0; u < 64; ++u)
    {
      pcl::PointXYZRGBA& p = cloud.at(u, v);
      p.rgba = 0xFF102030u;
      if ((u * 7 + v * 3) % 11 == 0 || (u > 20 && u < 30 && v > 10 && v < 20))
      {
        p.x = p.y = p.z = nan;
        continue;
      }
      // Ray (a, b, 1) from the origin hits z = 2 - 0.5 x at t = 2 / (1 + 0.5 a).
      const float a = (static_cast<float>(u) - 32.0f) / 60.0f,
                  b = (static_cast<float>(v) - 24.0f) / 60.0f;
      const float t = 2.0f / (1.0f + 0.5f * a);
      p.x = a * t;
      p.y = b * t;
      p.z = t;
      ++*finite;
    }
  }
  cloud.is_dense = false;
  cloud.sensor_origin_ = Eigen::Vector4f(0.0f, 0.0f, 0.0f, 0.0f);
  return cloud;
}

/** Organized clouds too small for integral images (PCL crashed on them) use kNN. */
void TestSmallOrganized()
{
  for (const int side : { 1, 2, 3, 5, 9, 39 })
  {
    for (const int other : { 3, 48 })
    {
      pcl::PointCloud<pcl::PointXYZ> cloud(
        static_cast<std::uint32_t>(side), static_cast<std::uint32_t>(other));
      for (int v = 0; v < other; ++v)
      {
        for (int u = 0; u < side; ++u)
        {
          cloud.at(u, v) =
            pcl::PointXYZ(0.01f * static_cast<float>(u), 0.01f * static_cast<float>(v), 1.0f);
        }
      }
      const std::string path = mrgitest::TempPath("pcl_small_organized.pcd");
      MRGI_TEST_CHECK(pcl::io::savePCDFileBinary(path, cloud) == 0);
      auto reader = Read(path, nullptr);
      vtkSmartPointer<vtkMRGIPointCloudNormals> filter =
        vtkSmartPointer<vtkMRGIPointCloudNormals>::Take(vtkMRGIPointCloudNormals::New());
      filter->SetInputConnection(reader->GetOutputPort());
      filter->Update();
      auto* pclFilter = vtkMRGIPCLPointCloudNormals::SafeDownCast(filter);
      MRGI_TEST_CHECK(pclFilter && !pclFilter->GetUsedIntegralImage());
      vtkDataArray* normals = filter->GetOutput()->GetPointData()->GetNormals();
      MRGI_TEST_CHECK(normals && normals->GetNumberOfTuples() == side * other);
      if (side > 1)
      {
        // A plane seen from the origin: -z.
        MRGI_TEST_CHECK(normals->GetComponent(0, 2) < -0.999);
      }
    }
  }
}

void TestOrganized()
{
  int finite = 0;
  auto cloud = OrganizedPlane(&finite);
  const std::string path = mrgitest::TempPath("pcl_organized.pcd");
  MRGI_TEST_CHECK(pcl::io::savePCDFileBinaryCompressed(path, cloud) == 0);
  vtkNew<mrgitest::ErrorCatcher> errors;
  auto reader = Read(path, errors);
  MRGI_TEST_CHECK(errors->Count == 0);
  vtkPolyData* out = reader->GetOutput();
  MRGI_TEST_CHECK(out->GetNumberOfPoints() == finite);
  auto* pcl = vtkMRGIPCLPCDReader::SafeDownCast(reader);
  MRGI_TEST_CHECK(pcl->GetNumberOfPointsInFile() == 64 * 48);
  MRGI_TEST_CHECK(pcl->GetNumberOfDroppedPoints() == 64 * 48 - finite);
  vtkDataArray* dims = out->GetFieldData()->GetArray("OrganizedDimensions");
  vtkDataArray* pixels = out->GetPointData()->GetArray("PixelIndex");
  MRGI_TEST_CHECK(dims && dims->GetComponent(0, 0) == 64 && dims->GetComponent(1, 0) == 48);
  MRGI_TEST_CHECK(pixels && pixels->GetNumberOfTuples() == finite);
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    const auto pixel = static_cast<std::size_t>(pixels->GetComponent(i, 0));
    double x[3];
    out->GetPoint(i, x);
    MRGI_TEST_CHECK(x[0] == cloud[pixel].x && x[2] == cloud[pixel].z);
  }
  vtkDataArray* rgb = out->GetPointData()->GetScalars();
  MRGI_TEST_CHECK(rgb && rgb->GetComponent(0, 0) == 0x10 && rgb->GetComponent(0, 2) == 0x30);

  // Integral-image normals: the plane's normal (0.5, 0, 1)/|.| facing the
  // sensor at the origin, i.e. (-0.447, 0, -0.894).
  vtkSmartPointer<vtkMRGIPointCloudNormals> filter =
    vtkSmartPointer<vtkMRGIPointCloudNormals>::Take(vtkMRGIPointCloudNormals::New());
  filter->SetInputConnection(reader->GetOutputPort());
  filter->Update();
  auto* pclNormals = vtkMRGIPCLPointCloudNormals::SafeDownCast(filter);
  MRGI_TEST_CHECK(pclNormals && pclNormals->GetUsedIntegralImage());
  MRGI_TEST_CHECK(filter->GetLastOrientation() == vtkMRGIPointCloudNormals::ORIENT_VIEWPOINT);
  vtkDataArray* normals = filter->GetOutput()->GetPointData()->GetNormals();
  const double truth[3] = { -0.5 / std::sqrt(1.25), 0.0, -1.0 / std::sqrt(1.25) };
  double worst = 0.0;
  for (vtkIdType i = 0; i < filter->GetOutput()->GetNumberOfPoints(); ++i)
  {
    double n[3];
    normals->GetTuple(i, n);
    const double d = std::min(1.0, n[0] * truth[0] + n[1] * truth[1] + n[2] * truth[2]);
    worst = std::max(worst, std::acos(d) * 180.0 / Pi);
  }
  std::printf("organized plane: worst normal error %.3f degrees\n", worst);
  MRGI_TEST_CHECK(worst < 3.0);
  vtkDataArray* radius = filter->GetOutput()->GetPointData()->GetArray("Radius");
  MRGI_TEST_CHECK(radius && radius->GetRange()[0] > 0.0);
}

/** Writes `text` (size bytes) to a file named `name` in the temp directory. */
std::string WriteFile(const std::string& name, const std::string& text)
{
  const std::string path = mrgitest::TempPath(name);
  std::ofstream out(path, std::ios::binary);
  out << text;
  return path;
}

void TestBadFiles()
{
  const std::string header = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";
  struct Bad
  {
    const char* name;
    std::string text;
    const char* fragment;
  };
  // A valid binary and binary_compressed file, cut short.
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (int i = 0; i < 1000; ++i)
  {
    cloud.push_back(pcl::PointXYZ(static_cast<float>(i), static_cast<float>(i % 7), 1.0f));
  }
  const std::string bin = mrgitest::TempPath("pcl_bad_full_binary.pcd");
  const std::string comp = mrgitest::TempPath("pcl_bad_full_compressed.pcd");
  MRGI_TEST_CHECK(pcl::io::savePCDFileBinary(bin, cloud) == 0);
  MRGI_TEST_CHECK(pcl::io::savePCDFileBinaryCompressed(comp, cloud) == 0);
  auto slurp = [](const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  const std::string binText = slurp(bin), compText = slurp(comp);
  std::string compCorrupt = compText;
  for (std::size_t i = compCorrupt.size() - 40; i < compCorrupt.size(); ++i)
  {
    compCorrupt[i] = static_cast<char>(0xFF);
  }
  const std::vector<Bad> cases = {
    { "pcl_bad_empty.pcd", "", "empty" },
    { "pcl_bad_nofields.pcd", "VERSION 0.7\nWIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA ascii\n0 0 0\n",
      "FIELDS" },
    { "pcl_bad_noise.pcd", std::string("\x89\x01\xff\xfe garbage\n\x02\x03", 16), "not a PCD" },
    { "pcl_bad_truncated_binary.pcd", binText.substr(0, binText.size() - 100), "truncated" },
    { "pcl_bad_truncated_compressed.pcd", compText.substr(0, compText.size() - 50), "truncated" },
    { "pcl_bad_corrupt_compressed.pcd", compCorrupt, "PCL" },
    { "pcl_bad_huge.pcd",
      header + "WIDTH 2000000000\nHEIGHT 1\nPOINTS 2000000000\nDATA binary\n" +
        std::string(64, '\0'),
      "more than" },
    { "pcl_bad_huge_lzf.pcd",
      header + "WIDTH 1000\nHEIGHT 1\nPOINTS 1000\nDATA binary_compressed\n" +
        std::string("\x0a\x00\x00\x00\xf0\xff\xff\xff", 8) + std::string(10, '\0'),
      "uncompressed" },
    { "pcl_bad_ascii.pcd", header + "WIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA ascii\n1 2 3\n4 5\n6 7 8\n",
      "has 2 values" },
    { "pcl_bad_all_nan.pcd",
      header +
        "WIDTH 2\nHEIGHT 2\nPOINTS 4\nDATA ascii\nnan nan nan\nnan 0 0\n0 nan 0\nnan nan nan\n",
      "none of its 4 points is finite" },
  };
  for (const auto& c : cases)
  {
    const std::string path = WriteFile(c.name, c.text);
    vtkNew<mrgitest::ErrorCatcher> errors;
    auto reader = Read(path, errors);
    std::printf("%s: %s\n", c.name, errors->Last.c_str());
    MRGI_TEST_CHECK(errors->Last.find(path) != std::string::npos);
    MRGI_TEST_CHECK(errors->Caught(c.fragment));
    MRGI_TEST_CHECK(reader->GetOutput()->GetNumberOfPoints() == 0);
  }
  // No file, a directory, no file name.
  for (const char* path : { "/nonexistent/cloud.pcd", "/" })
  {
    vtkNew<mrgitest::ErrorCatcher> errors;
    auto reader = Read(path, errors);
    MRGI_TEST_CHECK(errors->Caught(path));
  }
  vtkNew<mrgitest::ErrorCatcher> errors;
  auto reader = Read("", errors);
  MRGI_TEST_CHECK(errors->Caught("no PCD file name"));
}

/** 10^7 points (issue 15's size): read exactly, then the file is removed. */
void TestTenMillionPoints()
{
  const std::string path = mrgitest::TempPath("pcl_1e7.pcd");
  {
    pcl::PointCloud<pcl::PointXYZ> cloud;
    cloud.resize(10000000);
    for (std::size_t i = 0; i < cloud.size(); ++i)
    {
      cloud[i] = pcl::PointXYZ(
        static_cast<float>(i % 3163), static_cast<float>(i / 3163), static_cast<float>(i % 7));
    }
    MRGI_TEST_CHECK(pcl::io::savePCDFileBinary(path, cloud) == 0);
  }
  vtkNew<mrgitest::ErrorCatcher> errors;
  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  auto reader = Read(path, errors);
  timer->StopTimer();
  std::remove(path.c_str());
  std::printf("10^7 points: read in %.3f s\n", timer->GetElapsedTime());
  MRGI_TEST_CHECK(errors->Count == 0);
  vtkPolyData* out = reader->GetOutput();
  MRGI_TEST_CHECK(out->GetNumberOfPoints() == 10000000);
  MRGI_TEST_CHECK(out->GetNumberOfVerts() == 10000000);
  for (const vtkIdType i : { vtkIdType(0), vtkIdType(1234567), vtkIdType(9999999) })
  {
    double p[3];
    out->GetPoint(i, p);
    MRGI_TEST_CHECK(p[0] == static_cast<double>(i % 3163) &&
      p[1] == static_cast<double>(i / 3163) && p[2] == static_cast<double>(i % 7));
  }
}

void TestSharedData()
{
  const char* dir = std::getenv("MRGI_SHARED_DATA_DIR");
  const std::string base = dir && dir[0] ? dir : "";
  const std::string bunny = base + "/bunny.pcd", milk = base + "/milk_cartoon_all_small_clorox.pcd";
  if (base.empty() || !std::ifstream(bunny) || !std::ifstream(milk))
  {
    std::printf("shared PCDs not found under '%s': skipped\n", base.c_str());
    return;
  }
  vtkNew<mrgitest::ErrorCatcher> errors;
  auto reader = Read(bunny, errors);
  MRGI_TEST_CHECK(errors->Count == 0);
  MRGI_TEST_CHECK(reader->GetOutput()->GetNumberOfPoints() == 397);
  MRGI_TEST_CHECK(reader->GetOutput()->GetNumberOfVerts() == 397);
  {
    // PCD v.5, no VIEWPOINT: PCL's default pose, unorganized: outward
    // normals (towards the origin, under the bunny, 318 of 397 faced in).
    vtkSmartPointer<vtkMRGIPointCloudNormals> normals =
      vtkSmartPointer<vtkMRGIPointCloudNormals>::Take(vtkMRGIPointCloudNormals::New());
    normals->SetInputConnection(reader->GetOutputPort());
    normals->Update();
    MRGI_TEST_CHECK(normals->GetLastOrientation() == vtkMRGIPointCloudNormals::ORIENT_OUTWARD);
  }
  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  reader = Read(milk, errors);
  timer->StopTimer();
  MRGI_TEST_CHECK(errors->Count == 0);
  auto* pcl = vtkMRGIPCLPCDReader::SafeDownCast(reader);
  MRGI_TEST_CHECK(pcl->GetNumberOfPointsInFile() == 307200);
  MRGI_TEST_CHECK(reader->GetOutput()->GetNumberOfPoints() == 241407);
  MRGI_TEST_CHECK(reader->GetOutput()->GetPointData()->GetScalars() != nullptr);
  double bounds[6];
  reader->GetOutput()->GetBounds(bounds);
  MRGI_TEST_CHECK(bounds[0] > -1.07 && bounds[1] < 1.16 && bounds[4] > 0.49 && bounds[5] < 2.07);
  std::printf("milk_cartoon: read in %.3f s\n", timer->GetElapsedTime());
  vtkSmartPointer<vtkMRGIPointCloudNormals> filter =
    vtkSmartPointer<vtkMRGIPointCloudNormals>::Take(vtkMRGIPointCloudNormals::New());
  filter->SetInputConnection(reader->GetOutputPort());
  timer->StartTimer();
  filter->Update();
  timer->StopTimer();
  std::printf("milk_cartoon: PCL normals (integral image) in %.3f s, %lld degenerate\n",
    timer->GetElapsedTime(), static_cast<long long>(filter->GetNumberOfDegeneratePoints()));
  MRGI_TEST_CHECK(vtkMRGIPCLPointCloudNormals::SafeDownCast(filter)->GetUsedIntegralImage());
  MRGI_TEST_CHECK(filter->GetLastOrientation() == vtkMRGIPointCloudNormals::ORIENT_VIEWPOINT);
  vtkDataArray* normals = filter->GetOutput()->GetPointData()->GetNormals();
  MRGI_TEST_CHECK(normals && normals->GetNumberOfTuples() == 241407);
  // Facing the sensor at the origin, all finite.
  vtkIdType facing = 0;
  for (vtkIdType i = 0; i < normals->GetNumberOfTuples(); ++i)
  {
    double n[3], p[3];
    normals->GetTuple(i, n);
    filter->GetOutput()->GetPoint(i, p);
    MRGI_TEST_CHECK(std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2]));
    facing += (n[0] * p[0] + n[1] * p[1] + n[2] * p[2] <= 0.0) ? 1 : 0;
  }
  MRGI_TEST_CHECK(facing == normals->GetNumberOfTuples());
}

/** n random points on a torus (R 1, r 0.35) and their true normals. */
vtkSmartPointer<vtkPolyData> Torus(int n, std::vector<double>* truth)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 2.0 * Pi), w(0.0, 1.0);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(n);
  truth->resize(3 * static_cast<std::size_t>(n));
  const double R = 1.0, r = 0.35;
  for (int i = 0; i < n;)
  {
    const double a = u(rng), b = u(rng);
    // Area-uniform: accept with probability (R + r cos b) / (R + r).
    if (w(rng) > (R + r * std::cos(b)) / (R + r))
    {
      continue;
    }
    const double nx = std::cos(a) * std::cos(b), ny = std::sin(a) * std::cos(b), nz = std::sin(b);
    points->SetPoint(
      i, (R + r * std::cos(b)) * std::cos(a), (R + r * std::cos(b)) * std::sin(a), r * std::sin(b));
    (*truth)[3 * i] = nx;
    (*truth)[3 * i + 1] = ny;
    (*truth)[3 * i + 2] = nz;
    ++i;
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  return poly;
}

/** Angles (degrees) between two normal arrays, sorted, ignoring sign when `unsigned_`. */
std::vector<double> Angles(vtkDataArray* a, const std::vector<double>& b, bool unsigned_)
{
  std::vector<double> angles;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    double n[3];
    a->GetTuple(i, n);
    double d = n[0] * b[3 * i] + n[1] * b[3 * i + 1] + n[2] * b[3 * i + 2];
    d = unsigned_ ? std::fabs(d) : d;
    angles.push_back(std::acos(std::max(-1.0, std::min(1.0, d))) * 180.0 / Pi);
  }
  std::sort(angles.begin(), angles.end());
  return angles;
}

void TestPCLAgreesWithCore()
{
  std::vector<double> truth;
  auto torus = Torus(30000, &truth);
  vtkNew<CoreNormals> core;
  core->SetInputData(torus);
  core->Update();
  vtkSmartPointer<vtkMRGIPointCloudNormals> pclFilter =
    vtkSmartPointer<vtkMRGIPointCloudNormals>::Take(vtkMRGIPointCloudNormals::New());
  MRGI_TEST_CHECK(vtkMRGIPCLPointCloudNormals::SafeDownCast(pclFilter) != nullptr);
  pclFilter->SetInputData(torus);
  pclFilter->Update();
  MRGI_TEST_CHECK(!vtkMRGIPCLPointCloudNormals::SafeDownCast(pclFilter)->GetUsedIntegralImage());
  vtkDataArray* a = core->GetOutput()->GetPointData()->GetNormals();
  vtkDataArray* b = pclFilter->GetOutput()->GetPointData()->GetNormals();
  std::vector<double> bv(3 * truth.size() / 3);
  for (vtkIdType i = 0; i < b->GetNumberOfTuples(); ++i)
  {
    b->GetTuple(i, &bv[3 * i]);
  }
  const auto between = Angles(a, bv, false);
  const auto coreTruth = Angles(a, truth, true);
  const auto pclTruth = Angles(b, truth, true);
  const std::size_t n = between.size();
  auto mean = [](const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v)
    {
      s += x;
    }
    return s / static_cast<double>(v.size());
  };
  std::printf("torus, 30000 points, k 16: core vs PCL mean %.4f, p95 %.4f, max %.4f deg; "
              "vs truth: core mean %.3f p95 %.3f, PCL mean %.3f p95 %.3f deg\n",
    mean(between), between[n * 95 / 100], between[n - 1], mean(coreTruth), coreTruth[n * 95 / 100],
    mean(pclTruth), pclTruth[n * 95 / 100]);
  MRGI_TEST_CHECK(mean(between) < 0.5);
  MRGI_TEST_CHECK(between[n * 95 / 100] < 1.0);
  MRGI_TEST_CHECK(mean(coreTruth) < 3.0 && mean(pclTruth) < 3.0);
  // Same kNN, same formula: the same radii.
  vtkDataArray* ra = core->GetOutput()->GetPointData()->GetArray("Radius");
  vtkDataArray* rb = pclFilter->GetOutput()->GetPointData()->GetArray("Radius");
  for (vtkIdType i = 0; i < ra->GetNumberOfTuples(); ++i)
  {
    MRGI_TEST_CHECK(
      std::fabs(ra->GetComponent(i, 0) - rb->GetComponent(i, 0)) <= 1e-4 * ra->GetComponent(i, 0));
  }
  // The override caches like the base class.
  int runs = 0;
  vtkNew<vtkCallbackCommand> counter;
  counter->SetClientData(&runs);
  counter->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*) { ++*static_cast<int*>(data); });
  pclFilter->AddObserver(vtkCommand::StartEvent, counter);
  pclFilter->Update();
  MRGI_TEST_CHECK(runs == 0);
  pclFilter->SetRadiusScale(2.0);
  pclFilter->Update();
  MRGI_TEST_CHECK(runs == 1);
}

/** Times reading `path` and both normal estimators on it. */
int BenchFile(const char* path)
{
  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  auto reader = Read(path, nullptr);
  timer->StopTimer();
  const vtkIdType n = reader->GetOutput()->GetNumberOfPoints();
  std::printf(
    "read %s: %lld points in %.3f s\n", path, static_cast<long long>(n), timer->GetElapsedTime());
  if (n == 0)
  {
    return 1;
  }
  vtkNew<CoreNormals> core;
  vtkSmartPointer<vtkMRGIPointCloudNormals> pclFilter =
    vtkSmartPointer<vtkMRGIPointCloudNormals>::Take(vtkMRGIPointCloudNormals::New());
  for (vtkMRGIPointCloudNormals* f :
    { static_cast<vtkMRGIPointCloudNormals*>(core), pclFilter.Get() })
  {
    f->SetInputConnection(reader->GetOutputPort());
    timer->StartTimer();
    f->Update();
    timer->StopTimer();
    std::printf("%s: %.3f s (%.3f s per million), %lld degenerate\n", f->GetClassName(),
      timer->GetElapsedTime(), timer->GetElapsedTime() * 1e6 / static_cast<double>(n),
      static_cast<long long>(f->GetNumberOfDegeneratePoints()));
  }
  return 0;
}

int Bench(vtkIdType n)
{
  std::vector<double> truth;
  auto torus = Torus(static_cast<int>(n), &truth);
  vtkNew<CoreNormals> core;
  vtkSmartPointer<vtkMRGIPointCloudNormals> pclFilter =
    vtkSmartPointer<vtkMRGIPointCloudNormals>::Take(vtkMRGIPointCloudNormals::New());
  vtkNew<vtkTimerLog> timer;
  for (vtkMRGIPointCloudNormals* f :
    { static_cast<vtkMRGIPointCloudNormals*>(core), pclFilter.Get() })
  {
    f->SetInputData(torus);
    timer->StartTimer();
    f->Update();
    timer->StopTimer();
    std::printf("%s: %lld points in %.3f s (%.3f s per million)\n", f->GetClassName(),
      static_cast<long long>(n), timer->GetElapsedTime(), timer->GetElapsedTime() * 1e6 / n);
  }
  // Radii alone (the input has normals).
  vtkNew<vtkPolyData> withNormals;
  withNormals->ShallowCopy(torus);
  withNormals->GetPointData()->SetNormals(core->GetOutput()->GetPointData()->GetNormals());
  for (vtkMRGIPointCloudNormals* f :
    { static_cast<vtkMRGIPointCloudNormals*>(core), pclFilter.Get() })
  {
    f->SetInputData(withNormals);
    timer->StartTimer();
    f->Update();
    timer->StopTimer();
    std::printf(
      "%s, radii only: %.3f s per million\n", f->GetClassName(), timer->GetElapsedTime() * 1e6 / n);
  }
  return 0;
}
}

int main(int argc, char* argv[])
{
  if (argc == 3 && std::strcmp(argv[1], "--bench") == 0)
  {
    return Bench(std::atoll(argv[2]));
  }
  if (argc == 3 && std::strcmp(argv[1], "--bench-pcd") == 0)
  {
    return BenchFile(argv[2]);
  }
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestOverridesActive), MRGI_TEST_CASE(TestRoundTrip),
      MRGI_TEST_CASE(TestSmallOrganized), MRGI_TEST_CASE(TestOrganized),
      MRGI_TEST_CASE(TestBadFiles), MRGI_TEST_CASE(TestTenMillionPoints),
      MRGI_TEST_CASE(TestSharedData), MRGI_TEST_CASE(TestPCLAgreesWithCore) });
}
