/* Display colours of LAS points: see mrgi_las_colors.h. */
#include "mrgi_las_colors.h"

#include <math.h>
#include <stdlib.h>

/* Classes 0..22 of LAS 1.4 R15 (table 17); the names are the standard's. */
static const uint8_t class_colors[23][3] = {
  { 190, 190, 190 }, /* 0 created, never classified */
  { 150, 150, 150 }, /* 1 unclassified */
  { 160, 110, 60 },  /* 2 ground */
  { 150, 210, 110 }, /* 3 low vegetation */
  { 70, 170, 60 },   /* 4 medium vegetation */
  { 20, 110, 30 },   /* 5 high vegetation */
  { 200, 60, 50 },   /* 6 building */
  { 255, 0, 255 },   /* 7 low point (noise) */
  { 255, 220, 0 },   /* 8 reserved (model key-point before 1.4) */
  { 40, 110, 220 },  /* 9 water */
  { 130, 80, 130 },  /* 10 rail */
  { 80, 80, 80 },    /* 11 road surface */
  { 230, 230, 110 }, /* 12 reserved (overlap before 1.4) */
  { 255, 255, 200 }, /* 13 wire - guard (shield) */
  { 255, 190, 0 },   /* 14 wire - conductor (phase) */
  { 160, 160, 210 }, /* 15 transmission tower */
  { 200, 160, 255 }, /* 16 wire-structure connector */
  { 170, 170, 120 }, /* 17 bridge deck */
  { 255, 0, 128 },   /* 18 high noise */
  { 250, 150, 100 }, /* 19 overhead structure */
  { 190, 150, 110 }, /* 20 ignored ground */
  { 240, 248, 255 }, /* 21 snow */
  { 200, 200, 140 }, /* 22 temporal exclusion */
};

void mrgi_las_classification_color(int classification, uint8_t rgb[3])
{
  static const uint8_t other[3] = { 128, 128, 128 };
  const uint8_t* c =
    (classification >= 0 && classification < 23) ? class_colors[classification] : other;
  rgb[0] = c[0];
  rgb[1] = c[1];
  rgb[2] = c[2];
}

mrgi_las_color_mode mrgi_las_auto_color_mode(const mrgi_las_points* points)
{
  if (!points || points->colors)
  {
    return MRGI_LAS_COLOR_RGB;
  }
  for (int64_t i = 0; i < points->count; ++i)
  {
    if (points->classification[i] > 1)
    {
      return MRGI_LAS_COLOR_CLASSIFICATION;
    }
  }
  return MRGI_LAS_COLOR_INTENSITY;
}

/* The intensity at cumulative fraction `f` of the histogram (nearest rank,
 * so that 3 points keep their 3 greys). */
static int percentile(const int64_t* histogram, int64_t count, double f)
{
  const int64_t target = (int64_t)floor(f * (double)(count - 1) + 0.5);
  int64_t seen = 0;
  for (int v = 0; v < 65536; ++v)
  {
    seen += histogram[v];
    if (seen > target)
    {
      return v;
    }
  }
  return 65535;
}

mrgi_status mrgi_las_colorize(const mrgi_las_points* points, mrgi_las_color_mode mode, uint8_t* rgb,
  mrgi_las_color_mode* used, mrgi_error* err)
{
  if (!points || points->count < 1 || !points->positions || !rgb)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "LAS colours: no points or no output");
  }
  if (mode == MRGI_LAS_COLOR_AUTO)
  {
    mode = mrgi_las_auto_color_mode(points);
  }
  const size_t n = (size_t)points->count;
  switch (mode)
  {
    case MRGI_LAS_COLOR_RGB:
      if (!points->colors)
      {
        return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
          "LAS colours: RGB asked for, but the point format has no RGB");
      }
      for (size_t i = 0; i < 3 * n; ++i)
      {
        const float c = points->colors[i];
        rgb[i] = (uint8_t)(c <= 0.0f ? 0 : c >= 1.0f ? 255 : (int)lrintf(c * 255.0f));
      }
      break;
    case MRGI_LAS_COLOR_CLASSIFICATION:
      for (size_t i = 0; i < n; ++i)
      {
        mrgi_las_classification_color(points->classification[i], rgb + 3 * i);
      }
      break;
    case MRGI_LAS_COLOR_INTENSITY:
    {
      int64_t* histogram = (int64_t*)calloc(65536, sizeof(int64_t));
      if (!histogram)
      {
        return mrgi_error_set(
          err, MRGI_ERR_OUT_OF_MEMORY, "LAS colours: no memory for a histogram");
      }
      for (size_t i = 0; i < n; ++i)
      {
        ++histogram[points->intensity[i]];
      }
      const int lo = percentile(histogram, points->count, 0.02);
      const int hi = percentile(histogram, points->count, 0.98);
      free(histogram);
      for (size_t i = 0; i < n; ++i)
      {
        uint8_t g = 204;
        if (hi > lo)
        {
          double t = ((double)points->intensity[i] - lo) / (double)(hi - lo);
          t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
          g = (uint8_t)lrint(255.0 * (0.15 + 0.85 * t));
        }
        rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = g;
      }
      break;
    }
    default:
      return mrgi_error_set(
        err, MRGI_ERR_INVALID_ARGUMENT, "LAS colours: unknown mode %d", (int)mode);
  }
  if (used)
  {
    *used = mode;
  }
  mrgi_error_clear(err);
  return MRGI_OK;
}
