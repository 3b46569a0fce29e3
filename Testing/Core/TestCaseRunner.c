/* The case runner of mrgi_test.h, on cases that pass and fail on purpose:
 * run by Testing/CheckCaseRunner.cmake (core.CaseRunner), which expects
 * exactly these names and outcomes. Not a test of the core. */
#include "mrgi_test.h"

static void passes(void)
{
  MRGI_CHECK(1 + 1 == 2);
  MRGI_CHECK_NEAR(0.1 + 0.2, 0.3, 1e-12);
}

static void check_fails(void)
{
  MRGI_CHECK(1 + 1 == 3);
  printf("not reached\n");
}

static void fail_fails(void)
{
  MRGI_FAIL("failed on purpose: %d", 42);
  printf("not reached\n");
}

static void other_fails(void)
{
  MRGI_CHECK_NEAR(1.0, 1.5, 0.25);
  printf("not reached\n");
}

static void passes_after_failures(void)
{
  MRGI_CHECK(2 * 2 == 4);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    { "Passes", passes },
    { "CheckFails", check_fails },
    { "FailFails", fail_fails },
    { "OtherFails", other_fails },
    { "PassesAfterFailures", passes_after_failures },
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
