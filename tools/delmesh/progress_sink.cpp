// ProgressLogSink (see progress_sink.h).
#include "tools/delmesh/progress_sink.h"

#include <unistd.h>

#include <chrono>
#include <iostream>

namespace delmesh::cli {

ProgressLogSink::ProgressLogSink(std::ostream& out, Settings settings, std::function<double()> now)
    : out_(out), settings_(settings), now_(std::move(now)), start_(now_()) {}

ProgressLogSink ProgressLogSink::for_stderr(bool quiet, bool verbose) {
  Settings settings;
  settings.quiet = quiet;
  settings.verbose = verbose;
  settings.terminal = isatty(STDERR_FILENO) != 0;
  return ProgressLogSink(std::cerr, settings, [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  });
}

void ProgressLogSink::finish_line() {
  if (!line_open_) return;
  out_ << '\n';
  line_open_ = false;
  line_width_ = 0;
}

void ProgressLogSink::write(LogLevel level, std::string_view message) {
  switch (level) {
    case LogLevel::Progress: {
      if (settings_.quiet) return;
      const double t = now_();
      if (t - start_ < settings_.delay) return;
      if (last_shown_ >= 0 && t - last_shown_ < settings_.interval) return;
      last_shown_ = t;
      if (settings_.terminal) {
        out_ << '\r' << message;
        if (message.size() < line_width_) out_ << std::string(line_width_ - message.size(), ' ');
        out_ << std::flush;
        line_open_ = true;
        line_width_ = message.size();
      } else {
        out_ << message << '\n' << std::flush;
      }
      return;
    }
    case LogLevel::Warning:
      finish_line();
      out_ << "warning: " << message << '\n';
      return;
    case LogLevel::Info:
    case LogLevel::Debug:
      if (settings_.quiet || !settings_.verbose) return;
      finish_line();
      out_ << message << '\n';
      return;
  }
}

}  // namespace delmesh::cli
