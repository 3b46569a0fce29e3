/* Tests of mrgi_flicker (temporal flicker, issue 12 part 6) on sequences whose
 * F is computed by hand. */
#include "mrgi_flicker.h"
#include "mrgi_test.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#define FRAMES 4

static mrgi_image make_constant(int32_t w, int32_t h, int32_t c, float v)
{
  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, w, h, c, NULL) == MRGI_OK);
  for (size_t i = 0; i < mrgi_image_value_count(&img); ++i)
  {
    img.pixels[i] = v;
  }
  return img;
}

/* A 4x4 RGB frame: a bright 1-pixel vertical bar at column `bar` on 0.5. */
static mrgi_image make_bar(int32_t bar)
{
  mrgi_image img = make_constant(4, 4, 3, 0.5f);
  for (int32_t y = 0; y < 4; ++y)
  {
    for (int32_t c = 0; c < 3; ++c)
    {
      mrgi_image_at(&img, bar, y)[c] = 1.5f;
    }
  }
  return img;
}

static void destroy_all(mrgi_image* frames, int32_t count)
{
  for (int32_t k = 0; k < count; ++k)
  {
    mrgi_image_destroy(&frames[k]);
  }
}

static mrgi_flicker_result flicker(const mrgi_image* images, const mrgi_image* refs, int32_t count,
                                   int32_t box)
{
  mrgi_flicker_result r;
  mrgi_error err;
  if (mrgi_flicker_sequence(images, refs, count, box, NULL, &r, &err) != MRGI_OK)
  {
    MRGI_FAIL("flicker failed: %s", err.message);
  }
  return r;
}

/* I = R (a moving bar): no flicker at all. */
static void test_identical_is_zero(void)
{
  mrgi_image refs[FRAMES];
  for (int32_t k = 0; k < FRAMES; ++k)
  {
    refs[k] = make_bar(k);
  }
  const mrgi_flicker_result r = flicker(refs, refs, FRAMES, 1);
  MRGI_CHECK(r.flicker == 0.0 && r.max_pair == 0.0);
  MRGI_CHECK(r.pairs_counted == FRAMES - 1 && r.pairs_excluded == 0);
  destroy_all(refs, FRAMES);
}

/* I = R + 0.25 (a constant bias): every difference cancels. */
static void test_constant_offset_is_zero(void)
{
  mrgi_image refs[FRAMES], images[FRAMES];
  for (int32_t k = 0; k < FRAMES; ++k)
  {
    refs[k] = make_bar(k);
    images[k] = make_bar(k);
    for (size_t i = 0; i < mrgi_image_value_count(&images[k]); ++i)
    {
      images[k].pixels[i] += 0.25f;
    }
  }
  const mrgi_flicker_result r = flicker(images, refs, FRAMES, 1);
  MRGI_CHECK_NEAR(r.flicker, 0.0, 1e-12);
  destroy_all(refs, FRAMES);
  destroy_all(images, FRAMES);
}

/* A static I (the bar stays at column 0) against R's bar moving one column a
 * frame. Pair k: I's change is 0, R's is +1 at column k+1 and -1 at column
 * k, so the numerator is rms of two columns of +-1 out of four:
 * sqrt(8 * 3 / 48) = sqrt(1/2). rms(R_k) = sqrt((4 * 1.5^2 + 12 * 0.5^2) /
 * 16) = sqrt(0.75). Every pair: sqrt(0.5 / 0.75) = sqrt(2/3). */
static void test_static_against_moving(void)
{
  mrgi_image refs[FRAMES], images[FRAMES];
  mrgi_flicker_pair pairs[FRAMES - 1];
  for (int32_t k = 0; k < FRAMES; ++k)
  {
    refs[k] = make_bar(k);
    images[k] = make_bar(0);
  }
  mrgi_flicker_result r;
  mrgi_error err;
  MRGI_CHECK(mrgi_flicker_sequence(images, refs, FRAMES, 1, pairs, &r, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(r.flicker, sqrt(2.0 / 3.0), 1e-12);
  MRGI_CHECK_NEAR(r.max_pair, sqrt(2.0 / 3.0), 1e-12);
  for (int32_t k = 0; k < FRAMES - 1; ++k)
  {
    MRGI_CHECK_NEAR(pairs[k].change_rms, sqrt(0.5), 1e-12);
    MRGI_CHECK_NEAR(pairs[k].reference_rms, sqrt(0.75), 1e-12);
    MRGI_CHECK(!pairs[k].excluded);
  }
  /* The same with I moving and R static: the numerator is the same and
   * rms(R_k) is the static bar's, also sqrt(0.75). */
  const mrgi_flicker_result swapped = flicker(refs, images, FRAMES, 1);
  MRGI_CHECK_NEAR(swapped.flicker, sqrt(2.0 / 3.0), 1e-12);
  destroy_all(refs, FRAMES);
  destroy_all(images, FRAMES);
}

/* Constant frames: R_k = k + 1, I static at 1. Pair k: change rms 1,
 * rms(R_k) = k + 1, so F = (1 + 1/2 + 1/3) / 3. Alpha (RGBA images against
 * RGB references) is ignored: setting it to junk changes nothing. */
static void test_brightening_reference_rgba(void)
{
  mrgi_image refs[FRAMES], images[FRAMES];
  for (int32_t k = 0; k < FRAMES; ++k)
  {
    refs[k] = make_constant(3, 2, 3, (float)(k + 1));
    images[k] = make_constant(3, 2, 4, 1.0f);
    for (int64_t p = 0; p < mrgi_image_pixel_count(&images[k]); ++p)
    {
      images[k].pixels[p * 4 + 3] = (float)(7 * k + p);
    }
  }
  const mrgi_flicker_result r = flicker(images, refs, FRAMES, 1);
  MRGI_CHECK_NEAR(r.flicker, (1.0 + 0.5 + 1.0 / 3.0) / 3.0, 1e-12);
  MRGI_CHECK_NEAR(r.max_pair, 1.0, 1e-12);
  destroy_all(refs, FRAMES);
  destroy_all(images, FRAMES);
}

/* A black R_0 excludes pair 0 and counts it: R = 0, 1, 2; I static at 0.
 * Pair 1: change 1, rms(R_1) = 1. F = 1 over one pair. */
static void test_black_reference_excluded(void)
{
  mrgi_image refs[3], images[3];
  mrgi_flicker_pair pairs[2];
  for (int32_t k = 0; k < 3; ++k)
  {
    refs[k] = make_constant(2, 2, 3, (float)k);
    images[k] = make_constant(2, 2, 3, 0.0f);
  }
  mrgi_flicker_result r;
  mrgi_error err;
  MRGI_CHECK(mrgi_flicker_sequence(images, refs, 3, 1, pairs, &r, &err) == MRGI_OK);
  MRGI_CHECK(r.pairs_counted == 1 && r.pairs_excluded == 1);
  MRGI_CHECK(pairs[0].excluded && pairs[0].value == 0.0 && !pairs[1].excluded);
  MRGI_CHECK_NEAR(r.flicker, 1.0, 1e-12);
  /* Every pair black (R = 0, 0): undefined, an error that says so. */
  MRGI_CHECK(mrgi_flicker_sequence(images, images, 2, 1, NULL, &r, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "black") != NULL);
  destroy_all(refs, 3);
  destroy_all(images, 3);
}

/* Per-pixel noise whose sign flips every frame (a checkerboard of +-0.1 on
 * I = R = 1) flickers per pixel (change +-0.2, and more in the junk) but
 * averages out in 2x2 boxes. A 5x5 frame with box 2 drops the last row and
 * column, where junk that grows by 5 a frame is put; box 5 keeps it. */
static void test_box_average(void)
{
  mrgi_image refs[FRAMES], images[FRAMES];
  for (int32_t k = 0; k < FRAMES; ++k)
  {
    refs[k] = make_constant(5, 5, 3, 1.0f);
    images[k] = make_constant(5, 5, 3, 1.0f);
    for (int32_t y = 0; y < 5; ++y)
    {
      for (int32_t x = 0; x < 5; ++x)
      {
        const float sign = ((x + y + k) % 2) ? 1.0f : -1.0f;
        for (int32_t c = 0; c < 3; ++c)
        {
          mrgi_image_at(&images[k], x, y)[c] += (x == 4 || y == 4) ? 5.0f * (float)k : 0.1f * sign;
        }
      }
    }
  }
  const mrgi_flicker_result boxed = flicker(images, refs, FRAMES, 2);
  MRGI_CHECK_NEAR(boxed.flicker, 0.0, 1e-7);
  const mrgi_flicker_result pixels = flicker(images, refs, FRAMES, 1);
  MRGI_CHECK(pixels.flicker > 0.2);
  /* Box 5 covers the whole frame, junk included: not zero. */
  MRGI_CHECK(flicker(images, refs, FRAMES, 5).flicker > 0.0);
  destroy_all(refs, FRAMES);
  destroy_all(images, FRAMES);
}

static void expect_error(const mrgi_image* images, const mrgi_image* refs, int32_t count,
                         int32_t box, const char* words)
{
  mrgi_flicker_result r = { -1.0, -1.0, -1, -1 };
  mrgi_error err;
  err.message[0] = '\0';
  MRGI_CHECK(mrgi_flicker_sequence(images, refs, count, box, NULL, &r, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  if (!strstr(err.message, words))
  {
    MRGI_FAIL("error '%s' does not name '%s'", err.message, words);
  }
  MRGI_CHECK(r.flicker == -1.0 && r.pairs_counted == -1); /* untouched */
}

static void test_errors(void)
{
  mrgi_image refs[3], images[3];
  for (int32_t k = 0; k < 3; ++k)
  {
    refs[k] = make_constant(4, 4, 3, 1.0f);
    images[k] = make_constant(4, 4, 3, 1.0f);
  }
  expect_error(images, refs, 1, 1, "at least 2 frames");
  expect_error(images, refs, 0, 1, "at least 2 frames");
  expect_error(NULL, refs, 3, 1, "NULL");
  expect_error(images, refs, 3, 0, "box side 0");
  expect_error(images, refs, 3, 5, "box side 5");
  images[2].pixels[7] = NAN;
  expect_error(images, refs, 3, 1, "image frame 2 holds 1 NaN or infinite");
  images[2].pixels[7] = 1.0f;
  refs[1].pixels[0] = INFINITY;
  refs[1].pixels[5] = -INFINITY;
  expect_error(images, refs, 3, 1, "reference frame 1 holds 2 NaN or infinite");
  refs[1].pixels[0] = refs[1].pixels[5] = 1.0f;

  mrgi_image small = make_constant(4, 2, 3, 1.0f);
  mrgi_image swap = images[1];
  images[1] = small;
  expect_error(images, refs, 3, 1, "image frame 1 is 4x2");
  images[1] = swap;
  mrgi_image gray[3];
  for (int32_t k = 0; k < 3; ++k)
  {
    gray[k] = make_constant(4, 4, 1, 1.0f);
  }
  expect_error(images, gray, 3, 1, "channels");
  mrgi_image wide[3];
  for (int32_t k = 0; k < 3; ++k)
  {
    wide[k] = make_constant(8, 4, 3, 1.0f);
  }
  expect_error(images, wide, 3, 1, "references 8x4");

  /* The pair function names its own errors too. */
  mrgi_flicker_pair pair;
  mrgi_error err;
  MRGI_CHECK(mrgi_flicker_compute_pair(&images[0], NULL, &refs[0], &refs[1], 1, &pair, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_flicker_compute_pair(&images[0], &small, &refs[0], &refs[1], 1, &pair, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_flicker_compute_pair(&images[0], &images[1], &refs[0], &refs[1], 1, &pair,
                                       &err) == MRGI_OK);
  MRGI_CHECK(pair.value == 0.0 && !pair.excluded);
  mrgi_image_destroy(&small);
  destroy_all(gray, 3);
  destroy_all(wide, 3);
  destroy_all(refs, 3);
  destroy_all(images, 3);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_identical_is_zero),
    MRGI_TEST_CASE(test_constant_offset_is_zero),
    MRGI_TEST_CASE(test_static_against_moving),
    MRGI_TEST_CASE(test_brightening_reference_rgba),
    MRGI_TEST_CASE(test_black_reference_excluded),
    MRGI_TEST_CASE(test_box_average),
    MRGI_TEST_CASE(test_errors),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
