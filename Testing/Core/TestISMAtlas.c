/* Tests of mrgi_ism_atlas (RGK08 3.3, RIHKS11 6.1): layout sizes, the
 * cos-sphere map round-trips and is equal-area in projected solid angle
 * (Monte Carlo, bounded error), texels are deterministic and in the VPL's
 * tile, push-pull fills every hole of a non-empty tile from that tile only,
 * and absurd sizes give clear errors. */
#include "mrgi_ism_atlas.h"
#include "mrgi_vpl.h"
#include "mrgi_test.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const double pi = 3.14159265358979323846;

static uint32_t rng_state = 12345u;
static double rnd(void)
{
  rng_state = rng_state * 1664525u + 1013904223u;
  return (rng_state >> 8) * (1.0 / 16777216.0);
}

static void random_unit(double d[3])
{
  const double z = 2.0 * rnd() - 1.0, ph = 2.0 * pi * rnd(), r = sqrt(1.0 - z * z);
  d[0] = r * cos(ph);
  d[1] = r * sin(ph);
  d[2] = z;
}

static void test_layout(void)
{
  mrgi_ism_atlas_layout L;
  MRGI_CHECK(mrgi_ism_atlas_layout_make(1024, 64, &L, NULL) == MRGI_OK);
  MRGI_CHECK(L.tiles_per_row == 32 && L.tile_rows == 32 && L.width == 2048 && L.height == 2048);
  MRGI_CHECK(mrgi_ism_atlas_layout_make(5, 32, &L, NULL) == MRGI_OK);
  MRGI_CHECK(L.tiles_per_row == 3 && L.tile_rows == 2 && L.width == 96 && L.height == 64);
  MRGI_CHECK(mrgi_ism_point_vpl(17, 5) == 2 && mrgi_ism_point_vpl(-1, 5) == -1);
}

/* Round trip, and disk area of 4 x 4 texel blocks == projected solid angle. */
static void test_cos_sphere(void)
{
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i)
  {
    double n[3], d[3], st[2], back[3];
    random_unit(n);
    random_unit(d);
    if (!mrgi_ism_cos_sphere_forward(n, d, st))
    {
      MRGI_CHECK(n[0] * d[0] + n[1] * d[1] + n[2] * d[2] < 0.0);
      continue;
    }
    MRGI_CHECK(st[0] * st[0] + st[1] * st[1] <= 1.0 + 1e-12);
    mrgi_ism_cos_sphere_inverse(n, st, back);
    for (int k = 0; k < 3; ++k)
    {
      const double e = fabs(back[k] - d[k]);
      worst = e > worst ? e : worst;
    }
  }
  printf("round trip: worst component error %.2e\n", worst);
  MRGI_CHECK(worst < 1e-9);
  /* Projected solid angle of the directions landing in each of 4 x 4 cells,
   * by uniform hemisphere sampling (weight 2 pi cos / N), against the cell's
   * area inside the unit disk (fine grid). N = 400000: sigma < 0.003, bound 0.02. */
  const double n[3] = { 0.3, -0.5, 0.8 };
  const double len = sqrt(0.09 + 0.25 + 0.64);
  const double nn[3] = { n[0] / len, n[1] / len, n[2] / len };
  double psa[16] = { 0 }, area[16] = { 0 };
  const int N = 400000;
  for (int i = 0; i < N; ++i)
  {
    double d[3], st[2];
    random_unit(d);
    const double c = d[0] * nn[0] + d[1] * nn[1] + d[2] * nn[2];
    if (c < 0.0)
    {
      d[0] = -d[0], d[1] = -d[1], d[2] = -d[2];
    }
    MRGI_CHECK(mrgi_ism_cos_sphere_forward(nn, d, st));
    const int x = (int)floor((st[0] + 1.0) * 2.0), y = (int)floor((st[1] + 1.0) * 2.0);
    psa[(y > 3 ? 3 : y) * 4 + (x > 3 ? 3 : x)] += 2.0 * pi * fabs(c) / N;
  }
  const int G = 800;
  for (int j = 0; j < G; ++j)
    for (int i = 0; i < G; ++i)
    {
      const double s = -1.0 + (i + 0.5) * 2.0 / G, t = -1.0 + (j + 0.5) * 2.0 / G;
      if (s * s + t * t <= 1.0)
        area[(int)((t + 1.0) * 2.0) * 4 + (int)((s + 1.0) * 2.0)] += 4.0 / ((double)G * G);
    }
  double werr = 0.0;
  for (int k = 0; k < 16; ++k)
    werr = fabs(psa[k] - area[k]) > werr ? fabs(psa[k] - area[k]) : werr;
  printf("equal area: worst |projected solid angle - disk area| over 16 cells %.4f"
         " (cells up to %.3f)\n",
    werr, area[5]);
  MRGI_CHECK(werr < 0.02);
}

static void test_texels(void)
{
  mrgi_ism_atlas_layout L;
  MRGI_CHECK(mrgi_ism_atlas_layout_make(7, 16, &L, NULL) == MRGI_OK);
  int landed = 0;
  for (int i = 0; i < 5000; ++i)
  {
    const int32_t l = mrgi_ism_point_vpl(i, 7);
    double vp[3], vn[3], p[3];
    random_unit(vn);
    for (int k = 0; k < 3; ++k)
    {
      vp[k] = rnd();
      p[k] = 2.0 * rnd() - 0.5;
    }
    int64_t tex = -1, tex2 = -1;
    float dep = 0.0f, dep2 = 0.0f;
    const int hit = mrgi_ism_point_texel(&L, l, vp, vn, p, &tex, &dep);
    MRGI_CHECK(hit == mrgi_ism_point_texel(&L, l, vp, vn, p, &tex2, &dep2));
    if (!hit)
      continue;
    ++landed;
    MRGI_CHECK(tex == tex2 && dep == dep2);
    const int64_t X = tex % L.width, Y = tex / L.width;
    MRGI_CHECK(X / L.tile_size == l % L.tiles_per_row && Y / L.tile_size == l / L.tiles_per_row);
    const double dx = p[0] - vp[0], dy = p[1] - vp[1], dz = p[2] - vp[2];
    MRGI_CHECK_NEAR(dep, sqrt(dx * dx + dy * dy + dz * dz), 1e-5);
  }
  MRGI_CHECK(landed > 1000);
  /* The normal direction lands in the tile's centre texels. */
  const double o[3] = { 0, 0, 0 }, z[3] = { 0, 0, 1 }, up[3] = { 0, 0, 2 };
  int64_t tex;
  MRGI_CHECK(mrgi_ism_point_texel(&L, 0, o, z, up, &tex, NULL));
  MRGI_CHECK(tex == 8 * L.width + 8);
}

static float atlas[96 * 64];
static float scratch[2048];

static void test_push_pull(void)
{
  mrgi_ism_atlas_layout L;
  MRGI_CHECK(mrgi_ism_atlas_layout_make(5, 32, &L, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_ism_push_pull_scratch_size(&L) <= sizeof(scratch) / sizeof(float));
  for (int i = 0; i < L.width * L.height; ++i)
    atlas[i] = MRGI_ISM_EMPTY_DEPTH;
  /* Tile l holds depths in [l + 1, l + 1.5); tile 3 has one texel; tiles 4
   * and 5 (5 = unused slot) none. */
  const int counts[5] = { 40, 200, 3, 1, 0 };
  for (int l = 0; l < 5; ++l)
    for (int k = 0; k < counts[l]; ++k)
    {
      const int x = (int)(rnd() * 32), y = (int)(rnd() * 32);
      atlas[((l / 3) * 32 + y) * L.width + (l % 3) * 32 + x] = (float)(l + 1 + 0.5 * rnd());
    }
  static float before[96 * 64];
  memcpy(before, atlas, sizeof(atlas));
  mrgi_error err;
  const size_t room = sizeof(scratch) / sizeof(float);
  MRGI_CHECK(mrgi_ism_push_pull(&L, atlas, 1, scratch, 10, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_ism_push_pull(&L, atlas, 0, scratch, room, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "push-pull levels") != NULL);
  MRGI_CHECK(mrgi_ism_push_pull(&L, atlas, MRGI_ISM_MAX_PUSH_PULL_LEVELS + 1, scratch, room, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);

  /* One level: a hole is filled exactly when its 2x2 block holds a valid
   * texel, with the mean of the block's valid depths (summed in the block's
   * order, section 4); valid texels keep their depth. */
  MRGI_CHECK(mrgi_ism_push_pull(&L, atlas, 1, scratch, room, &err) == MRGI_OK);
  int filled = 0;
  for (int Y = 0; Y < L.height; ++Y)
    for (int X = 0; X < L.width; ++X)
    {
      const int bx = X & ~1, by = Y & ~1;
      const float q[4] = { before[by * L.width + bx], before[by * L.width + bx + 1],
        before[(by + 1) * L.width + bx], before[(by + 1) * L.width + bx + 1] };
      float sum = 0.0f;
      int count = 0;
      for (int i = 0; i < 4; ++i)
        if (q[i] < MRGI_ISM_EMPTY_DEPTH)
        {
          sum += q[i];
          ++count;
        }
      const float own = before[Y * L.width + X];
      const float expected = own < MRGI_ISM_EMPTY_DEPTH ? own
        : count > 0                                    ? sum / (float)count
                                                       : MRGI_ISM_EMPTY_DEPTH;
      MRGI_CHECK(atlas[Y * L.width + X] == expected);
      filled += !(own < MRGI_ISM_EMPTY_DEPTH) && count > 1;
    }
  MRGI_CHECK(filled > 0); /* some holes got a mean of two or more depths */

  /* All levels: every texel of a tile with a valid texel is filled from
   * its own tile; empty tiles stay empty. */
  memcpy(atlas, before, sizeof(atlas));
  MRGI_CHECK(mrgi_ism_push_pull(&L, atlas, MRGI_ISM_MAX_PUSH_PULL_LEVELS, scratch, room, &err) ==
    MRGI_OK);
  for (int Y = 0; Y < L.height; ++Y)
    for (int X = 0; X < L.width; ++X)
    {
      const int l = (Y / 32) * 3 + X / 32;
      const float d = atlas[Y * L.width + X];
      if (before[Y * L.width + X] < MRGI_ISM_EMPTY_DEPTH)
        MRGI_CHECK(d == before[Y * L.width + X]);
      if (l >= 4)
        MRGI_CHECK(d == MRGI_ISM_EMPTY_DEPTH);
      else
        MRGI_CHECK(d >= l + 1 && d < l + 1.5f); /* filled, from its own tile */
    }
}

static void test_bad_sizes(void)
{
  mrgi_ism_atlas_layout L;
  mrgi_error err;
  MRGI_CHECK(mrgi_ism_atlas_layout_make(0, 32, &L, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "VPL count") != NULL);
  MRGI_CHECK(mrgi_ism_atlas_layout_make(16, 48, &L, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "power of two") != NULL);
  MRGI_CHECK(mrgi_ism_atlas_layout_make(1 << 20, 1024, &L, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "atlas") != NULL);
  MRGI_CHECK(mrgi_ism_atlas_layout_make(16, 1 << 20, &L, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_ism_push_pull(NULL, atlas, 1, scratch, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

/* mrgi_ism_atlas_render (section 5): point i goes to VPL i mod V, the
 * nearest distance wins, points behind a VPL or at it land nowhere, an
 * empty VPL's tile stays empty through push-pull while its neighbours fill. */
static void test_render(void)
{
  mrgi_ism_atlas_layout L;
  MRGI_CHECK(mrgi_ism_atlas_layout_make(3, 8, &L, NULL) == MRGI_OK);
  mrgi_vpl v[3];
  memset(v, 0, sizeof(v));
  for (int l = 0; l < 2; ++l)
  {
    v[l].position[0] = (float)l;
    v[l].normal[2] = 1.0f;
  }
  /* v[2] is an empty VPL (zero normal). Points 0, 3 -> VPL 0; 1, 4 -> VPL 1; 2, 5 -> VPL 2. */
  const float pts[] = {
    0.0f, 0.0f, 2.0f, /* VPL 0, straight up, distance 2 */
    1.0f, 0.0f, -1.0f, /* VPL 1, behind: nowhere */
    0.0f, 0.0f, 1.0f,  /* VPL 2 (empty): nowhere */
    0.0f, 0.0f, 1.5f,  /* VPL 0, same texel, nearer: wins */
    1.0f, 0.0f, 0.0f,  /* VPL 1, at the VPL: nowhere */
    0.0f, 0.0f, 3.0f,  /* VPL 2 (empty): nowhere */
  };
  float depth[24 * 16];
  float pp_scratch[128];
  MRGI_CHECK(mrgi_ism_atlas_render(&L, pts, 6, v, 0, depth, NULL, 0, NULL) == MRGI_OK);
  int64_t texel;
  const double p0[3] = { 0, 0, 0 }, n0[3] = { 0, 0, 1 }, x0[3] = { 0, 0, 2 };
  MRGI_CHECK(mrgi_ism_point_texel(&L, 0, p0, n0, x0, &texel, NULL));
  int valid = 0;
  for (int k = 0; k < L.width * L.height; ++k)
    valid += depth[k] < MRGI_ISM_EMPTY_DEPTH;
  MRGI_CHECK(valid == 1);
  MRGI_CHECK(depth[texel] == 1.5f);
  /* Push-pull over all levels: tile 0 fills with 1.5, tiles 1 and 2 stay empty. */
  MRGI_CHECK(mrgi_ism_atlas_render(&L, pts, 6, v, MRGI_ISM_MAX_PUSH_PULL_LEVELS, depth, pp_scratch,
               128, NULL) == MRGI_OK);
  for (int y = 0; y < L.height; ++y)
    for (int x = 0; x < L.width; ++x)
    {
      const int tile = (y / 8) * L.tiles_per_row + x / 8;
      const float d = depth[y * L.width + x];
      if (tile == 0)
        MRGI_CHECK(d == 1.5f);
      else
        MRGI_CHECK(d == MRGI_ISM_EMPTY_DEPTH);
    }
  /* One level: only the 2x2 block around the point fills. */
  MRGI_CHECK(mrgi_ism_atlas_render(&L, pts, 6, v, 1, depth, pp_scratch, 128, NULL) == MRGI_OK);
  valid = 0;
  for (int k = 0; k < L.width * L.height; ++k)
    valid += depth[k] == 1.5f;
  MRGI_CHECK(valid == 4);
  /* Errors: too little scratch, negative count or levels, NULL arrays. */
  mrgi_error err;
  MRGI_CHECK(mrgi_ism_atlas_render(&L, pts, 6, v, -1, depth, pp_scratch, 128, &err) != MRGI_OK);
  MRGI_CHECK(strstr(err.message, "push-pull levels") != NULL);
  MRGI_CHECK(mrgi_ism_atlas_render(&L, pts, 6, v, 1, depth, pp_scratch, 4, &err) != MRGI_OK);
  MRGI_CHECK(strstr(err.message, "scratch") != NULL);
  MRGI_CHECK(mrgi_ism_atlas_render(&L, pts, -1, v, 0, depth, NULL, 0, &err) != MRGI_OK);
  MRGI_CHECK(mrgi_ism_atlas_render(&L, NULL, 6, v, 0, depth, NULL, 0, &err) != MRGI_OK);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_layout),
    MRGI_TEST_CASE(test_cos_sphere),
    MRGI_TEST_CASE(test_texels),
    MRGI_TEST_CASE(test_push_pull),
    MRGI_TEST_CASE(test_render),
    MRGI_TEST_CASE(test_bad_sizes),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
