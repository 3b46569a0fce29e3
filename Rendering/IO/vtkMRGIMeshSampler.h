/**
 * @class   vtkMRGIMeshSampler
 * @brief   A point cloud sampled from a triangle mesh, uniformly by area, with
 *          normals and radii: the clouds that tests and benchmarks compare
 *          with the mesh they came from.
 *
 * Through the C core's mrgi_mesh_sample.h: NumberOfPoints points, the same
 * for the same mesh, count and Seed on every machine; each point gets its
 * triangle's unit normal (what VTK draws for a mesh without point normals)
 * and the radius RadiusFactor * sqrt(A / (pi N)), A the mesh's area (with the
 * default factor 2.5, 0.19% of the surface is left uncovered by the disks).
 *
 * Input: a vtkPolyData whose polygons are the surface (each polygon is cut
 * into a fan of triangles; vertices and lines are ignored; triangle strips
 * are refused: put vtkTriangleFilter first). Output: the points (float),
 * point data "Normals" (active normals) and "Radius", one vertex cell per
 * point (32-bit storage): ready for vtkMRGISurfels, or to draw as pixels.
 */
#ifndef vtkMRGIMeshSampler_h
#define vtkMRGIMeshSampler_h

#include "MRGIRenderingIOModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class MRGIRENDERINGIO_EXPORT vtkMRGIMeshSampler : public vtkPolyDataAlgorithm
{
public:
  static vtkMRGIMeshSampler* New();
  vtkTypeMacro(vtkMRGIMeshSampler, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Points to sample (default 100000). */
  vtkSetClampMacro(NumberOfPoints, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(NumberOfPoints, vtkIdType);
  ///@}

  ///@{
  /** Seed of the sampler's random sequence (default 1). */
  vtkSetMacro(Seed, vtkTypeUInt64);
  vtkGetMacro(Seed, vtkTypeUInt64);
  ///@}

  ///@{
  /** Radius over sqrt(A / (pi N)) (default 2.5, MRGI_MESH_SAMPLE_RADIUS_FACTOR). */
  vtkSetClampMacro(RadiusFactor, double, 1e-6, 1e6);
  vtkGetMacro(RadiusFactor, double);
  ///@}

  /** The radius every point got in the last update (0 before). */
  vtkGetMacro(SampledRadius, double);

protected:
  vtkMRGIMeshSampler();
  ~vtkMRGIMeshSampler() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  vtkIdType NumberOfPoints = 100000;
  vtkTypeUInt64 Seed = 1;
  double RadiusFactor;
  double SampledRadius = 0.0;

private:
  vtkMRGIMeshSampler(const vtkMRGIMeshSampler&) = delete;
  void operator=(const vtkMRGIMeshSampler&) = delete;
};

#endif
