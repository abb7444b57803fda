// The test programs' main: GoogleTest's, but a run in which every test was skipped (a suite
// whose tests all need ../shared/data, run without it) exits 77, which ctest's
// SKIP_RETURN_CODE reports as skipped (tests/support/suite_tests.cmake). A run with a failure
// fails, and one with a test that passed passes, whatever else it skipped.
#include <gtest/gtest.h>

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    const int result = RUN_ALL_TESTS();
    const ::testing::UnitTest& run = *::testing::UnitTest::GetInstance();
    if (result == 0 && run.successful_test_count() == 0 && run.skipped_test_count() > 0) return 77;
    return result;
}
