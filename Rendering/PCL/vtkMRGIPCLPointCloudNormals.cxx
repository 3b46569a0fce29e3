#include "vtkMRGIPCLPointCloudNormals.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <pcl/features/integral_image_normal.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <cmath>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkMRGIPCLPointCloudNormals);

namespace
{
/** Smallest width and height given to the integral-image estimator. */
constexpr double MinimumIntegralImageSide = 40.0;
}

vtkMRGIPCLPointCloudNormals::vtkMRGIPCLPointCloudNormals() = default;
vtkMRGIPCLPointCloudNormals::~vtkMRGIPCLPointCloudNormals() = default;

bool vtkMRGIPCLPointCloudNormals::Estimate(vtkPolyData* input, const float* xyz, vtkIdType n,
  int orientation, const double reference[3], float* normals, float* radii)
{
  this->UsedIntegralImage = false;
  const int k = this->NumberOfNeighbors;

  // The finite points, compacted (PCL's search wants finite points only).
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  std::vector<vtkIdType> original;
  cloud->reserve(static_cast<std::size_t>(n));
  original.reserve(static_cast<std::size_t>(n));
  double centroid[3] = { 0.0, 0.0, 0.0 };
  for (vtkIdType i = 0; i < n; ++i)
  {
    const float* p = xyz + 3 * i;
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
    {
      cloud->push_back(pcl::PointXYZ(p[0], p[1], p[2]));
      original.push_back(i);
      for (int a = 0; a < 3; ++a)
      {
        centroid[a] += p[a];
      }
    }
  }
  const std::size_t m = cloud->size();
  this->NumberOfNonFinitePoints = n - static_cast<vtkIdType>(m);
  for (int a = 0; a < 3 && m > 0; ++a)
  {
    centroid[a] /= static_cast<double>(m);
  }

  // Normals of the compact cloud; NaN where none was found.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> compact(3 * m, nan);
  if (normals && m > 0)
  {
    std::vector<int> missing;
    vtkDataArray* dims = input->GetFieldData()->GetArray("OrganizedDimensions");
    vtkDataArray* pixels = input->GetPointData()->GetArray("PixelIndex");
    bool organized = dims && dims->GetNumberOfTuples() * dims->GetNumberOfComponents() == 2 &&
      pixels && pixels->GetNumberOfTuples() == n;
    std::size_t width = 0, height = 0;
    if (organized)
    {
      const double w = dims->GetComponent(0, 0);
      const double h =
        dims->GetNumberOfComponents() == 2 ? dims->GetComponent(0, 1) : dims->GetComponent(1, 0);
      // PCL 1.13's integral-image estimator reads outside its image when a
      // side is under 10 pixels (SIGSEGV, measured) and finds no normal
      // within 2 x 10 + 1 pixels of a border: small grids go to kNN.
      organized = w >= MinimumIntegralImageSide && h >= MinimumIntegralImageSide && w * h <= 1e9;
      width = organized ? static_cast<std::size_t>(w) : 0;
      height = organized ? static_cast<std::size_t>(h) : 0;
    }
    if (organized)
    {
      // Back on the sensor's grid, NaN where no point is.
      pcl::PointCloud<pcl::PointXYZ>::Ptr grid(
        new pcl::PointCloud<pcl::PointXYZ>(static_cast<std::uint32_t>(width),
          static_cast<std::uint32_t>(height), pcl::PointXYZ(nan, nan, nan)));
      grid->is_dense = false;
      std::vector<std::size_t> where(m);
      for (std::size_t j = 0; j < m && organized; ++j)
      {
        const double pixel = pixels->GetComponent(original[j], 0);
        organized = pixel >= 0 && pixel < static_cast<double>(width * height);
        where[j] = organized ? static_cast<std::size_t>(pixel) : 0;
        if (organized)
        {
          (*grid)[where[j]] = (*cloud)[j];
        }
      }
      if (organized)
      {
        pcl::IntegralImageNormalEstimation<pcl::PointXYZ, pcl::Normal> integral;
        integral.setNormalEstimationMethod(integral.AVERAGE_3D_GRADIENT);
        integral.setMaxDepthChangeFactor(0.02f);
        integral.setNormalSmoothingSize(10.0f);
        integral.setViewPoint(static_cast<float>(reference[0]), static_cast<float>(reference[1]),
          static_cast<float>(reference[2]));
        integral.setInputCloud(grid);
        pcl::PointCloud<pcl::Normal> result;
        integral.compute(result);
        for (std::size_t j = 0; j < m; ++j)
        {
          const pcl::Normal& nn = result[where[j]];
          if (std::isfinite(nn.normal_x) && std::isfinite(nn.normal_y) &&
            std::isfinite(nn.normal_z))
          {
            compact[3 * j + 0] = nn.normal_x;
            compact[3 * j + 1] = nn.normal_y;
            compact[3 * j + 2] = nn.normal_z;
          }
          else
          {
            missing.push_back(static_cast<int>(j));
          }
        }
        this->UsedIntegralImage = true;
      }
    }
    if (!this->UsedIntegralImage)
    {
      missing.resize(m);
      for (std::size_t j = 0; j < m; ++j)
      {
        missing[j] = static_cast<int>(j);
      }
    }
    if (!missing.empty() && m >= 3)
    {
      pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> knn;
      knn.setInputCloud(cloud);
      knn.setIndices(pcl::IndicesPtr(new pcl::Indices(missing.begin(), missing.end())));
      pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
      knn.setSearchMethod(tree);
      knn.setKSearch(std::min<int>(k + 1, static_cast<int>(m)));
      pcl::PointCloud<pcl::Normal> result;
      knn.compute(result);
      for (std::size_t t = 0; t < missing.size() && t < result.size(); ++t)
      {
        const std::size_t j = static_cast<std::size_t>(missing[t]);
        compact[3 * j + 0] = result[t].normal_x;
        compact[3 * j + 1] = result[t].normal_y;
        compact[3 * j + 2] = result[t].normal_z;
      }
    }
  }

  // Radii: the core's (its grid search was 2.7x faster than PCL's k-d tree
  // on a million points: Documentation/PointClouds-Readers.md).
  if (radii &&
    !this->vtkMRGIPointCloudNormals::Estimate(
      input, xyz, n, orientation, reference, nullptr, radii))
  {
    return false;
  }

  // Back to the input's order; orientation as in the base class.
  vtkIdType degenerate = 0;
  double fallback[3] = { 0.0, 0.0, 1.0 };
  if (orientation == ORIENT_UP)
  {
    const double l = std::sqrt(
      reference[0] * reference[0] + reference[1] * reference[1] + reference[2] * reference[2]);
    for (int a = 0; a < 3 && l > 0.0; ++a)
    {
      fallback[a] = reference[a] / l;
    }
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (normals)
    {
      for (int a = 0; a < 3; ++a)
      {
        normals[3 * i + a] = static_cast<float>(fallback[a]);
      }
    }
  }
  for (std::size_t j = 0; j < m; ++j)
  {
    const vtkIdType i = original[j];
    if (!normals)
    {
      continue;
    }
    const float* p = xyz + 3 * i;
    double ref[3];
    for (int a = 0; a < 3; ++a)
    {
      ref[a] = orientation == ORIENT_VIEWPOINT ? reference[a] - p[a]
        : orientation == ORIENT_UP             ? reference[a]
                                               : p[a] - centroid[a];
    }
    double v[3] = { compact[3 * j], compact[3 * j + 1], compact[3 * j + 2] };
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(l > 1e-12) || !std::isfinite(l))
    {
      ++degenerate;
      if (orientation == ORIENT_VIEWPOINT)
      {
        const double lr = std::sqrt(ref[0] * ref[0] + ref[1] * ref[1] + ref[2] * ref[2]);
        for (int a = 0; a < 3; ++a)
        {
          v[a] = lr > 0.0 ? ref[a] / lr : fallback[a];
        }
      }
      else
      {
        for (int a = 0; a < 3; ++a)
        {
          v[a] = fallback[a];
        }
      }
    }
    else
    {
      for (int a = 0; a < 3; ++a)
      {
        v[a] /= l;
      }
    }
    if (v[0] * ref[0] + v[1] * ref[1] + v[2] * ref[2] < 0.0)
    {
      for (int a = 0; a < 3; ++a)
      {
        v[a] = -v[a];
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      normals[3 * i + a] = static_cast<float>(v[a]);
    }
  }
  this->NumberOfDegeneratePoints = degenerate;
  return true;
}

void vtkMRGIPCLPointCloudNormals::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "UsedIntegralImage: " << (this->UsedIntegralImage ? "On" : "Off") << "\n";
}
