// The log sink of long CLI runs: a status line on stderr, "<phase> <seconds> s: <latest
// message>", shown only once the run has lasted `delay` seconds and then at most every
// `interval` seconds, so short runs print none. The latest Progress (or Info) message from
// the library becomes the status; tick(), called by a ticker thread of the CLI, keeps the
// elapsed time moving while the library is silent. On a terminal the line is rewritten in
// place ('\r'); otherwise each shown status is a line of its own. Warnings always print,
// Info lines with verbose; nothing but warnings with quiet. Thread-safe.
#pragma once

#include <functional>
#include <mutex>
#include <ostream>
#include <string>
#include <string_view>
#include <thread>

#include "toolkit/core/log.h"

namespace delmesh::cli {

class ProgressLogSink final : public LogSink {
 public:
  struct Settings {
    bool quiet = false;
    bool verbose = false;
    bool terminal = false;   ///< rewrite one line with '\r' instead of printing lines
    double delay = 1.0;      ///< seconds before the first status line
    double interval = 0.5;   ///< seconds between status lines
  };

  /// `now` returns seconds on a monotonic clock (injectable for tests).
  ProgressLogSink(std::ostream& out, Settings settings, std::function<double()> now);

  void write(LogLevel level, std::string_view message) override;
  /// Names what the run is doing ("importing", "meshing"); clears the status message.
  void set_phase(std::string_view phase);
  /// Shows the status line if it is due.
  void tick();
  /// Ends a status line left open on a terminal (call before printing anything else).
  void finish_line();

 private:
  void show_if_due();  // with mutex_ held
  void end_line();     // with mutex_ held

  std::mutex mutex_;
  std::ostream& out_;
  Settings settings_;
  std::function<double()> now_;
  double start_;
  double last_shown_ = -1.0;
  std::string phase_;
  std::string status_;
  bool line_open_ = false;
  std::size_t line_width_ = 0;
};

/// The sink of a CLI run on stderr (steady clock; terminal mode when stderr is a tty) with
/// a ticker thread that calls tick() every 0.1 s until stop() or destruction.
class StderrProgress {
 public:
  StderrProgress(bool quiet, bool verbose);
  ~StderrProgress();
  StderrProgress(const StderrProgress&) = delete;
  StderrProgress& operator=(const StderrProgress&) = delete;

  ProgressLogSink& sink() { return sink_; }
  /// Stops the ticker and ends an open status line (before printing results).
  void stop();

 private:
  ProgressLogSink sink_;
  std::jthread ticker_;
};

}  // namespace delmesh::cli
