#include "mrgi_area_light_rsm.h"

#include <math.h>
#include <stddef.h>

mrgi_status mrgi_area_light_rsm_views(const mrgi_area_light* light,
                                      double directions[MRGI_AREA_LIGHT_RSM_MAX_VIEWS][3],
                                      int32_t* out_count, mrgi_error* err)
{
  if (!light || !directions || !out_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_area_light_rsm_views: light, directions or out_count is NULL");
  }
  mrgi_status status = mrgi_area_light_check(light, err);
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "mrgi_area_light_rsm_views: ");
    return status;
  }
  const double* u = light->edge_u;
  const double* v = light->edge_v;
  const double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                        u[0] * v[1] - u[1] * v[0] };
  const double ln = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const double lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  const double lv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  const int32_t count = light->two_sided ? 6 : 5;
  for (int k = 0; k < 3; ++k)
  {
    directions[0][k] = n[k] / ln;
    directions[1][k] = u[k] / lu;
    directions[2][k] = -u[k] / lu;
    directions[3][k] = v[k] / lv;
    directions[4][k] = -v[k] / lv;
    if (count == 6)
    {
      directions[5][k] = -n[k] / ln;
    }
  }
  *out_count = count;
  return MRGI_OK;
}

void mrgi_area_light_rsm_texel(const mrgi_area_light_uniforms* light,
                               const mrgi_area_light_sample* samples, int32_t count,
                               const float position[3], const float normal[3],
                               const float albedo[3], float area, float flux[3])
{
  float x[3];
  mrgi_area_light_diffuse(light, samples, count, position, normal, x);
  for (int c = 0; c < 3; ++c)
  {
    flux[c] = albedo[c] * x[c] * area;
  }
}
