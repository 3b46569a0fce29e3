/* mrgi_multires_receivers_build: level means by hand on a 5 x 3 G-buffer
 * (odd sizes: children outside the finer level are skipped, not counted
 * twice), invalid pixels left out, unit normals, bad input. */
#include "mrgi_buffers.h"
#include "mrgi_multires_receivers.h"
#include "mrgi_test.h"

#include <string.h>

static void test_receivers(void)
{
  enum { W = 5, H = 3 };
  float position[W * H * 4], normal[W * H * 4];
  for (int y = 0; y < H; ++y)
  {
    for (int x = 0; x < W; ++x)
    {
      float* p = position + 4 * (y * W + x);
      float* n = normal + 4 * (y * W + x);
      p[0] = (float)x;
      p[1] = (float)y;
      p[2] = -10.0f;
      p[3] = MRGI_GBUFFER_VALID;
      n[0] = 0.0f;
      n[1] = 0.0f;
      n[2] = 2.0f; /* not unit: the builder normalizes */
      n[3] = 0.0f;
    }
  }
  position[4 * (0 * W + 1) + 3] = 0.0f; /* pixel (1, 0) is background */
  mrgi_multires_layout layout;
  mrgi_error err;
  MRGI_CHECK(mrgi_multires_layout_init(&layout, W, H, 1, &err) == MRGI_OK);
  MRGI_CHECK(layout.level_count == 4); /* 5x3, 3x2, 2x1, 1x1 */
  const size_t count = 4 * (size_t)mrgi_multires_texel_count(&layout);
  float* rp = (float*)malloc(count * sizeof(float));
  float* rn = (float*)malloc(count * sizeof(float));
  MRGI_CHECK(rp && rn);
  const mrgi_gather_receivers gbuffer = { W, H, position, normal };
  MRGI_CHECK(mrgi_multires_receivers_build(&layout, &gbuffer, rp, rn, count, &err) == MRGI_OK);

  /* Level 0: the pixels themselves, the background pixel empty. */
  const float* t = rp + 4 * mrgi_multires_index(&layout, 0, 2, 1);
  MRGI_CHECK(t[0] == 2.0f && t[1] == 1.0f && t[2] == -10.0f && t[3] == 1.0f);
  MRGI_CHECK(rp[4 * mrgi_multires_index(&layout, 0, 1, 0) + 3] == 0.0f);
  MRGI_CHECK_NEAR(rn[4 * mrgi_multires_index(&layout, 0, 2, 1) + 2], 1.0, 1e-7);
  /* Level 1, texel (0, 0): pixels (0,0), (0,1), (1,1) -> mean x 1/3, y 2/3, count 3. */
  t = rp + 4 * mrgi_multires_index(&layout, 1, 0, 0);
  MRGI_CHECK_NEAR(t[0], 1.0 / 3.0, 1e-6);
  MRGI_CHECK_NEAR(t[1], 2.0 / 3.0, 1e-6);
  MRGI_CHECK(t[3] == 3.0f);
  /* Level 1, texel (2, 1): only pixel (4, 2) exists (odd sizes), counted once. */
  t = rp + 4 * mrgi_multires_index(&layout, 1, 2, 1);
  MRGI_CHECK(t[0] == 4.0f && t[1] == 2.0f && t[3] == 1.0f);
  /* Coarsest: all 14 valid pixels, mean x = (0+2+3+4 + 2*10) / 14 = 29/14... computed: */
  double sx = 0.0, sy = 0.0;
  int valid = 0;
  for (int y = 0; y < H; ++y)
  {
    for (int x = 0; x < W; ++x)
    {
      if (!(x == 1 && y == 0))
      {
        sx += x;
        sy += y;
        ++valid;
      }
    }
  }
  t = rp + 4 * mrgi_multires_index(&layout, 3, 0, 0);
  MRGI_CHECK(t[3] == (float)valid);
  MRGI_CHECK_NEAR(t[0], sx / valid, 1e-5);
  MRGI_CHECK_NEAR(t[1], sy / valid, 1e-5);
  MRGI_CHECK_NEAR(rn[4 * mrgi_multires_index(&layout, 3, 0, 0) + 2], 1.0, 1e-6);

  /* Bad input. */
  MRGI_CHECK(mrgi_multires_receivers_build(&layout, &gbuffer, rp, rn, count - 1, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "too small") != NULL);
  MRGI_CHECK(mrgi_multires_receivers_build(&layout, NULL, rp, rn, count, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  const mrgi_gather_receivers wrong = { W - 1, H, position, normal };
  MRGI_CHECK(mrgi_multires_receivers_build(&layout, &wrong, rp, rn, count, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "layout is for") != NULL);
  free(rp);
  free(rn);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_receivers),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
