#include "vtkMRGIBuiltInScenes.h"

#include "vtkMRGIAreaLight.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkTypeInt32Array.h"

#include "mrgi_scene.h"
#include "mrgi_scene_cornell.h"
#include "mrgi_scene_indirect.h"
#include "mrgi_scene_living_room.h"
#include "mrgi_scene_scaling.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace
{
const char* const Names[] = { "cornell", "cornell-spot", "cornell-area", "living-room",
  "scaling", "corridor", "corridor-large", "corner", "u-shape" };

// Whether every vertex of `mesh` lies in the rectangle of `light` (up to a
// small fraction of its size).
bool InRectangle(const mrgi_mesh& mesh, const mrgi_area_light& light)
{
  double n[3];
  vtkMath::Cross(light.edge_u, light.edge_v, n);
  const double uu = vtkMath::Dot(light.edge_u, light.edge_u);
  const double vv = vtkMath::Dot(light.edge_v, light.edge_v);
  const double nn = vtkMath::Norm(n);
  if (mesh.vertex_count < 1 || !(uu > 0.0) || !(vv > 0.0) || !(nn > 0.0))
  {
    return false;
  }
  const double tolerance = 1e-4;
  const double size = std::sqrt(uu) + std::sqrt(vv);
  for (int64_t i = 0; i < mesh.vertex_count; ++i)
  {
    double d[3];
    for (int c = 0; c < 3; ++c)
    {
      d[c] = mesh.positions[3 * static_cast<size_t>(i) + static_cast<size_t>(c)] - light.center[c];
    }
    if (std::fabs(vtkMath::Dot(d, n)) / nn > tolerance * size ||
      std::fabs(vtkMath::Dot(d, light.edge_u)) / uu > 0.5 + tolerance ||
      std::fabs(vtkMath::Dot(d, light.edge_v)) / vv > 0.5 + tolerance)
    {
      return false;
    }
  }
  return true;
}

vtkSmartPointer<vtkLight> MakeLight(const mrgi_light& in)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->SetPosition(in.position[0], in.position[1], in.position[2]);
  light->SetFocalPoint(in.focal_point[0], in.focal_point[1], in.focal_point[2]);
  light->SetColor(in.color[0], in.color[1], in.color[2]);
  light->SetIntensity(in.intensity);
  switch (in.type)
  {
    case MRGI_LIGHT_DIRECTIONAL:
      light->SetPositional(false);
      break;
    case MRGI_LIGHT_SPOT:
      light->SetPositional(true);
      light->SetConeAngle(in.cone_angle_deg);
      light->SetExponent(in.exponent);
      break;
    case MRGI_LIGHT_POSITIONAL:
    default:
      light->SetPositional(true);
      light->SetConeAngle(90.0);
      break;
  }
  return light;
}
}

//------------------------------------------------------------------------------
bool vtkMRGIBuiltInScenes::IsName(const char* name)
{
  return name &&
    std::any_of(std::begin(Names), std::end(Names),
      [name](const char* s) { return std::strcmp(s, name) == 0; });
}

//------------------------------------------------------------------------------
const char* vtkMRGIBuiltInScenes::NameList()
{
  return "cornell cornell-spot cornell-area living-room scaling corridor corridor-large corner "
         "u-shape";
}

//------------------------------------------------------------------------------
bool vtkMRGIBuiltInScenes::Make(const std::string& name, int objectCount, vtkIdType triangleCount,
  vtkTypeUInt64 seed, mrgi_scene* scene, mrgi_error* err)
{
  mrgi_status status = MRGI_OK;
  mrgi_indirect_scene which = MRGI_INDIRECT_CORRIDOR;
  if (name == "scaling")
  {
    status = mrgi_scene_scaling(objectCount, triangleCount, seed, scene, err);
  }
  else if (name == "living-room")
  {
    status = mrgi_scene_living_room(scene, err);
  }
  else if (mrgi_indirect_scene_parse(name.c_str(), &which, nullptr) == MRGI_OK)
  {
    status = mrgi_scene_indirect(which, scene, err);
  }
  else
  {
    mrgi_cornell_variant variant = MRGI_CORNELL_POINT;
    status = mrgi_cornell_variant_parse(name.c_str(), &variant, err);
    if (status == MRGI_OK)
    {
      status = mrgi_scene_cornell_box(variant, scene, err);
    }
  }
  return status == MRGI_OK;
}

//------------------------------------------------------------------------------
vtkPolyData* vtkMRGIBuiltInScenes::MeshToPolyData(const mrgi_mesh* mesh)
{
  vtkPolyData* poly = vtkPolyData::New();
  if (!mesh || mesh->vertex_count < 1 || mesh->triangle_count < 1)
  {
    return poly;
  }
  const vtkIdType nv = static_cast<vtkIdType>(mesh->vertex_count);
  const vtkIdType nt = static_cast<vtkIdType>(mesh->triangle_count);

  vtkNew<vtkFloatArray> coords;
  coords->SetNumberOfComponents(3);
  coords->SetNumberOfTuples(nv);
  std::memcpy(coords->GetPointer(0), mesh->positions, sizeof(float) * 3 * static_cast<size_t>(nv));
  vtkNew<vtkPoints> points;
  points->SetData(coords);
  poly->SetPoints(points);

  if (mesh->normals)
  {
    vtkNew<vtkFloatArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(nv);
    std::memcpy(
      normals->GetPointer(0), mesh->normals, sizeof(float) * 3 * static_cast<size_t>(nv));
    poly->GetPointData()->SetNormals(normals);
  }

  // 32-bit cell storage: half the memory of vtkIdType for 1e7-triangle scenes.
  vtkNew<vtkTypeInt32Array> offsets;
  offsets->SetNumberOfTuples(nt + 1);
  vtkNew<vtkTypeInt32Array> connectivity;
  connectivity->SetNumberOfTuples(3 * nt);
  vtkTypeInt32* off = offsets->GetPointer(0);
  vtkTypeInt32* con = connectivity->GetPointer(0);
  for (vtkIdType t = 0; t <= nt; ++t)
  {
    off[t] = static_cast<vtkTypeInt32>(3 * t);
  }
  for (vtkIdType i = 0; i < 3 * nt; ++i)
  {
    con[i] = static_cast<vtkTypeInt32>(mesh->indices[i]);
  }
  vtkNew<vtkCellArray> triangles;
  triangles->SetData(offsets, connectivity);
  poly->SetPolys(triangles);
  return poly;
}

//------------------------------------------------------------------------------
vtkIdType vtkMRGIBuiltInScenes::AddToRenderer(const mrgi_scene* scene, vtkRenderer* renderer,
  std::vector<vtkSmartPointer<vtkMRGIAreaLight>>& areaLights)
{
  vtkIdType triangles = 0;
  std::vector<vtkSmartPointer<vtkActor>> actors;
  std::vector<std::pair<const mrgi_mesh*, vtkActor*>> emitters; // for textured area lights
  for (int32_t m = 0; m < scene->mesh_count; ++m)
  {
    const mrgi_mesh& mesh = scene->meshes[m];
    vtkSmartPointer<vtkPolyData> poly = vtkSmartPointer<vtkPolyData>::Take(MeshToPolyData(&mesh));
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(poly);
    mapper->ScalarVisibilityOff();
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    vtkProperty* property = actor->GetProperty();
    const bool emitter = mesh.emission[0] > 0.f || mesh.emission[1] > 0.f || mesh.emission[2] > 0.f;
    if (emitter)
    {
      // An emitter shows its radiance whatever the lights: VTK's ambient term
      // with the (unclamped) radiance as colour; the float buffers keep it HDR.
      property->SetAmbient(1.0);
      property->SetDiffuse(0.0);
      property->SetSpecular(0.0);
      property->SetAmbientColor(mesh.emission[0], mesh.emission[1], mesh.emission[2]);
      property->SetColor(mesh.emission[0], mesh.emission[1], mesh.emission[2]);
      emitters.emplace_back(&mesh, actor.Get());
    }
    else
    {
      property->SetColor(mesh.albedo[0], mesh.albedo[1], mesh.albedo[2]);
      property->SetAmbient(0.0);
      property->SetDiffuse(1.0);
      property->SetSpecular(0.0);
    }
    actors.push_back(actor);
    triangles += static_cast<vtkIdType>(mesh.triangle_count);
  }

  for (const auto& actor : actors)
  {
    renderer->AddActor(actor);
  }
  for (int32_t l = 0; l < scene->light_count; ++l)
  {
    renderer->AddLight(MakeLight(scene->lights[l]));
  }
  for (int32_t l = 0; l < scene->area_light_count; ++l)
  {
    const mrgi_area_light& core = scene->area_lights[l];
    auto light = vtkSmartPointer<vtkMRGIAreaLight>::New();
    light->SetCenter(const_cast<double*>(core.center));
    light->SetEdgeU(const_cast<double*>(core.edge_u));
    light->SetEdgeV(const_cast<double*>(core.edge_v));
    light->SetColor(const_cast<double*>(core.color));
    light->SetIntensity(core.intensity);
    light->SetTwoSided(core.two_sided != 0);
    light->SetVisible(false); // the scene's emitter mesh shows it
    if (core.texture && core.texture->pixels && core.texture->channels >= 3)
    {
      // Core images run top-down; VTK's bottom-up.
      const mrgi_image& t = *core.texture;
      vtkNew<vtkImageData> image;
      image->SetDimensions(t.width, t.height, 1);
      image->AllocateScalars(VTK_FLOAT, 3);
      auto* out = static_cast<float*>(image->GetScalarPointer());
      for (int32_t y = 0; y < t.height; ++y)
      {
        for (int32_t x = 0; x < t.width; ++x)
        {
          const float* in = t.pixels + (static_cast<size_t>(t.height - 1 - y) * t.width + x) * t.channels;
          float* o = out + 3 * (static_cast<size_t>(y) * t.width + x);
          o[0] = in[0];
          o[1] = in[1];
          o[2] = in[2];
        }
      }
      light->SetTextureData(image);
      // The emitter mesh lying in this light's rectangle (living-room's
      // screen) shows the light's picture instead of its mean radiance: it
      // becomes a view of the light's geometry actor (the same quad, unlit,
      // the picture scaled for display, the next video frame included; see
      // vtkMRGIAreaLight::GetGeometryActor()) with its own visibility.
      for (const auto& emitter : emitters)
      {
        if (InRectangle(*emitter.first, core))
        {
          light->ShareGeometryActor(emitter.second);
        }
      }
    }
    areaLights.push_back(light);
  }
  if (scene->light_count == 0 && scene->area_light_count > 0)
  {
    // Lit by area lights only (vtkMRGIPass adds their light). Without any
    // vtkLight, VTK would draw every surface unlit, at its full colour; a
    // switched-on light of intensity 0 keeps VTK's lighting on, and black.
    vtkNew<vtkLight> dark;
    dark->SetLightTypeToSceneLight();
    dark->SetIntensity(0.0);
    renderer->AddLight(dark);
  }
  // Built-in scenes carry their own lighting: no automatic headlight.
  renderer->AutomaticLightCreationOff();

  vtkCamera* camera = renderer->GetActiveCamera();
  const mrgi_camera& c = scene->camera;
  camera->SetPosition(c.position[0], c.position[1], c.position[2]);
  camera->SetFocalPoint(c.focal_point[0], c.focal_point[1], c.focal_point[2]);
  camera->SetViewUp(c.view_up[0], c.view_up[1], c.view_up[2]);
  camera->SetViewAngle(c.view_angle_deg);
  renderer->ResetCameraClippingRange();
  return triangles;
}
