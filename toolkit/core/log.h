// Logging through a sink.
//
// Library code never prints. Anything worth telling the user (progress, warnings about
// repaired input, statistics) goes to a LogSink the caller provides; the default sink
// discards everything. The CLI installs a sink that writes to stderr.
#pragma once

#include <string_view>

namespace delmesh {

enum class LogLevel { Debug, Info, Progress, Warning };

class LogSink {
 public:
  virtual ~LogSink() = default;
  virtual void write(LogLevel level, std::string_view message) = 0;
};

/// A sink that drops every message (the default of every options struct).
LogSink& null_log_sink();

/// Sends to `sink` if it is not null.
inline void log(LogSink* sink, LogLevel level, std::string_view message) {
  if (sink) sink->write(level, message);
}

}  // namespace delmesh
