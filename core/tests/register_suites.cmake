# Registers torrance_tests with CTest one test suite per test, not one test per test as
# gtest_discover_tests does. Every torrance_tests process links OpenImageIO and its ~260 shared
# libraries, and the dynamic loader's relocations cost ~0.3 s per start: one process per test
# (447 of them) spent about two minutes of the suite's time in the loader alone.
#
# Script mode, run after each link of torrance_tests:
#   cmake -DEXE=<torrance_tests> -DOUT=<file to write> -P register_suites.cmake
# It lists the tests (--gtest_list_tests), and writes one add_test per suite, running
# `<exe> --gtest_filter=<Suite>.*`. A failing suite's output names the failing tests.
execute_process(COMMAND "${EXE}" --gtest_list_tests
                OUTPUT_VARIABLE listing RESULT_VARIABLE code TIMEOUT 60)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "${EXE} --gtest_list_tests failed (${code}):\n${listing}")
endif()
string(REPLACE "\n" ";" lines "${listing}")
set(body "")
foreach(line IN LISTS lines)
  # Suite lines start in column 0 and end with '.' (typed suites add "  # TypeParam = ...").
  if(line MATCHES "^([^ #][^ ]*)\\.")
    set(suite "${CMAKE_MATCH_1}")
    string(APPEND body "add_test([=[${suite}]=] [==[${EXE}]==] [=[--gtest_filter=${suite}.*]=])\n"
                       "set_tests_properties([=[${suite}]=] PROPERTIES LABELS core)\n")
  endif()
endforeach()
file(WRITE "${OUT}" "${body}")
