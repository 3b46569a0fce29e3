# The case runner of the C and C++ tests (Testing/Core/mrgi_test.h,
# Testing/Cxx/mrgiTestUtilities.h) on its self-test program, whose cases
# pass or fail on purpose (Testing/Core/TestCaseRunner.c,
# Testing/Cxx/TestCaseRunnerCxx.cxx): every case runs, a failed check ends
# its case only, every failed case is named, the exit status tells, and
# --case / --list work.
# Usage: cmake -DPROGRAM=/path/to/TestCaseRunner -P CheckCaseRunner.cmake
if (NOT PROGRAM)
  message(FATAL_ERROR "usage: cmake -DPROGRAM=... -P CheckCaseRunner.cmake")
endif ()

# Runs PROGRAM with the remaining arguments; expects exit status `rc` and
# every string in EXPECT in the output (stdout and stderr), none of REJECT.
function(expect rc)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "ARGS;EXPECT;REJECT")
  execute_process(COMMAND "${PROGRAM}" ${arg_ARGS}
    RESULT_VARIABLE got OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(all "${out}${err}")
  list(JOIN arg_ARGS " " shown)
  set(what "'${PROGRAM} ${shown}'")
  if (NOT got STREQUAL rc)
    message(FATAL_ERROR "${what}: exit status ${got}, expected ${rc}; output:\n${all}")
  endif ()
  foreach (text IN LISTS arg_EXPECT)
    string(FIND "${all}" "${text}" at)
    if (at LESS 0)
      message(FATAL_ERROR "${what}: output lacks '${text}':\n${all}")
    endif ()
  endforeach ()
  foreach (text IN LISTS arg_REJECT)
    string(FIND "${all}" "${text}" at)
    if (NOT at LESS 0)
      message(FATAL_ERROR "${what}: output has '${text}':\n${all}")
    endif ()
  endforeach ()
  message(STATUS "${what}: exit status ${got} as expected")
endfunction()

# All cases: the three failures are named, the cases after them still run.
expect(1
  EXPECT "[     OK ] Passes" "[ FAILED ] CheckFails" "check failed: 1 + 1 == 3"
         "[ FAILED ] FailFails" "failed on purpose: 42" "[ FAILED ] OtherFails"
         "[     OK ] PassesAfterFailures"
         "3 of 5 cases failed: CheckFails FailFails OtherFails"
  REJECT "not reached" "all 5 cases passed")
# One case by name, passing or failing; several.
expect(0 ARGS --case Passes EXPECT "[     OK ] Passes" "all 1 cases passed" REJECT "CheckFails")
expect(1 ARGS --case CheckFails EXPECT "1 of 1 cases failed: CheckFails" REJECT "Passes")
expect(1 ARGS --case PassesAfterFailures --case OtherFails
  EXPECT "[     OK ] PassesAfterFailures" "1 of 2 cases failed: OtherFails" REJECT "CheckFails")
# The names, in order.
expect(0 ARGS --list EXPECT "Passes\nCheckFails\nFailFails\nOtherFails\nPassesAfterFailures\n"
  REJECT "[ RUN")
# A bad command line runs nothing.
expect(2 ARGS --case Nope EXPECT "no case 'Nope'" REJECT "[ RUN")
expect(2 ARGS --case EXPECT "usage:" REJECT "[ RUN")
expect(2 ARGS --bogus EXPECT "usage:" REJECT "[ RUN")
