# Registers one ctest test per GoogleTest suite of a test program (cmake -P, after each build of
# it): the program's suites, read from --gtest_list_tests, each run as `--gtest_filter=Suite.*`.
# A process of a test program spends ~0.45 s of CPU before its first test (the dynamic linker
# binding ~270 libraries: OpenImageIO's, OpenVDB AX's LLVM), as long as most unit tests take; one
# process per suite instead of per test spares that for all but ~120 of ~530 unit tests.
#   -D EXE=<test program> -D OUT=<ctest file to write> -D LABEL=<label> -D TIMEOUT=<s>
#   -D WORKDIR=<working directory>
# A suite's process exits 77 when every test it ran was skipped (support/gtest_main.cpp), which
# SKIP_RETURN_CODE reports as skipped; a suite with a failure fails, whatever else it skipped.
execute_process(COMMAND "${EXE}" --gtest_list_tests OUTPUT_VARIABLE listing
                RESULT_VARIABLE rc TIMEOUT 60)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${EXE} --gtest_list_tests failed (${rc}):\n${listing}")
endif()
# Suites are the unindented lines, "Suite." (typed suites add "  # TypeParam = ...").
string(REGEX MATCHALL "\n[^ \n#][^ \n]*\\." suites "\n${listing}")
set(script "")
foreach(match IN LISTS suites)
  string(REGEX REPLACE "^\n(.*)\\.$" "\\1" suite "${match}")
  string(APPEND script
    "add_test([=[${suite}]=] \"${EXE}\" [==[--gtest_filter=${suite}.*]==])\n"
    "set_tests_properties([=[${suite}]=] PROPERTIES LABELS ${LABEL} TIMEOUT ${TIMEOUT} "
    "SKIP_RETURN_CODE 77 WORKING_DIRECTORY \"${WORKDIR}\")\n")
endforeach()
file(WRITE "${OUT}" "${script}")
