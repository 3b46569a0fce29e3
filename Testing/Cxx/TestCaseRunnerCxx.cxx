// The case runner of mrgiTestUtilities.h, on cases that pass and fail on
// purpose: run by Testing/CheckCaseRunner.cmake (cxx.CaseRunner), which
// expects exactly these names and outcomes. Not a test of the module.
#include "mrgiTestUtilities.h"

#include <stdexcept>

namespace
{
void Passes()
{
  MRGI_TEST_CHECK(1 + 1 == 2);
}

void CheckFails()
{
  vtkNew<vtkImageData> image; // released by the unwinding
  MRGI_TEST_CHECK(1 + 1 == 3);
  std::printf("not reached\n");
}

void FailFails()
{
  MRGI_TEST_FAIL("failed on purpose: %d", 42);
  std::printf("not reached\n");
}

void OtherFails()
{
  throw std::runtime_error("thrown on purpose");
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(Passes), MRGI_TEST_CASE(CheckFails), MRGI_TEST_CASE(FailFails),
      MRGI_TEST_CASE(OtherFails), { "PassesAfterFailures", [] { MRGI_TEST_CHECK(2 * 2 == 4); } } });
}
