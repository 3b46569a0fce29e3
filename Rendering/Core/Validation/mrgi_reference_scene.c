/* Ground-truth renderer, scene setup: the Embree device's error callback,
 * geometry upload (usable triangles only), lights and the camera frame
 * (mrgi_reference.h; shared state in mrgi_reference_internal.h). */
/* clock_gettime: POSIX.1-2008 */
#define _POSIX_C_SOURCE 200809L
#include "mrgi_reference_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- Embree setup ---- */

void mrgi_reference_embree_error_callback(void* user, enum RTCError code, const char* str)
{
  ref_embree_error* e = (ref_embree_error*)user;
  if (e->message[0] == '\0')
  {
    snprintf(e->message, sizeof(e->message), "Embree error %d: %s", (int)code, str ? str : "");
  }
}

static int ref_triangle_usable(const mrgi_mesh* mesh, int64_t t)
{
  const uint32_t* tri = mesh->indices + 3 * t;
  double c[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      c[i][k] = (double)mesh->positions[3 * (size_t)tri[i] + k];
      if (!isfinite(c[i][k]))
      {
        return 0;
      }
    }
  }
  const double e1[3] = { c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2] };
  const double e2[3] = { c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2] };
  double n[3];
  ref_cross(e1, e2, n);
  const double twice_area = sqrt(ref_dot(n, n));
  return twice_area > 0.0 && isfinite(twice_area);
}

/* Upload every mesh's usable triangles; geometry ids are 0.. in upload order. */
mrgi_status mrgi_reference_build_scene(RTCDevice device, const mrgi_scene* scene, int with_filter,
                                   const ref_embree_error* embree_error, RTCScene* out_scene,
                                   ref_geometry* geometries, int64_t* skipped, mrgi_error* err)
{
  static const char* caller = "mrgi_reference_render";
  RTCScene rtc = rtcNewScene(device);
  if (!rtc)
  {
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED, "%s: rtcNewScene failed: %s", caller,
                          embree_error->message);
  }
  /* ROBUST: no traversal shortcuts that lose accuracy (rays along shared
   * edges must not slip through); CONTEXT_FILTER: the RSM hit collector. */
  rtcSetSceneFlags(rtc, (enum RTCSceneFlags)(RTC_SCENE_FLAG_ROBUST |
                                             (with_filter ? RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION
                                                          : 0)));
  rtcSetSceneBuildQuality(rtc, RTC_BUILD_QUALITY_MEDIUM);
  *skipped = 0;
  uint32_t next_id = 0;
  for (int32_t m = 0; m < scene->mesh_count; ++m)
  {
    const mrgi_mesh* mesh = &scene->meshes[m];
    int64_t usable = 0;
    for (int64_t t = 0; t < mesh->triangle_count; ++t)
    {
      usable += ref_triangle_usable(mesh, t);
    }
    *skipped += mesh->triangle_count - usable;
    if (usable == 0)
    {
      continue;
    }
    ref_geometry* g = &geometries[next_id];
    g->mesh = mesh;
    g->emitter = mesh->emission[0] > 0.0f || mesh->emission[1] > 0.0f || mesh->emission[2] > 0.0f;
    g->triangle_of_prim = malloc((size_t)usable * sizeof(uint32_t));
    if (!g->triangle_of_prim)
    {
      rtcReleaseScene(rtc);
      return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "%s: no memory for mesh %d's triangle map",
                            caller, (int)m);
    }
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    /* Embree allocates (and pads, as its SIMD loads need) its own buffers:
     * the mesh's exactly-sized arrays cannot be shared. */
    float* vertices = geom ? rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                     RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                     (size_t)mesh->vertex_count)
                           : NULL;
    uint32_t* indices = vertices ? rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                           RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
                                                           (size_t)usable)
                                 : NULL;
    if (!indices)
    {
      if (geom)
      {
        rtcReleaseGeometry(geom);
      }
      rtcReleaseScene(rtc);
      return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "%s: Embree buffers for mesh %d: %s",
                            caller, (int)m, embree_error->message);
    }
    memcpy(vertices, mesh->positions, 3 * sizeof(float) * (size_t)mesh->vertex_count);
    int64_t k = 0;
    for (int64_t t = 0; t < mesh->triangle_count; ++t)
    {
      if (ref_triangle_usable(mesh, t))
      {
        memcpy(indices + 3 * k, mesh->indices + 3 * t, 3 * sizeof(uint32_t));
        g->triangle_of_prim[k] = (uint32_t)t;
        ++k;
      }
    }
    rtcCommitGeometry(geom);
    const unsigned int id = rtcAttachGeometry(rtc, geom);
    rtcReleaseGeometry(geom);
    if (id != next_id)
    {
      rtcReleaseScene(rtc);
      return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
                            "%s: Embree gave geometry id %u, expected %u: %s", caller, id,
                            (unsigned)next_id, embree_error->message);
    }
    ++next_id;
  }
  if (next_id == 0)
  {
    rtcReleaseScene(rtc);
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s: the scene has no usable triangles (%d meshes, %lld skipped as "
                          "degenerate or non-finite)",
                          caller, (int)scene->mesh_count, (long long)*skipped);
  }
  rtcCommitScene(rtc);
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE || embree_error->message[0])
  {
    rtcReleaseScene(rtc);
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED, "%s: building the Embree scene failed: %s",
                          caller, embree_error->message);
  }
  *out_scene = rtc;
  return MRGI_OK;
}

void mrgi_reference_setup_lights(const mrgi_scene* scene, ref_shared* shared)
{
  shared->light_count = scene->light_count;
  for (int32_t i = 0; i < scene->light_count; ++i)
  {
    const mrgi_light* in = &scene->lights[i];
    ref_light* l = &shared->lights[i];
    memset(l, 0, sizeof(*l));
    l->directional = in->type == MRGI_LIGHT_DIRECTIONAL;
    l->spot = in->type == MRGI_LIGHT_SPOT;
    for (int k = 0; k < 3; ++k)
    {
      l->position[k] = in->position[k];
      l->to_light[k] = in->position[k] - in->focal_point[k];
      l->axis[k] = in->focal_point[k] - in->position[k];
      l->rgb[k] = in->intensity * in->color[k];
    }
    ref_normalize(l->to_light);
    ref_normalize(l->axis);
    l->cos_cone = cos(in->cone_angle_deg * REF_PI / 180.0);
    l->exponent = in->exponent;
  }
}

mrgi_status mrgi_reference_setup_camera(const mrgi_camera* camera, const mrgi_reference_options* o,
                                    ref_shared* shared, mrgi_error* err)
{
  for (int k = 0; k < 3; ++k)
  {
    shared->eye[k] = camera->position[k];
    shared->forward[k] = camera->focal_point[k] - camera->position[k];
  }
  ref_normalize(shared->forward);
  /* vtkCamera: the image's right is direction_of_projection x view_up; the
   * true up is right x direction, view_up orthogonalized. */
  ref_cross(shared->forward, camera->view_up, shared->right);
  if (!(ref_normalize(shared->right) > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference_render: camera view_up is parallel to the view direction");
  }
  ref_cross(shared->right, shared->forward, shared->up);
  ref_normalize(shared->up);
  shared->aspect = (double)o->width / (double)o->height;
  shared->half_height = o->parallel_projection
                          ? o->parallel_scale
                          : tan(0.5 * camera->view_angle_deg * REF_PI / 180.0);
  return MRGI_OK;
}
