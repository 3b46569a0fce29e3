/* Ground-truth renderer: Embree 3 ray casting of direct light and one diffuse
 * bounce in VTK's lighting model. The contract is in mrgi_reference.h; this
 * file has the options, threads, passes and results;
 * mrgi_reference_scene.c the geometry upload, lights and camera, and
 * mrgi_reference_kernel.c the per-pixel kernel. */
/* clock_gettime, sysconf(_SC_NPROCESSORS_ONLN): POSIX.1-2008 */
#define _POSIX_C_SOURCE 200809L
#include "mrgi_reference_internal.h"
#include "mrgi_reference_noise.h"

#include <embree3/rtcore.h>

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* ---- options ---- */

void mrgi_reference_options_default(mrgi_reference_options* options)
{
  if (!options)
  {
    return;
  }
  memset(options, 0, sizeof(*options));
  options->width = 256;
  options->height = 256;
  options->pixel_samples = 1;
  options->pixel_filter = MRGI_REFERENCE_PIXEL_BOX;
  options->indirect_samples = 16;
  options->target_relative_error = MRGI_REFERENCE_DEFAULT_TARGET;
  options->target_percentile = MRGI_REFERENCE_DEFAULT_PERCENTILE;
  options->max_passes = MRGI_REFERENCE_DEFAULT_MAX_PASSES;
  options->max_seconds = 0.0;
  options->shadows = 1;
  options->secondary_visibility = 1;
  options->shading_normals = 1;
  options->parallel_projection = 0;
  options->parallel_scale = 1.0;
  options->seed = 1;
  options->threads = 0;
  options->area_light_samples = 16;
}

static mrgi_status ref_check_int(const char* name, int32_t value, int32_t lo, int32_t hi,
                                 mrgi_error* err)
{
  if (value < lo || value > hi)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference: option %s = %d is outside %d..%d", name, (int)value,
                          (int)lo, (int)hi);
  }
  return MRGI_OK;
}

mrgi_status mrgi_reference_options_validate(const mrgi_reference_options* o, mrgi_error* err)
{
  if (!o)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_reference: options is NULL");
  }
  mrgi_status s = ref_check_int("width", o->width, 1, MRGI_REFERENCE_MAX_DIMENSION, err);
  if (!s)
    s = ref_check_int("height", o->height, 1, MRGI_REFERENCE_MAX_DIMENSION, err);
  if (!s)
    s = ref_check_int("pixel_samples", o->pixel_samples, 1, MRGI_REFERENCE_MAX_PIXEL_SAMPLES, err);
  if (!s)
    s = ref_check_int("pixel_filter", o->pixel_filter, MRGI_REFERENCE_PIXEL_BOX,
                      MRGI_REFERENCE_PIXEL_CENTER, err);
  if (!s)
    s = ref_check_int("indirect_samples", o->indirect_samples, 0,
                      MRGI_REFERENCE_MAX_INDIRECT_SAMPLES, err);
  if (!s)
    s = ref_check_int("max_passes", o->max_passes, 1, MRGI_REFERENCE_MAX_PASSES, err);
  if (!s)
    s = ref_check_int("shadows", o->shadows, 0, 1, err);
  if (!s)
    s = ref_check_int("secondary_visibility", o->secondary_visibility, 0, 1, err);
  if (!s)
    s = ref_check_int("shading_normals", o->shading_normals, 0, 1, err);
  if (!s)
    s = ref_check_int("parallel_projection", o->parallel_projection, 0, 1, err);
  if (!s)
    s = ref_check_int("threads", o->threads, 0, MRGI_REFERENCE_MAX_THREADS, err);
  if (!s)
    s = ref_check_int("area_light_samples", o->area_light_samples, 0,
                      MRGI_REFERENCE_MAX_AREA_LIGHT_SAMPLES, err);
  if (s)
  {
    return s;
  }
  if (!(isfinite(o->target_relative_error) && o->target_relative_error >= 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference: option target_relative_error = %g is not finite and >= 0",
                          o->target_relative_error);
  }
  if (!(o->target_percentile > 0.0 && o->target_percentile <= 1.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference: option target_percentile = %g is outside (0, 1]",
                          o->target_percentile);
  }
  if (!(isfinite(o->max_seconds) && o->max_seconds >= 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference: option max_seconds = %g is not finite and >= 0",
                          o->max_seconds);
  }
  if (o->parallel_projection && !(isfinite(o->parallel_scale) && o->parallel_scale > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference: option parallel_scale = %g is not finite and > 0",
                          o->parallel_scale);
  }
  return MRGI_OK;
}

/* ---- result ---- */

void mrgi_reference_result_destroy(mrgi_reference_result* result)
{
  if (!result)
  {
    return;
  }
  mrgi_image_destroy(&result->direct);
  mrgi_image_destroy(&result->indirect);
  mrgi_image_destroy(&result->albedo);
  mrgi_image_destroy(&result->indirect_stderr);
  mrgi_image_destroy(&result->direct_stderr);
  free(result->background);
  memset(result, 0, sizeof(*result));
}

/* Noise of the per-pass estimates (mean, m2) after `passes` passes
 * (definitions in the header); `enabled` = 0: known exactly. */
static void ref_noise_of(const ref_shared* shared, const double* est_mean, const double* est_m2,
                         int enabled, int32_t passes, double* relative, double* per_pixel)
{
  const size_t count = (size_t)shared->options.width * (size_t)shared->options.height;
  double sum_mean = 0.0, sum_var = 0.0;
  size_t lit = 0;
  for (size_t i = 0; i < count; ++i)
  {
    if (!shared->hit[i])
    {
      continue;
    }
    ++lit;
    sum_mean += est_mean[i];
    if (passes > 1)
    {
      sum_var += est_m2[i] / ((double)(passes - 1) * (double)passes);
    }
  }
  if (!enabled || !(sum_mean > 0.0))
  {
    *relative = 0.0;
    *per_pixel = 0.0;
    return;
  }
  if (passes < 2)
  {
    *relative = INFINITY;
    *per_pixel = INFINITY;
    return;
  }
  *relative = sqrt(sum_var) / sum_mean;
  *per_pixel = *relative * sqrt((double)lit);
}

/* Noise of the indirect (relative_error, pixel_relative_error). */
static void ref_noise(const ref_shared* shared, int32_t passes, double* relative,
                      double* per_pixel)
{
  ref_noise_of(shared, shared->est_mean, shared->est_m2, shared->options.indirect_samples != 0,
               passes, relative, per_pixel);
}

/* Noise of the direct image: area lights only (direct_relative_error). */
static double ref_direct_noise(const ref_shared* shared, int32_t passes)
{
  double relative = 0.0, per_pixel = 0.0;
  if (shared->dir_mean)
  {
    ref_noise_of(shared, shared->dir_mean, shared->dir_m2, 1, passes, &relative, &per_pixel);
  }
  return relative;
}

/* The stopping statistic (mrgi_reference_noise.h) of the per-pass estimates
 * (mean, m2); `enabled` = 0 or NULL accumulators: known exactly, 0. The
 * arguments were checked when the call began, so this cannot fail. */
static double ref_pixel_error_of(const ref_shared* shared, const double* est_mean,
                                 const double* est_m2, int enabled, int32_t passes)
{
  if (!enabled || !est_mean)
  {
    return 0.0;
  }
  const size_t count = (size_t)shared->options.width * (size_t)shared->options.height;
  double error = INFINITY;
  if (mrgi_reference_pixel_error(est_mean, est_m2, shared->hit, count, passes,
                                 shared->options.target_percentile, shared->noise_scratch,
                                 &error, NULL) != MRGI_OK)
  {
    return INFINITY; /* unreachable: keeps rendering rather than stopping on a bad value */
  }
  return error;
}

static int32_t ref_thread_count(const mrgi_reference_options* o)
{
  int64_t n = o->threads;
  if (n == 0)
  {
    const long online = sysconf(_SC_NPROCESSORS_ONLN);
    n = online > 0 ? online : 1;
  }
  if (n > MRGI_REFERENCE_MAX_THREADS)
  {
    n = MRGI_REFERENCE_MAX_THREADS;
  }
  if (n > o->height)
  {
    n = o->height;
  }
  return (int32_t)n;
}

/* Everything one call owns, released in one place. */
typedef struct ref_call
{
  RTCDevice device;
  RTCScene rtc;
  ref_geometry* geometries;
  int32_t geometry_slots;
  ref_worker* workers;
  pthread_t* thread_ids;
  ref_hit_record* hit_storage;
  ref_shared shared;
} ref_call;

static void ref_call_release(ref_call* c)
{
  if (c->rtc)
  {
    rtcReleaseScene(c->rtc);
  }
  if (c->device)
  {
    rtcReleaseDevice(c->device);
  }
  for (int32_t i = 0; c->geometries && i < c->geometry_slots; ++i)
  {
    free(c->geometries[i].triangle_of_prim);
  }
  free(c->geometries);
  free(c->workers);
  free(c->thread_ids);
  free(c->hit_storage);
  free(c->shared.sums);
  free(c->shared.est_mean);
  free(c->shared.est_m2);
  free(c->shared.dir_mean);
  free(c->shared.dir_m2);
  free(c->shared.hit);
  free(c->shared.noise_scratch);
}

/* Run one pass with `thread_count` workers; the calling thread is worker 0.
 * A thread that cannot be started just leaves its rows to the others. */
static void ref_run_pass(ref_call* c, int32_t thread_count)
{
  atomic_store(&c->shared.next_row, 0);
  int32_t started = 0;
  for (int32_t i = 1; i < thread_count; ++i)
  {
    if (pthread_create(&c->thread_ids[started], NULL, mrgi_reference_worker_run, &c->workers[i]) == 0)
    {
      ++started;
    }
  }
  mrgi_reference_worker_run(&c->workers[0]);
  for (int32_t i = 0; i < started; ++i)
  {
    pthread_join(c->thread_ids[i], NULL);
  }
}

/* Fills a progress report after `passes` passes that took `pass_seconds`
 * (the Embree build not included). The stopping statistic (the worse of
 * the indirect's and the direct's pixel_error) falls as 1/sqrt(passes): the
 * target is expected after passes * (worst / target)^2 passes. */
static void ref_progress(const mrgi_reference_options* o, int32_t passes, double relative,
  double direct_relative, double pixel, double direct_pixel, double seconds, double pass_seconds,
  mrgi_reference_progress* p)
{
  const double worst = direct_pixel > pixel ? direct_pixel : pixel;
  double expected = (double)o->max_passes;
  if (o->target_relative_error > 0.0 && isfinite(worst))
  {
    const double ratio = worst / o->target_relative_error;
    const double needed = worst == 0.0 ? (double)passes : (double)passes * ratio * ratio;
    /* The loop stops after pass 2 at the earliest (file comment). */
    const double at_least = worst == 0.0 ? (double)passes : 2.0;
    expected = needed < expected ? needed : expected;
    expected = expected < at_least ? at_least : expected;
  }
  if (expected < (double)passes)
  {
    expected = (double)passes;
  }
  p->passes = passes;
  p->max_passes = o->max_passes;
  p->relative_error = relative;
  p->direct_relative_error = direct_relative;
  p->pixel_error = pixel;
  p->direct_pixel_error = direct_pixel;
  p->target_relative_error = o->target_relative_error;
  p->seconds = seconds;
  p->passes_expected = expected;
  p->fraction = (double)passes / expected;
  p->seconds_left = (expected - (double)passes) * (pass_seconds / (double)passes);
}

static mrgi_status ref_write_images(const ref_call* c, int32_t passes, mrgi_reference_result* out,
                                    mrgi_error* err)
{
  const mrgi_reference_options* o = &c->shared.options;
  mrgi_status s = mrgi_image_create(&out->direct, o->width, o->height, 3, err);
  if (!s)
    s = mrgi_image_create(&out->indirect, o->width, o->height, 3, err);
  if (!s)
    s = mrgi_image_create(&out->albedo, o->width, o->height, 3, err);
  if (!s)
    s = mrgi_image_create(&out->indirect_stderr, o->width, o->height, 1, err);
  if (!s)
    s = mrgi_image_create(&out->direct_stderr, o->width, o->height, 1, err);
  if (s)
  {
    return s;
  }
  const size_t count = (size_t)o->width * (size_t)o->height;
  out->background = calloc(count, 1);
  if (!out->background)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "mrgi_reference_render: no memory for the background mask");
  }
  const double scale = 1.0 / ((double)passes * (double)o->pixel_samples);
  for (size_t i = 0; i < count; ++i)
  {
    const double* sums = c->shared.sums + 9 * i;
    for (int k = 0; k < 3; ++k)
    {
      out->direct.pixels[3 * i + k] = (float)(sums[k] * scale);
      out->indirect.pixels[3 * i + k] = (float)(sums[3 + k] * scale);
      out->albedo.pixels[3 * i + k] = (float)(sums[6 + k] * scale);
    }
    out->background[i] = !c->shared.hit[i];
    const double var_of_mean =
      passes > 1 ? c->shared.est_m2[i] / ((double)(passes - 1) * (double)passes) : 0.0;
    out->indirect_stderr.pixels[i] = (float)sqrt(var_of_mean > 0.0 ? var_of_mean : 0.0);
    if (c->shared.dir_mean && passes > 1)
    {
      const double direct_var = c->shared.dir_m2[i] / ((double)(passes - 1) * (double)passes);
      out->direct_stderr.pixels[i] = (float)sqrt(direct_var > 0.0 ? direct_var : 0.0);
    }
  }
  return MRGI_OK;
}

/* Reduce the (checked) area lights to ref_area_light records. */
static void ref_setup_area_lights(const mrgi_area_light* lights, int32_t count,
                                  int32_t samples, ref_shared* shared)
{
  shared->area_light_count = count;
  for (int32_t i = 0; i < count; ++i)
  {
    const mrgi_area_light* in = &lights[i];
    ref_area_light* a = &shared->area_lights[i];
    memset(a, 0, sizeof(*a));
    a->light = in;
    memcpy(a->center, in->center, sizeof(a->center));
    memcpy(a->edge_u, in->edge_u, sizeof(a->edge_u));
    memcpy(a->edge_v, in->edge_v, sizeof(a->edge_v));
    ref_cross(in->edge_u, in->edge_v, a->normal);
    const double area = ref_normalize(a->normal);
    int32_t cells_u = 1, cells_v = 1;
    /* cannot fail: light and count were checked by the caller */
    mrgi_area_light_sample_layout(in, samples, &cells_u, &cells_v, NULL, NULL);
    a->cells_u = cells_u;
    a->cells_v = cells_v;
    a->weight = area / (REF_PI * (double)cells_u * (double)cells_v);
    a->two_sided = in->two_sided != 0;
  }
}

mrgi_status mrgi_reference_render(const mrgi_scene* scene, const mrgi_reference_options* options,
                                  mrgi_reference_result* out, mrgi_error* err)
{
  return mrgi_reference_render_area_lights(scene, options, NULL, 0, out, err);
}

mrgi_status mrgi_reference_render_area_lights(const mrgi_scene* scene,
                                              const mrgi_reference_options* options,
                                              const mrgi_area_light* area_lights,
                                              int32_t area_light_count,
                                              mrgi_reference_result* out, mrgi_error* err)
{
  static const char* caller = "mrgi_reference_render";
  const double start = ref_seconds_now();
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: out is NULL", caller);
  }
  memset(out, 0, sizeof(*out));
  if (!scene)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: scene is NULL", caller);
  }
  mrgi_status status = mrgi_reference_options_validate(options, err);
  if (status)
  {
    return status;
  }
  status = mrgi_scene_validate(scene, err);
  if (status)
  {
    mrgi_error_prefix(err, "%s: ", caller);
    return status;
  }
  if (mrgi_scene_triangle_count(scene) == 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: the scene has no triangles",
                          caller);
  }
  if (area_light_count < 0 || area_light_count > MRGI_REFERENCE_MAX_AREA_LIGHTS ||
      (area_light_count > 0 && !area_lights))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s: area_light_count %d is outside 0..%d or the area lights are NULL",
                          caller, (int)area_light_count, MRGI_REFERENCE_MAX_AREA_LIGHTS);
  }
  for (int32_t i = 0; i < area_light_count; ++i)
  {
    status = mrgi_area_light_check(&area_lights[i], err);
    if (status)
    {
      mrgi_error_prefix(err, "%s: area light %d: ", caller, (int)i);
      return status;
    }
  }
  if (area_light_count > 0 && options->area_light_samples < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s: option area_light_samples = %d, but %d area lights are to be "
                          "rendered (1..%d needed)",
                          caller, (int)options->area_light_samples, (int)area_light_count,
                          MRGI_REFERENCE_MAX_AREA_LIGHT_SAMPLES);
  }

  ref_call c;
  memset(&c, 0, sizeof(c));
  c.shared.options = *options;
  status = mrgi_reference_setup_camera(&scene->camera, options, &c.shared, err);
  if (status)
  {
    return status;
  }
  mrgi_reference_setup_lights(scene, &c.shared);
  ref_setup_area_lights(area_lights, area_light_count, options->area_light_samples, &c.shared);
  double bounds[6];
  status = mrgi_scene_bounds(scene, bounds, err);
  if (status)
  {
    mrgi_error_prefix(err, "%s: ", caller);
    return status;
  }
  double extent = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const double e = bounds[2 * k + 1] - bounds[2 * k];
    extent = e > extent ? e : extent;
  }
  c.shared.epsilon_floor = 0.01 * extent;

  const int32_t thread_count = ref_thread_count(options);
  const size_t count = (size_t)options->width * (size_t)options->height;
  c.geometry_slots = scene->mesh_count;
  c.geometries = calloc((size_t)scene->mesh_count, sizeof(ref_geometry));
  c.workers = calloc((size_t)thread_count, sizeof(ref_worker));
  c.thread_ids = calloc((size_t)thread_count, sizeof(pthread_t));
  c.hit_storage =
    calloc((size_t)thread_count * MRGI_REFERENCE_MAX_RAY_HITS, sizeof(ref_hit_record));
  c.shared.sums = calloc(9 * count, sizeof(double));
  c.shared.est_mean = calloc(count, sizeof(double));
  c.shared.est_m2 = calloc(count, sizeof(double));
  c.shared.hit = calloc(count, 1);
  c.shared.noise_scratch = malloc(count * sizeof(double));
  if (area_light_count > 0)
  {
    c.shared.dir_mean = calloc(count, sizeof(double));
    c.shared.dir_m2 = calloc(count, sizeof(double));
  }
  if (!c.geometries || !c.workers || !c.thread_ids || !c.hit_storage || !c.shared.sums ||
      !c.shared.est_mean || !c.shared.est_m2 || !c.shared.hit || !c.shared.noise_scratch ||
      (area_light_count > 0 && (!c.shared.dir_mean || !c.shared.dir_m2)))
  {
    ref_call_release(&c);
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "%s: no memory for %dx%d accumulation buffers", caller,
                          (int)options->width, (int)options->height);
  }

  ref_embree_error embree_error;
  memset(&embree_error, 0, sizeof(embree_error));
  c.device = rtcNewDevice(NULL);
  if (!c.device)
  {
    ref_call_release(&c);
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED, "%s: rtcNewDevice failed (Embree error %d)",
                          caller, (int)rtcGetDeviceError(NULL));
  }
  rtcSetDeviceErrorFunction(c.device, mrgi_reference_embree_error_callback, &embree_error);
  if (!options->secondary_visibility &&
      !rtcGetDeviceProperty(c.device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED))
  {
    ref_call_release(&c);
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
                          "%s: secondary_visibility = 0 needs Embree filter functions, and this "
                          "Embree was built without them",
                          caller);
  }
  const double build_start = ref_seconds_now();
  status = mrgi_reference_build_scene(c.device, scene, !options->secondary_visibility, &embree_error, &c.rtc,
                           c.geometries, &out->skipped_triangles, err);
  if (status)
  {
    ref_call_release(&c);
    return status;
  }
  out->build_seconds = ref_seconds_now() - build_start;
  c.shared.rtc = c.rtc;
  c.shared.geometries = c.geometries;
  for (int32_t i = 0; i < thread_count; ++i)
  {
    c.workers[i].shared = &c.shared;
    c.workers[i].hits = c.hit_storage + (size_t)i * MRGI_REFERENCE_MAX_RAY_HITS;
  }

  int32_t passes = 0;
  int32_t cancelled = 0;
  double relative = INFINITY, per_pixel = INFINITY, direct_relative = INFINITY;
  double pixel = INFINITY, direct_pixel = INFINITY;
  const double passes_start = ref_seconds_now();
  while (passes < options->max_passes)
  {
    c.shared.pass = passes;
    ref_run_pass(&c, thread_count);
    ++passes;
    ref_noise(&c.shared, passes, &relative, &per_pixel);
    direct_relative = ref_direct_noise(&c.shared, passes); /* 0 without area lights */
    /* The stopping rule: per pixel (mrgi_reference_noise.h), on the direct
     * image too when area lights make it noisy. */
    pixel = ref_pixel_error_of(&c.shared, c.shared.est_mean, c.shared.est_m2,
                               options->indirect_samples != 0, passes);
    direct_pixel = ref_pixel_error_of(&c.shared, c.shared.dir_mean, c.shared.dir_m2, 1, passes);
    const double worst = direct_pixel > pixel ? direct_pixel : pixel;
    if (options->progress)
    {
      mrgi_reference_progress p;
      ref_progress(options, passes, relative, direct_relative, pixel, direct_pixel,
        ref_seconds_now() - start,
        ref_seconds_now() - passes_start, &p);
      if (options->progress(options->progress_user_data, &p) != 0)
      {
        cancelled = 1;
        break;
      }
    }
    if (options->target_relative_error > 0.0 && worst <= options->target_relative_error &&
        (passes >= 2 || worst == 0.0))
    {
      break;
    }
    if (options->max_seconds > 0.0 && ref_seconds_now() - start >= options->max_seconds)
    {
      break;
    }
  }
  for (int32_t i = 0; i < thread_count; ++i)
  {
    out->rays_traced += c.workers[i].rays;
    out->hit_list_overflows += c.workers[i].overflows;
  }
  const int64_t skipped = out->skipped_triangles;
  const double build_seconds = out->build_seconds;
  const int64_t rays = out->rays_traced, overflows = out->hit_list_overflows;
  status = ref_write_images(&c, passes, out, err);
  ref_call_release(&c);
  if (status)
  {
    mrgi_reference_result_destroy(out);
    return status;
  }
  out->skipped_triangles = skipped;
  out->build_seconds = build_seconds;
  out->rays_traced = rays;
  out->hit_list_overflows = overflows;
  out->relative_error = relative;
  out->pixel_relative_error = per_pixel;
  out->direct_relative_error = direct_relative;
  out->pixel_error = pixel;
  out->direct_pixel_error = direct_pixel;
  out->passes = passes;
  out->cancelled = cancelled;
  out->threads = thread_count;
  out->seconds = ref_seconds_now() - start;
  return MRGI_OK;
}
