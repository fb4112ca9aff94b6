// The log sink of long CLI runs: Progress messages become one status line on stderr, shown
// only once the run has lasted `delay` seconds and then at most every `interval` seconds
// (short runs print none). On a terminal the line is rewritten in place ('\r'); otherwise
// each shown message is a line of its own. Warnings always print, Info and Debug with
// verbose; nothing but warnings with quiet.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <string_view>

#include "toolkit/core/log.h"

namespace delmesh::cli {

class ProgressLogSink final : public LogSink {
 public:
  struct Settings {
    bool quiet = false;
    bool verbose = false;
    bool terminal = false;   ///< rewrite one line with '\r' instead of printing lines
    double delay = 1.0;      ///< seconds before the first progress line
    double interval = 0.5;   ///< seconds between progress lines
  };

  /// `now` returns seconds on a monotonic clock (injectable for tests).
  ProgressLogSink(std::ostream& out, Settings settings, std::function<double()> now);
  /// Writes to stderr with the steady clock; `terminal` from isatty(stderr).
  static ProgressLogSink for_stderr(bool quiet, bool verbose);

  void write(LogLevel level, std::string_view message) override;
  /// Ends a progress line left open on a terminal (call before printing anything else).
  void finish_line();

 private:
  std::ostream& out_;
  Settings settings_;
  std::function<double()> now_;
  double start_;
  double last_shown_ = -1.0;
  bool line_open_ = false;
  std::size_t line_width_ = 0;
};

}  // namespace delmesh::cli
