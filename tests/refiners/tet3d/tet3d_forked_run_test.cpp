// The hang and crash guard the 3D corpus tests run each input under
// (tests/support/forked_run.h): an answer, an exception, a crash and a hang are each told
// apart, so a corpus input cannot pass by throwing or stall the suite.
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

}  // namespace
}  // namespace delmesh::test
