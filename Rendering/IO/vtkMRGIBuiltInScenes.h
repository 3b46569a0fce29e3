/**
 * @file    vtkMRGIBuiltInScenes.h
 * @brief   Internal (MRGI::RenderingIO): the built-in scenes of
 *          vtkMRGISceneBuilder, made by MRGI's C core and turned into VTK
 *          actors, lights, area lights and a camera.
 *
 * The scenes and their lighting are documented on vtkMRGISceneBuilder
 * (cornell, cornell-spot, cornell-area, living-room, scaling, corridor,
 * corridor-large, corner, u-shape; the core's mrgi_scene_cornell.h,
 * mrgi_scene_living_room.h, mrgi_scene_scaling.h, mrgi_scene_indirect.h).
 * Not wrapped, not installed.
 */
#ifndef vtkMRGIBuiltInScenes_h
#define vtkMRGIBuiltInScenes_h

#include "vtkSmartPointer.h" // For vtkSmartPointer
#include "vtkType.h"         // For vtkIdType, vtkTypeUInt64

#include <string> // For std::string
#include <vector> // For std::vector

class vtkMRGIAreaLight;
class vtkPolyData;
class vtkRenderer;
struct mrgi_error;
struct mrgi_mesh;
struct mrgi_scene;

namespace vtkMRGIBuiltInScenes
{
/** Whether `name` is a built-in scene (false for nullptr). */
bool IsName(const char* name);

/** The built-in scene names, space separated. */
const char* NameList();

/**
 * Make built-in scene `name` into `scene` (the caller destroys it with
 * mrgi_scene_destroy()); the scaling scene takes `objectCount`,
 * `triangleCount` and `seed`. False with `err` set when the core refuses.
 */
bool Make(const std::string& name, int objectCount, vtkIdType triangleCount, vtkTypeUInt64 seed,
  mrgi_scene* scene, mrgi_error* err);

/** vtkMRGISceneBuilder::MeshToPolyData(): the caller owns the result. */
vtkPolyData* MeshToPolyData(const mrgi_mesh* mesh);

/**
 * Add `scene`'s meshes (emitters drawn by their radiance), vtkLights and
 * camera to `renderer`, turning off its automatic headlight; append its
 * area lights (hidden: the scene's emitter mesh draws them, a textured
 * light's picture through ShareGeometryActor()) to `areaLights`. Returns
 * the number of triangles added.
 */
vtkIdType AddToRenderer(const mrgi_scene* scene, vtkRenderer* renderer,
  std::vector<vtkSmartPointer<vtkMRGIAreaLight>>& areaLights);
}

#endif
