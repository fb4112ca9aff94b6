// The log sink that holds lines back (toolkit/core/holding_log_sink.h): without a hold
// every line goes straight to the target; under a hold nothing does until release sends
// the held lines on in their order, while discard, drop and the end of the hold's scope
// lose them; a hold on a null sink is harmless.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "toolkit/core/holding_log_sink.h"

namespace delmesh {
namespace {

class RecordingSink final : public LogSink {
 public:
  void write(LogLevel level, std::string_view message) override { lines.emplace_back(level, message); }
  std::vector<std::pair<LogLevel, std::string>> lines;
};

TEST(HoldingLogSink, ForwardsWithoutAHold) {
  RecordingSink target;
  HoldingLogSink sink(&target);
  sink.write(LogLevel::Info, "one");
  sink.write(LogLevel::Warning, "two");
  ASSERT_EQ(target.lines.size(), 2u);
  EXPECT_EQ(target.lines[0], std::make_pair(LogLevel::Info, std::string("one")));
  EXPECT_EQ(target.lines[1], std::make_pair(LogLevel::Warning, std::string("two")));
  HoldingLogSink discarding(nullptr);
  discarding.write(LogLevel::Info, "nowhere");
}

TEST(HoldingLogSink, ReleaseSendsTheHeldLinesInOrder) {
  RecordingSink target;
  HoldingLogSink sink(&target);
  {
    LogHold hold(&sink);
    sink.write(LogLevel::Info, "reference");
    hold.discard();
    sink.write(LogLevel::Info, "a");
    sink.write(LogLevel::Warning, "b");
    EXPECT_TRUE(target.lines.empty());
    hold.release();
    sink.write(LogLevel::Info, "after");
  }
  ASSERT_EQ(target.lines.size(), 3u);
  EXPECT_EQ(target.lines[0].second, "a");
  EXPECT_EQ(target.lines[1], std::make_pair(LogLevel::Warning, std::string("b")));
  EXPECT_EQ(target.lines[2].second, "after");
}

TEST(HoldingLogSink, DropAndTheEndOfTheScopeLoseTheHeldLines) {
  RecordingSink target;
  HoldingLogSink sink(&target);
  {
    LogHold hold(&sink);
    sink.write(LogLevel::Info, "undone");
    hold.drop();
    sink.write(LogLevel::Info, "undone line");
  }
  {
    LogHold hold(&sink);
    sink.write(LogLevel::Info, "left in scope");
  }
  sink.write(LogLevel::Info, "next");
  ASSERT_EQ(target.lines.size(), 2u);
  EXPECT_EQ(target.lines[0].second, "undone line");
  EXPECT_EQ(target.lines[1].second, "next");
  LogHold none(nullptr);
  none.discard();
  none.release();
  none.drop();
}

}  // namespace
}  // namespace delmesh
