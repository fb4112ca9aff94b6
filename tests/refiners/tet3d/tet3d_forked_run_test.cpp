// The hang and crash guard the 3D corpus tests run each input under
// (tests/support/forked_run.h): an answer, an exception, a crash and a hang are each told
// apart, so a corpus input cannot pass by throwing or stall the suite; every finding of
// an answered run is a failure.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <csignal>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include "tests/support/forked_run.h"

namespace delmesh::test {
namespace {

TEST(ForkedRun, ReturnsTheWorksText) {
  const ForkedRun run = run_forked([] { return std::string("summary\nfinding\n"); }, 30);
  EXPECT_TRUE(run.finished);
  EXPECT_FALSE(run.crashed);
  EXPECT_FALSE(run.threw);
  EXPECT_EQ(run.text, "summary\nfinding\n");
}

TEST(ForkedRun, ReportsAnExceptionAsThrown) {
  const ForkedRun run = run_forked([]() -> std::string { throw std::runtime_error("internal check failed"); }, 30);
  EXPECT_TRUE(run.finished);
  EXPECT_FALSE(run.crashed);
  EXPECT_TRUE(run.threw);
  EXPECT_NE(run.text.find("internal check failed"), std::string::npos) << run.text;
}

TEST(ForkedRun, ReportsACrashWithItsSignal) {
  const ForkedRun run = run_forked(
      []() -> std::string {
        std::raise(SIGABRT);
        return "not reached";
      },
      30);
  EXPECT_TRUE(run.finished);
  EXPECT_TRUE(run.crashed);
  EXPECT_FALSE(run.threw);
  EXPECT_EQ(run.signal, SIGABRT);
}

TEST(ForkedRun, StopsAHang) {
  const ForkedRun run = run_forked(
      [] {
        for (;;) pause();
        return std::string();
      },
      1);
  EXPECT_FALSE(run.finished);
  EXPECT_FALSE(run.threw);
}

TEST(ForkedRun, FindingsHangsAndExceptionsAreFailures) {
  ForkedRun answered;
  answered.finished = true;
  answered.text = "12 tets\nmore than 0.1% unmet\n";
  EXPECT_NONFATAL_FAILURE(report_findings("input.off", answered, 5), "more than 0.1% unmet");
  ForkedRun threw;
  threw.finished = threw.threw = true;
  threw.text = "exception from the library: internal check failed";
  EXPECT_NONFATAL_FAILURE(report_findings("input.off", threw, 5), "internal check failed");
  ForkedRun hung;
  EXPECT_NONFATAL_FAILURE(report_findings("input.off", hung, 5), "did not terminate within 5 s");
  ForkedRun clean;
  clean.finished = true;
  clean.text = "12 tets\n";
  report_findings("input.off", clean, 5);
}

}  // namespace
}  // namespace delmesh::test
