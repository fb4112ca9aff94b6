// The log sink that holds lines back during a trial (see holding_log_sink.h).
#include "toolkit/core/holding_log_sink.h"

namespace delmesh {

void HoldingLogSink::write(LogLevel level, std::string_view message) {
  if (holding_) {
    held_.emplace_back(level, std::string(message));
  } else {
    log(target_, level, message);
  }
}

LogHold::LogHold(HoldingLogSink* sink) : sink_(sink) {
  if (sink_) sink_->holding_ = true;
}

LogHold::~LogHold() { drop(); }

void LogHold::discard() {
  if (sink_) sink_->held_.clear();
}

void LogHold::release() {
  if (!sink_) return;
  sink_->holding_ = false;
  for (const auto& [level, message] : sink_->held_) log(sink_->target_, level, message);
  sink_->held_.clear();
  sink_ = nullptr;
}

void LogHold::drop() {
  if (!sink_) return;
  sink_->holding_ = false;
  sink_->held_.clear();
  sink_ = nullptr;
}

}  // namespace delmesh
