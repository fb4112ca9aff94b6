// A log sink that can hold lines back: it forwards every message to another sink, except
// while a hold is open, when it keeps them until the hold is released (sent on, in their
// order) or dropped. An operation that is tried and then undone (a trial judged by the
// mesh it leaves, refiners/tet3d/deferred_split.h) holds the lines its steps write, so
// that the log describes only what the result contains.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "toolkit/core/log.h"

namespace delmesh {

class HoldingLogSink final : public LogSink {
 public:
  /// Forwards to `target` (null: discards).
  explicit HoldingLogSink(LogSink* target) : target_(target) {}
  void write(LogLevel level, std::string_view message) override;

 private:
  friend class LogHold;
  LogSink* target_;
  bool holding_ = false;
  std::vector<std::pair<LogLevel, std::string>> held_;
};

/// A hold on a HoldingLogSink for the life of this object, one at a time: the lines
/// written to the sink meanwhile are dropped unless release() sends them on. A null sink
/// holds nothing (there is no log).
class LogHold {
 public:
  explicit LogHold(HoldingLogSink* sink);
  ~LogHold();
  LogHold(const LogHold&) = delete;
  LogHold& operator=(const LogHold&) = delete;
  /// Drops the lines held so far; the hold stays open.
  void discard();
  /// Sends the held lines on, in order, and ends the hold.
  void release();
  /// Drops the held lines and ends the hold (what the destructor does if still open).
  void drop();

 private:
  HoldingLogSink* sink_;
};

}  // namespace delmesh
