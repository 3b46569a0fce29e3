#include "vtkMRGIPCLPCDReader.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include "mrgi_pcd_check.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>

#include <cmath>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIPCLPCDReader);

namespace
{
/** One field of a PCLPointCloud2 read as double, or NaN for unknown types. */
double ReadValue(const std::uint8_t* p, std::uint8_t datatype)
{
  switch (datatype)
  {
    case pcl::PCLPointField::INT8:
    {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return v;
    }
    case pcl::PCLPointField::UINT8:
      return *p;
    case pcl::PCLPointField::INT16:
    {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case pcl::PCLPointField::UINT16:
    {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case pcl::PCLPointField::INT32:
    {
      std::int32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case pcl::PCLPointField::UINT32:
    {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case pcl::PCLPointField::FLOAT32:
    {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case pcl::PCLPointField::FLOAT64:
    {
      double v;
      std::memcpy(&v, p, 8);
      return v;
    }
    default:
      return std::nan("");
  }
}

const pcl::PCLPointField* FindField(const pcl::PCLPointCloud2& cloud, const char* name)
{
  for (const auto& field : cloud.fields)
  {
    if (field.name == name)
    {
      return &field;
    }
  }
  return nullptr;
}
}

vtkMRGIPCLPCDReader::vtkMRGIPCLPCDReader() = default;
vtkMRGIPCLPCDReader::~vtkMRGIPCLPCDReader() = default;

int vtkMRGIPCLPCDReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  this->NumberOfPointsInFile = 0;
  this->NumberOfDroppedPoints = 0;
  if (!this->FileName || !this->FileName[0])
  {
    vtkErrorMacro(<< "no PCD file name given (SetFileName)");
    return 0;
  }
  const std::string path = this->FileName;

  // The core's structure check first: PCL would crash or allocate what the
  // header declares on some of what it refuses.
  mrgi_error err;
  mrgi_pcd_info info;
  if (mrgi_pcd_check(path.c_str(), this->MaximumNumberOfPoints, &info, &err) != MRGI_OK)
  {
    vtkErrorMacro(<< err.message);
    return 0;
  }

  pcl::PCLPointCloud2 cloud;
  Eigen::Vector4f origin = Eigen::Vector4f::Zero();
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
  int version = 0;
  int rc = -1;
  try
  {
    pcl::PCDReader reader;
    rc = reader.read(path, cloud, origin, orientation, version, 0);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "'" << path << "': PCL's PCD reader failed: " << e.what());
    return 0;
  }
  if (rc != 0)
  {
    vtkErrorMacro(<< "'" << path << "': PCL's PCD reader refused the file (code " << rc
                  << "; its message is on the standard error)");
    return 0;
  }
  const std::size_t count = static_cast<std::size_t>(cloud.width) * cloud.height;
  if (count != static_cast<std::size_t>(info.points) ||
    cloud.data.size() < count * cloud.point_step)
  {
    vtkErrorMacro(<< "'" << path << "': PCL read " << cloud.width << " x " << cloud.height
                  << " points in " << cloud.data.size() << " bytes, the header declares "
                  << info.points);
    return 0;
  }
  const pcl::PCLPointField* xyz[3] = { FindField(cloud, "x"), FindField(cloud, "y"),
    FindField(cloud, "z") };
  for (int a = 0; a < 3; ++a)
  {
    if (!xyz[a] || xyz[a]->offset + 4 > cloud.point_step)
    {
      vtkErrorMacro(<< "'" << path << "': no usable field '"
                    << "xyz"[a] << "'");
      return 0;
    }
  }

  // Finite points: their indices in the file.
  std::vector<vtkIdType> kept;
  kept.reserve(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    const std::uint8_t* p = cloud.data.data() + i * cloud.point_step;
    bool finite = true;
    for (int a = 0; a < 3 && finite; ++a)
    {
      finite = std::isfinite(ReadValue(p + xyz[a]->offset, xyz[a]->datatype));
    }
    if (finite)
    {
      kept.push_back(static_cast<vtkIdType>(i));
    }
  }
  if (kept.empty())
  {
    vtkErrorMacro(<< "'" << path << "': none of its " << count << " points is finite");
    return 0;
  }
  const vtkIdType n = static_cast<vtkIdType>(kept.size());
  this->NumberOfPointsInFile = static_cast<vtkIdType>(count);
  this->NumberOfDroppedPoints = static_cast<vtkIdType>(count) - n;

  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(n);
  float* pts = vtkFloatArray::SafeDownCast(points->GetData())->GetPointer(0);
  for (vtkIdType k = 0; k < n; ++k)
  {
    const std::uint8_t* p = cloud.data.data() + kept[k] * cloud.point_step;
    for (int a = 0; a < 3; ++a)
    {
      pts[3 * k + a] = static_cast<float>(ReadValue(p + xyz[a]->offset, xyz[a]->datatype));
    }
  }
  output->SetPoints(points);

  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(n);
  for (vtkIdType k = 0; k < n; ++k)
  {
    offsets->SetValue(k, k);
    connectivity->SetValue(k, k);
  }
  offsets->SetValue(n, n);
  vtkNew<vtkCellArray> verts;
  verts->SetData(offsets, connectivity);
  output->SetVerts(verts);

  vtkPointData* pd = output->GetPointData();
  // Colour: rgb (PCL packs it in a float or a uint32) or rgba (uint32).
  const pcl::PCLPointField* rgb = FindField(cloud, "rgb");
  if (!rgb)
  {
    rgb = FindField(cloud, "rgba");
  }
  if (rgb && rgb->offset + 4 <= cloud.point_step &&
    (rgb->datatype == pcl::PCLPointField::FLOAT32 || rgb->datatype == pcl::PCLPointField::UINT32 ||
      rgb->datatype == pcl::PCLPointField::INT32))
  {
    vtkNew<vtkUnsignedCharArray> colors;
    colors->SetName("RGB");
    colors->SetNumberOfComponents(3);
    colors->SetNumberOfTuples(n);
    unsigned char* c = colors->GetPointer(0);
    for (vtkIdType k = 0; k < n; ++k)
    {
      std::uint32_t v;
      std::memcpy(&v, cloud.data.data() + kept[k] * cloud.point_step + rgb->offset, 4);
      c[3 * k + 0] = static_cast<unsigned char>((v >> 16) & 0xFF);
      c[3 * k + 1] = static_cast<unsigned char>((v >> 8) & 0xFF);
      c[3 * k + 2] = static_cast<unsigned char>(v & 0xFF);
    }
    pd->SetScalars(colors);
  }
  else if (rgb)
  {
    vtkWarningMacro(<< "'" << path << "': field '" << rgb->name
                    << "' is not a packed 32-bit colour: ignored");
  }

  // Normals, kept only when every kept point has a finite one.
  const pcl::PCLPointField* nrm[3] = { FindField(cloud, "normal_x"), FindField(cloud, "normal_y"),
    FindField(cloud, "normal_z") };
  if (nrm[0] && nrm[1] && nrm[2])
  {
    vtkNew<vtkFloatArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(n);
    float* out = normals->GetPointer(0);
    vtkIdType bad = 0;
    for (vtkIdType k = 0; k < n; ++k)
    {
      const std::uint8_t* p = cloud.data.data() + kept[k] * cloud.point_step;
      for (int a = 0; a < 3; ++a)
      {
        const double v = ReadValue(p + nrm[a]->offset, nrm[a]->datatype);
        out[3 * k + a] = static_cast<float>(v);
        bad += std::isfinite(v) ? 0 : 1;
      }
    }
    if (bad == 0)
    {
      pd->SetNormals(normals);
    }
    else
    {
      vtkWarningMacro(<< "'" << path << "': " << bad
                      << " normal components are not finite: the file's normals are dropped "
                         "(vtkMRGIPointCloudNormals estimates them)");
    }
  }

  // Scalar fields kept as float arrays.
  const char* scalars[2][2] = { { "intensity", "Intensity" }, { "curvature", "Curvature" } };
  for (const auto& names : scalars)
  {
    const pcl::PCLPointField* field = FindField(cloud, names[0]);
    if (!field)
    {
      continue;
    }
    vtkNew<vtkFloatArray> values;
    values->SetName(names[1]);
    values->SetNumberOfTuples(n);
    for (vtkIdType k = 0; k < n; ++k)
    {
      values->SetValue(k,
        static_cast<float>(ReadValue(
          cloud.data.data() + kept[k] * cloud.point_step + field->offset, field->datatype)));
    }
    pd->AddArray(values);
  }

  vtkFieldData* fd = output->GetFieldData();
  if (cloud.height > 1)
  {
    vtkNew<vtkIdTypeArray> pixels;
    pixels->SetName("PixelIndex");
    pixels->SetNumberOfValues(n);
    for (vtkIdType k = 0; k < n; ++k)
    {
      pixels->SetValue(k, kept[k]);
    }
    pd->AddArray(pixels);
    vtkNew<vtkIntArray> dims;
    dims->SetName("OrganizedDimensions");
    dims->SetNumberOfValues(2);
    dims->SetValue(0, static_cast<int>(cloud.width));
    dims->SetValue(1, static_cast<int>(cloud.height));
    fd->AddArray(dims);
  }
  vtkNew<vtkDoubleArray> sensorOrigin;
  sensorOrigin->SetName("SensorOrigin");
  sensorOrigin->SetNumberOfComponents(3);
  sensorOrigin->InsertNextTuple3(origin[0], origin[1], origin[2]);
  fd->AddArray(sensorOrigin);
  vtkNew<vtkDoubleArray> sensorOrientation;
  sensorOrientation->SetName("SensorOrientation");
  sensorOrientation->SetNumberOfComponents(4);
  sensorOrientation->InsertNextTuple4(
    orientation.w(), orientation.x(), orientation.y(), orientation.z());
  fd->AddArray(sensorOrientation);
  return 1;
}

void vtkMRGIPCLPCDReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumNumberOfPoints: " << this->MaximumNumberOfPoints << "\n";
  os << indent << "NumberOfPointsInFile: " << this->NumberOfPointsInFile << "\n";
  os << indent << "NumberOfDroppedPoints: " << this->NumberOfDroppedPoints << "\n";
}
