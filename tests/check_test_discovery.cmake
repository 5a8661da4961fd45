# Fails unless every Catch2 TEST_CASE is exactly one CTest entry: a name that catch_discover_tests
# splits (at ';') or that matches no test case would otherwise be counted as passed.
#   cmake -DTEST_BINARY=... [-DBUILD_DIR=...] -P check_test_discovery.cmake
execute_process(COMMAND "${TEST_BINARY}" --list-test-names-only
                OUTPUT_VARIABLE names RESULT_VARIABLE rc)
# Catch2 v2 exits with the number of test cases listed, so only a crash or an empty list is an error.
if(NOT rc MATCHES "^[0-9]+$" OR names STREQUAL "")
  message(FATAL_ERROR "${TEST_BINARY} --list-test-names-only failed (${rc})")
endif()
string(REPLACE ";" "<semicolon>" names "${names}")
string(REGEX MATCHALL "[^\n]+" cases "${names}")
list(LENGTH cases case_count)
foreach(name IN LISTS cases)
  if(name MATCHES "<semicolon>")
    message(FATAL_ERROR "test case name contains ';', which CTest splits: ${name}")
  endif()
endforeach()

# Given only the binary (the build's POST_BUILD step), the names are all it checks: a name CTest
# would split fails the build, before any CTest run can count its halves.
if(NOT DEFINED BUILD_DIR)
  return()
endif()

execute_process(COMMAND "${CMAKE_CTEST_COMMAND}" -N WORKING_DIRECTORY "${BUILD_DIR}"
                OUTPUT_VARIABLE listing RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "ctest -N failed (${rc})")
endif()
string(REGEX MATCHALL "Test +#[0-9]+:" entries "${listing}")
list(LENGTH entries entry_count)
# This checker is a CTest entry itself.
math(EXPR entry_count "${entry_count} - 1")
if(NOT entry_count EQUAL case_count)
  message(FATAL_ERROR "${entry_count} CTest entries for ${case_count} Catch2 test cases")
endif()
message(STATUS "${case_count} Catch2 test cases, ${entry_count} CTest entries")
