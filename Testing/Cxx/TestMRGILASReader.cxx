// vtkMRGILASReader on LAS files written here byte by byte: every array with
// its type and values, the field data, one vertex per point, the display
// colours for each ColorBy, UTM-sized offsets kept to the millimetre after
// recentring, one point, 10^7 points (read time printed, never asserted),
// and bad files (truncated, bad header, LAZ, absurd counts, missing): one
// error naming the file, an empty output, no crash.
#include "mrgiLASTestUtilities.h"
#include "mrgiTestUtilities.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkLookupTable.h"
#include "vtkMRGILASReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include "mrgi_las_colors.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <sys/stat.h>

using mrgitest::LASFile;
using mrgitest::LASPoint;

namespace
{
// Counts the reader's error and warning events (and keeps them off stderr).
struct Events
{
  explicit Events(vtkObject* o)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback([](vtkObject*, unsigned long id, void* self, void* text) {
      auto* e = static_cast<Events*>(self);
      (id == vtkCommand::ErrorEvent ? e->Errors : e->Warnings) += 1;
      e->Last = text ? static_cast<const char*>(text) : "";
    });
    o->AddObserver(vtkCommand::ErrorEvent, this->Callback);
    o->AddObserver(vtkCommand::WarningEvent, this->Callback);
  }
  vtkNew<vtkCallbackCommand> Callback;
  int Errors = 0;
  int Warnings = 0;
  std::string Last;
};

std::vector<LASPoint> ThreePoints()
{
  std::vector<LASPoint> p(3);
  p[0].X = 512345.678;
  p[0].Y = 5432109.876;
  p[0].Z = 312.345;
  p[0].Intensity = 100;
  p[0].Classification = 2;
  p[0].RGB[0] = 65535;
  p[0].RGB[2] = 32768;
  p[1].X = 512346.001;
  p[1].Y = 5432110.002;
  p[1].Z = 313.001;
  p[1].Intensity = 200;
  p[1].ReturnNumber = 2;
  p[1].NumberOfReturns = 2;
  p[1].Classification = 5;
  p[1].RGB[1] = 65535;
  p[2].X = 512399.999;
  p[2].Y = 5432150.5;
  p[2].Z = 290.25;
  p[2].Intensity = 300;
  p[2].Classification = 9;
  p[2].RGB[0] = 1000;
  p[2].RGB[1] = 2000;
  p[2].RGB[2] = 3000;
  return p;
}

LASFile UTMFile(int minor, int format)
{
  LASFile f;
  f.Minor = minor;
  f.Format = format;
  f.Offset[0] = 500000;
  f.Offset[1] = 5400000;
  return f;
}

vtkSmartPointer<vtkMRGILASReader> Read(const std::string& path, int colorBy = 0)
{
  auto reader = vtkSmartPointer<vtkMRGILASReader>::New();
  reader->SetFileName(path.c_str());
  reader->SetColorBy(colorBy);
  reader->Update();
  return reader;
}

void CheckVertices(vtkPolyData* out)
{
  const vtkIdType n = out->GetNumberOfPoints();
  MRGI_TEST_CHECK(out->GetNumberOfVerts() == n && out->GetNumberOfCells() == n);
  vtkCellArray* verts = out->GetVerts();
  MRGI_TEST_CHECK(verts->GetNumberOfConnectivityIds() == n);
  for (vtkIdType c = 0; c < n; c += std::max<vtkIdType>(1, n / 97))
  {
    MRGI_TEST_CHECK(verts->GetCellSize(c) == 1);
    vtkNew<vtkIdList> ids;
    verts->GetCellAtId(c, ids);
    MRGI_TEST_CHECK(ids->GetId(0) == c);
  }
}

void CheckWorld(vtkPolyData* out, vtkIdType i, const LASPoint& expected, double tolerance)
{
  auto* origin = vtkDoubleArray::SafeDownCast(out->GetFieldData()->GetArray("Origin"));
  MRGI_TEST_CHECK(
    origin && origin->GetNumberOfTuples() == 1 && origin->GetNumberOfComponents() == 3);
  double p[3];
  out->GetPoint(i, p);
  const double xyz[3] = { expected.X, expected.Y, expected.Z };
  for (int c = 0; c < 3; ++c)
  {
    MRGI_TEST_CHECK(std::fabs(p[c] + origin->GetComponent(0, c) - xyz[c]) <= tolerance);
  }
}

void TestAttributes()
{
  const std::string path = mrgitest::TempPath("las_reader_attributes.las");
  const std::vector<LASPoint> points = ThreePoints();
  mrgitest::WriteBytes(path, mrgitest::LASBytes(UTMFile(2, 3), points));
  auto reader = Read(path);
  vtkPolyData* out = reader->GetOutput();
  MRGI_TEST_CHECK(reader->GetErrorCode() == vtkErrorCode::NoError);
  MRGI_TEST_CHECK(std::strlen(reader->GetLastErrorMessage()) == 0);
  MRGI_TEST_CHECK(out->GetNumberOfPoints() == 3);
  MRGI_TEST_CHECK(out->GetPoints()->GetDataType() == VTK_FLOAT);
  CheckVertices(out);
  for (vtkIdType i = 0; i < 3; ++i)
  {
    CheckWorld(out, i, points[static_cast<size_t>(i)], 2e-4);
  }
  // The origin is the centre of the points' bounding box.
  double origin[3];
  out->GetFieldData()->GetArray("Origin")->GetTuple(0, origin);
  MRGI_TEST_CHECK(std::fabs(origin[0] - 0.5 * (512345.678 + 512399.999)) < 1e-6);
  MRGI_TEST_CHECK(std::fabs(origin[1] - 0.5 * (5432109.876 + 5432150.5)) < 1e-6);
  auto* version = vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("LASVersion"));
  MRGI_TEST_CHECK(version && version->GetValue(0) == "1.2");
  auto* format = vtkIntArray::SafeDownCast(out->GetFieldData()->GetArray("LASPointFormat"));
  MRGI_TEST_CHECK(format && format->GetValue(0) == 3);

  vtkPointData* pd = out->GetPointData();
  auto* intensity = vtkUnsignedShortArray::SafeDownCast(pd->GetArray("Intensity"));
  auto* classification = vtkUnsignedCharArray::SafeDownCast(pd->GetArray("Classification"));
  auto* returns = vtkUnsignedCharArray::SafeDownCast(pd->GetArray("ReturnNumber"));
  auto* numberOfReturns = vtkUnsignedCharArray::SafeDownCast(pd->GetArray("NumberOfReturns"));
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(pd->GetArray("RGB"));
  MRGI_TEST_CHECK(intensity && classification && returns && numberOfReturns && rgb);
  MRGI_TEST_CHECK(pd->GetArray("Colors") == nullptr);
  MRGI_TEST_CHECK(pd->GetScalars() == rgb && rgb->GetNumberOfComponents() == 3);
  MRGI_TEST_CHECK(reader->GetColorByUsed() == vtkMRGILASReader::COLOR_BY_RGB);
  for (vtkIdType i = 0; i < 3; ++i)
  {
    const LASPoint& p = points[static_cast<size_t>(i)];
    MRGI_TEST_CHECK(intensity->GetValue(i) == p.Intensity);
    MRGI_TEST_CHECK(classification->GetValue(i) == p.Classification);
    MRGI_TEST_CHECK(returns->GetValue(i) == p.ReturnNumber);
    MRGI_TEST_CHECK(numberOfReturns->GetValue(i) == p.NumberOfReturns);
    for (int c = 0; c < 3; ++c)
    {
      // 16-bit in the file: v / 65535 * 255, rounded.
      const long expected = std::lround(p.RGB[c] / 65535.0 * 255.0);
      MRGI_TEST_CHECK(rgb->GetTypedComponent(i, c) == expected);
    }
  }
  MRGI_TEST_CHECK(rgb->GetTypedComponent(0, 0) == 255 && rgb->GetTypedComponent(0, 2) == 128);
}

void TestEightBitRGB()
{
  const std::string path = mrgitest::TempPath("las_reader_8bit.las");
  std::vector<LASPoint> points = ThreePoints();
  for (LASPoint& p : points)
  {
    for (uint16_t& c : p.RGB)
    {
      c = static_cast<uint16_t>(c % 256);
    }
  }
  points[0].RGB[0] = 255;
  points[0].RGB[1] = 7;
  mrgitest::WriteBytes(path, mrgitest::LASBytes(UTMFile(2, 2), points));
  auto reader = Read(path);
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(reader->GetOutput()->GetPointData()->GetScalars());
  MRGI_TEST_CHECK(rgb && std::string(rgb->GetName()) == "RGB");
  for (vtkIdType i = 0; i < 3; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      MRGI_TEST_CHECK(rgb->GetTypedComponent(i, c) == points[static_cast<size_t>(i)].RGB[c]);
    }
  }
}

void TestClassifiedColors()
{
  // LAS 1.4, format 6 (no RGB), classified: the class palette, as Colors.
  const std::string path = mrgitest::TempPath("las_reader_classified.las");
  const std::vector<LASPoint> points = ThreePoints();
  mrgitest::WriteBytes(path, mrgitest::LASBytes(UTMFile(4, 6), points));
  auto reader = Read(path);
  vtkPolyData* out = reader->GetOutput();
  MRGI_TEST_CHECK(out->GetNumberOfPoints() == 3);
  vtkPointData* pd = out->GetPointData();
  MRGI_TEST_CHECK(pd->GetArray("RGB") == nullptr);
  auto* colors = vtkUnsignedCharArray::SafeDownCast(pd->GetScalars());
  MRGI_TEST_CHECK(colors && std::string(colors->GetName()) == "Colors");
  MRGI_TEST_CHECK(reader->GetColorByUsed() == vtkMRGILASReader::COLOR_BY_CLASSIFICATION);
  auto* version = vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("LASVersion"));
  MRGI_TEST_CHECK(version && version->GetValue(0) == "1.4");
  vtkSmartPointer<vtkLookupTable> table;
  table.TakeReference(vtkMRGILASReader::NewClassificationLookupTable());
  for (vtkIdType i = 0; i < 3; ++i)
  {
    uint8_t expected[3];
    mrgi_las_classification_color(points[static_cast<size_t>(i)].Classification, expected);
    double fromTable[3];
    table->GetColor(points[static_cast<size_t>(i)].Classification, fromTable);
    for (int c = 0; c < 3; ++c)
    {
      MRGI_TEST_CHECK(colors->GetTypedComponent(i, c) == expected[c]);
      MRGI_TEST_CHECK(std::lround(fromTable[c] * 255) == expected[c]);
    }
  }
  // Ground is brown, high vegetation green, water blue.
  MRGI_TEST_CHECK(colors->GetTypedComponent(0, 0) > colors->GetTypedComponent(0, 2));
  MRGI_TEST_CHECK(colors->GetTypedComponent(1, 1) > colors->GetTypedComponent(1, 0));
  MRGI_TEST_CHECK(colors->GetTypedComponent(2, 2) > colors->GetTypedComponent(2, 0));
  // The table's last entries (user classes) are grey, not clamped to another colour.
  double last[3];
  table->GetColor(255, last);
  MRGI_TEST_CHECK(std::fabs(last[0] - 128 / 255.0) < 1e-6 && last[0] == last[2]);
}

void TestColorBy()
{
  const std::string rgbPath = mrgitest::TempPath("las_reader_colorby.las");
  const std::vector<LASPoint> points = ThreePoints();
  mrgitest::WriteBytes(rgbPath, mrgitest::LASBytes(UTMFile(2, 3), points));
  // Classes of an RGB file: Colors active, RGB kept.
  auto reader = Read(rgbPath, vtkMRGILASReader::COLOR_BY_CLASSIFICATION);
  vtkPointData* pd = reader->GetOutput()->GetPointData();
  MRGI_TEST_CHECK(pd->GetArray("RGB") != nullptr);
  MRGI_TEST_CHECK(pd->GetScalars() && std::string(pd->GetScalars()->GetName()) == "Colors");
  MRGI_TEST_CHECK(reader->GetColorByUsed() == vtkMRGILASReader::COLOR_BY_CLASSIFICATION);
  // Intensity: a grey ramp rising with intensity.
  reader->SetColorByToIntensity();
  reader->Update();
  auto* grey =
    vtkUnsignedCharArray::SafeDownCast(reader->GetOutput()->GetPointData()->GetScalars());
  MRGI_TEST_CHECK(grey && reader->GetColorByUsed() == vtkMRGILASReader::COLOR_BY_INTENSITY);
  MRGI_TEST_CHECK(grey->GetTypedComponent(0, 0) == grey->GetTypedComponent(0, 2));
  MRGI_TEST_CHECK(grey->GetTypedComponent(0, 0) < grey->GetTypedComponent(1, 0));
  MRGI_TEST_CHECK(grey->GetTypedComponent(1, 0) < grey->GetTypedComponent(2, 0));

  // RGB asked of a format without RGB: a warning, and Auto's choice
  // (unclassified: intensity).
  const std::string plainPath = mrgitest::TempPath("las_reader_plain.las");
  std::vector<LASPoint> plain = ThreePoints();
  for (LASPoint& p : plain)
  {
    p.Classification = 1;
  }
  mrgitest::WriteBytes(plainPath, mrgitest::LASBytes(UTMFile(2, 1), plain));
  auto plainReader = vtkSmartPointer<vtkMRGILASReader>::New();
  Events events(plainReader);
  plainReader->SetFileName(plainPath.c_str());
  plainReader->SetColorByToRGB();
  plainReader->Update();
  MRGI_TEST_CHECK(events.Warnings == 1 && events.Errors == 0);
  MRGI_TEST_CHECK(events.Last.find("has no RGB") != std::string::npos);
  MRGI_TEST_CHECK(plainReader->GetOutput()->GetNumberOfPoints() == 3);
  MRGI_TEST_CHECK(plainReader->GetColorByUsed() == vtkMRGILASReader::COLOR_BY_INTENSITY);
}

void TestOnePoint()
{
  const std::string path = mrgitest::TempPath("las_reader_one.las");
  std::vector<LASPoint> one(1);
  one[0].X = 512345.678;
  one[0].Y = 5432109.876;
  one[0].Z = -12.5;
  one[0].Intensity = 42;
  mrgitest::WriteBytes(path, mrgitest::LASBytes(UTMFile(3, 0), one));
  auto reader = Read(path);
  vtkPolyData* out = reader->GetOutput();
  MRGI_TEST_CHECK(out->GetNumberOfPoints() == 1);
  CheckVertices(out);
  double p[3];
  out->GetPoint(0, p);
  MRGI_TEST_CHECK(p[0] == 0 && p[1] == 0 && p[2] == 0); // the origin is the point itself
  CheckWorld(out, 0, one[0], 1e-9);
  // One intensity value: uniform grey, not black.
  auto* colors = vtkUnsignedCharArray::SafeDownCast(out->GetPointData()->GetScalars());
  MRGI_TEST_CHECK(colors && colors->GetTypedComponent(0, 0) == 204);
}

// Pieces, as ParaView's ranks ask for them: every point exactly once, in
// file order, with its attributes, and all pieces on the whole file's origin.
void TestPieces()
{
  const std::string path = mrgitest::TempPath("las_reader_pieces.las");
  std::vector<LASPoint> points(10);
  for (size_t i = 0; i < points.size(); ++i)
  {
    points[i].X = 512300.0 + static_cast<double>(i);
    points[i].Y = 5432100.0 + 0.5 * static_cast<double>(i);
    points[i].Z = 300.0;
    points[i].Intensity = static_cast<uint16_t>(100 + i);
    points[i].Classification = static_cast<uint8_t>(i % 3 + 1);
  }
  mrgitest::WriteBytes(path, mrgitest::LASBytes(UTMFile(2, 3), points));
  auto whole = Read(path);
  double origin[3];
  whole->GetOutput()->GetFieldData()->GetArray("Origin")->GetTuple(0, origin);
  vtkIdType next = 0;
  for (int piece = 0; piece < 3; ++piece)
  {
    vtkNew<vtkMRGILASReader> reader;
    reader->SetFileName(path.c_str());
    reader->UpdatePiece(piece, 3, 0);
    vtkPolyData* out = reader->GetOutput();
    const vtkIdType n = out->GetNumberOfPoints();
    MRGI_TEST_CHECK(n >= 3 && n <= 4);
    CheckVertices(out);
    double pieceOrigin[3];
    out->GetFieldData()->GetArray("Origin")->GetTuple(0, pieceOrigin);
    MRGI_TEST_CHECK(pieceOrigin[0] == origin[0] && pieceOrigin[1] == origin[1] &&
      pieceOrigin[2] == origin[2]);
    auto* intensity = vtkUnsignedShortArray::SafeDownCast(out->GetPointData()->GetArray("Intensity"));
    MRGI_TEST_CHECK(intensity && intensity->GetNumberOfTuples() == n);
    MRGI_TEST_CHECK(out->GetPointData()->GetScalars() != nullptr &&
      out->GetPointData()->GetScalars()->GetNumberOfTuples() == n);
    for (vtkIdType i = 0; i < n; ++i, ++next)
    {
      CheckWorld(out, i, points[static_cast<size_t>(next)], 2e-4);
      MRGI_TEST_CHECK(intensity->GetValue(i) == 100 + next);
    }
  }
  MRGI_TEST_CHECK(next == 10);
}

// UTM-sized coordinates (x ~ 5e5, y ~ 5e6 m) with a millimetre scale: in
// float they would collapse (the ulp at 5e6 is 0.5 m); recentred, they stay
// distinct and exact.
void TestHugeOffsets()
{
  MRGI_TEST_CHECK(static_cast<float>(5432109.876) == static_cast<float>(5432109.877));
  LASFile f = UTMFile(4, 6);
  f.Offset[2] = 100;
  // A 20 x 20 grid spaced 1 mm, and two 1-mm pairs 5 km away on either side.
  std::vector<LASPoint> points;
  for (int j = 0; j < 20; ++j)
  {
    for (int i = 0; i < 20; ++i)
    {
      LASPoint p;
      p.X = 512345.000 + 0.001 * i;
      p.Y = 5432109.000 + 0.001 * j;
      p.Z = 312.345 + 0.001 * ((i + j) % 3);
      points.push_back(p);
    }
  }
  const std::string compactPath = mrgitest::TempPath("las_reader_utm_compact.las");
  mrgitest::WriteBytes(compactPath, mrgitest::LASBytes(f, points));
  auto reader = Read(compactPath);
  vtkPolyData* out = reader->GetOutput();
  MRGI_TEST_CHECK(out->GetNumberOfPoints() == 400);
  for (vtkIdType k = 0; k < 400; ++k)
  {
    CheckWorld(out, k, points[static_cast<size_t>(k)], 1e-6);
    if (k % 20 != 0)
    {
      double a[3], b[3];
      out->GetPoint(k - 1, a);
      out->GetPoint(k, b);
      MRGI_TEST_CHECK(std::fabs((b[0] - a[0]) - 0.001) < 1e-6);
    }
  }

  // A 10 km wide tile: at 5 km from the centre a float keeps ~0.5 mm, so
  // 1-mm neighbours stay apart, and each point within half a millimetre.
  std::vector<LASPoint> wide(4);
  wide[0].X = 507345.000;
  wide[1].X = 507345.001;
  wide[2].X = 517345.000;
  wide[3].X = 517345.001;
  for (LASPoint& p : wide)
  {
    p.Y = 5432109.876;
    p.Z = 312.345;
  }
  const std::string widePath = mrgitest::TempPath("las_reader_utm_wide.las");
  mrgitest::WriteBytes(widePath, mrgitest::LASBytes(f, wide));
  auto wideReader = Read(widePath);
  vtkPolyData* wideOut = wideReader->GetOutput();
  MRGI_TEST_CHECK(wideOut->GetNumberOfPoints() == 4);
  for (vtkIdType k = 0; k < 4; ++k)
  {
    CheckWorld(wideOut, k, wide[static_cast<size_t>(k)], 5e-4);
  }
  double a[3], b[3];
  wideOut->GetPoint(0, a);
  wideOut->GetPoint(1, b);
  MRGI_TEST_CHECK(b[0] > a[0] && std::fabs(b[0] - a[0] - 0.001) < 5e-4);
  wideOut->GetPoint(2, a);
  wideOut->GetPoint(3, b);
  MRGI_TEST_CHECK(b[0] > a[0] && std::fabs(b[0] - a[0] - 0.001) < 5e-4);
}

// A bad file: one error event naming the file and `what`, an empty output,
// an error code, and the reader still works on a good file afterwards.
void ExpectFailure(const std::string& path, const std::string& what, vtkTypeInt64 limit = 0)
{
  auto reader = vtkSmartPointer<vtkMRGILASReader>::New();
  Events events(reader);
  reader->SetFileName(path.c_str());
  if (limit > 0)
  {
    reader->SetMaximumNumberOfPoints(limit);
  }
  reader->Update();
  const std::string message = reader->GetLastErrorMessage();
  std::printf("%s -> %s\n", path.c_str(), message.c_str());
  MRGI_TEST_CHECK(events.Errors == 1);
  MRGI_TEST_CHECK(message.find("'" + path + "'") != std::string::npos);
  MRGI_TEST_CHECK(message.find(what) != std::string::npos);
  MRGI_TEST_CHECK(events.Last.find(what) != std::string::npos);
  MRGI_TEST_CHECK(reader->GetErrorCode() != vtkErrorCode::NoError);
  MRGI_TEST_CHECK(reader->GetOutput()->GetNumberOfPoints() == 0);
  MRGI_TEST_CHECK(reader->GetOutput()->GetNumberOfCells() == 0);
  MRGI_TEST_CHECK(reader->GetColorByUsed() == -1);
}

void TestBadFiles()
{
  const std::vector<LASPoint> points = ThreePoints();
  const std::vector<unsigned char> good = mrgitest::LASBytes(UTMFile(2, 3), points);
  auto variant = [&](const std::string& name,
                   const std::function<void(std::vector<unsigned char>&)>& edit) {
    std::vector<unsigned char> b = good;
    edit(b);
    const std::string path = mrgitest::TempPath("las_reader_bad_" + name);
    mrgitest::WriteBytes(path, b);
    return path;
  };
  ExpectFailure(variant("signature.las", [](std::vector<unsigned char>& b) { b[0] = 'X'; }),
    "no 'LASF' signature");
  ExpectFailure(
    variant("version.las", [](std::vector<unsigned char>& b) { b[25] = 9; }), "version 1.9");
  ExpectFailure(
    variant("short.las", [](std::vector<unsigned char>& b) { b.resize(100); }), "shorter than");
  ExpectFailure(
    variant("truncated.las", [](std::vector<unsigned char>& b) { b.resize(b.size() - 5); }),
    "truncated");
  ExpectFailure(variant("header-size.las",
                  [](std::vector<unsigned char>& b) {
                    b[94] = 10;
                    b[95] = 0;
                  }),
    "header size");
  ExpectFailure(
    variant("format.las", [](std::vector<unsigned char>& b) { b[104] = 11; }), "point format 11");
  ExpectFailure(
    variant("record.las", [](std::vector<unsigned char>& b) { b[105] = 4; }), "record length");
  ExpectFailure(variant("scale.las",
                  [](std::vector<unsigned char>& b) { mrgitest::LASPutDouble(b, 131, 0.0); }),
    "scale factor");
  ExpectFailure(variant("offset.las",
                  [](std::vector<unsigned char>& b) { mrgitest::LASPutDouble(b, 163, NAN); }),
    "offset is not finite");
  ExpectFailure(variant("count.las",
                  [](std::vector<unsigned char>& b) { mrgitest::LASPut(b, 107, 0xFFFFFFFFu, 4); }),
    "truncated");
  ExpectFailure(
    variant("zero.las", [](std::vector<unsigned char>& b) { mrgitest::LASPut(b, 107, 0, 4); }),
    "no points");
  ExpectFailure(variant("offset-to-points.las",
                  [](std::vector<unsigned char>& b) { mrgitest::LASPut(b, 96, 0x7FFFFFF0u, 4); }),
    "point data offset");
  // LAS 1.4's 64-bit count, absurd.
  {
    std::vector<unsigned char> b = mrgitest::LASBytes(UTMFile(4, 6), points);
    mrgitest::LASPut(b, 247, 0x7FFFFFFFFFFFFFFFull, 8);
    const std::string path = mrgitest::TempPath("las_reader_bad_count64.las");
    mrgitest::WriteBytes(path, b);
    ExpectFailure(path, "truncated");
  }
  // LAZ: LASzip sets bit 7 of the point format byte.
  ExpectFailure(variant("compressed.laz", [](std::vector<unsigned char>& b) { b[104] |= 0x80; }),
    "compressed LAZ is not supported");
  // More points than allowed.
  ExpectFailure(variant("limit.las", [](std::vector<unsigned char>&) {}), "exceed the limit", 2);
  // Missing file, a directory, an empty name.
  ExpectFailure(mrgitest::TempPath("las_reader_no_such_file.las"), "las_reader_no_such_file");
  const std::string directory = mrgitest::TempPath("las_reader_directory.las");
  ::mkdir(directory.c_str(), 0755);
  ExpectFailure(directory, "las_reader_directory");
  auto unnamed = vtkSmartPointer<vtkMRGILASReader>::New();
  Events events(unnamed);
  unnamed->Update();
  MRGI_TEST_CHECK(events.Errors == 1 && unnamed->GetOutput()->GetNumberOfPoints() == 0);
  MRGI_TEST_CHECK(
    std::string(unnamed->GetLastErrorMessage()).find("FileName") != std::string::npos);

  // A reader that failed reads a good file next (nothing stale).
  const std::string goodPath = mrgitest::TempPath("las_reader_good_after_bad.las");
  mrgitest::WriteBytes(goodPath, good);
  auto reader = vtkSmartPointer<vtkMRGILASReader>::New();
  Events quiet(reader);
  reader->SetFileName(mrgitest::TempPath("las_reader_bad_truncated.las").c_str());
  reader->Update();
  MRGI_TEST_CHECK(reader->GetOutput()->GetNumberOfPoints() == 0);
  reader->SetFileName(goodPath.c_str());
  reader->Update();
  MRGI_TEST_CHECK(reader->GetOutput()->GetNumberOfPoints() == 3);
  MRGI_TEST_CHECK(reader->GetErrorCode() == vtkErrorCode::NoError);
  MRGI_TEST_CHECK(std::strlen(reader->GetLastErrorMessage()) == 0);
}

// 10^7 points (200 MB, format 0) written into the build tree's temporary
// directory, read, spot-checked and deleted. The read time is printed for
// Documentation/PointClouds-LAS.md, never asserted.
void TestTenMillion()
{
  const vtkIdType n = 10000000;
  const vtkIdType side = 4000; // 4000 x 2500 grid, 1 cm apart, UTM-sized
  LASFile f = UTMFile(2, 0);
  f.Scale[0] = f.Scale[1] = f.Scale[2] = 0.001;
  const std::string path = mrgitest::TempPath("las_reader_1e7.las");
  auto pointAt = [&](vtkIdType k) {
    LASPoint p;
    p.X = 512000.0 + 0.01 * static_cast<double>(k % side);
    p.Y = 5432000.0 + 0.01 * static_cast<double>(k / side);
    p.Z = 300.0 + 0.001 * static_cast<double>(k % 1000);
    p.Intensity = static_cast<uint16_t>(k % 4096);
    p.Classification = static_cast<uint8_t>(k % 3 == 0 ? 2 : 1);
    return p;
  };
  const auto t0 = std::chrono::steady_clock::now();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    std::vector<unsigned char> chunk = mrgitest::LASHeader(f, static_cast<uint64_t>(n));
    for (vtkIdType k = 0; k < n; ++k)
    {
      mrgitest::LASAppend(chunk, f, pointAt(k));
      if (chunk.size() > (1u << 22) || k == n - 1)
      {
        out.write(
          reinterpret_cast<const char*>(chunk.data()), static_cast<std::streamsize>(chunk.size()));
        chunk.clear();
      }
    }
    MRGI_TEST_CHECK(out.good());
  }
  const auto t1 = std::chrono::steady_clock::now();
  auto reader = Read(path);
  const auto t2 = std::chrono::steady_clock::now();
  std::remove(path.c_str());
  const double writeSeconds = std::chrono::duration<double>(t1 - t0).count();
  const double readSeconds = std::chrono::duration<double>(t2 - t1).count();
  std::printf("1e7 LAS points (format 0, 200 MB): written in %.2f s, read in %.2f s "
              "(%.3f s per million points)\n",
    writeSeconds, readSeconds, readSeconds / 10.0);
  vtkPolyData* out = reader->GetOutput();
  MRGI_TEST_CHECK(std::strlen(reader->GetLastErrorMessage()) == 0);
  MRGI_TEST_CHECK(out->GetNumberOfPoints() == n);
  CheckVertices(out);
  MRGI_TEST_CHECK(reader->GetColorByUsed() == vtkMRGILASReader::COLOR_BY_CLASSIFICATION);
  auto* intensity = vtkUnsignedShortArray::SafeDownCast(out->GetPointData()->GetArray("Intensity"));
  MRGI_TEST_CHECK(intensity && intensity->GetNumberOfTuples() == n);
  for (vtkIdType k = 0; k < n; k += 999983)
  {
    CheckWorld(out, k, pointAt(k), 1e-4);
    MRGI_TEST_CHECK(intensity->GetValue(k) == pointAt(k).Intensity);
  }
  CheckWorld(out, n - 1, pointAt(n - 1), 1e-4);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestAttributes), MRGI_TEST_CASE(TestEightBitRGB),
      MRGI_TEST_CASE(TestClassifiedColors), MRGI_TEST_CASE(TestColorBy),
      MRGI_TEST_CASE(TestOnePoint), MRGI_TEST_CASE(TestPieces), MRGI_TEST_CASE(TestHugeOffsets), MRGI_TEST_CASE(TestBadFiles),
      MRGI_TEST_CASE(TestTenMillion) });
}
