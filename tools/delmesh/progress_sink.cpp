// ProgressLogSink and StderrProgress (see progress_sink.h).
#include "tools/delmesh/progress_sink.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>

namespace delmesh::cli {

ProgressLogSink::ProgressLogSink(std::ostream& out, Settings settings, std::function<double()> now)
    : out_(out), settings_(settings), now_(std::move(now)), start_(now_()) {}

void ProgressLogSink::end_line() {
  if (!line_open_) return;
  out_ << '\n';
  line_open_ = false;
  line_width_ = 0;
}

void ProgressLogSink::finish_line() {
  const std::lock_guard lock(mutex_);
  end_line();
}

void ProgressLogSink::set_phase(std::string_view phase) {
  const std::lock_guard lock(mutex_);
  phase_ = phase;
  status_.clear();
}

void ProgressLogSink::tick() {
  const std::lock_guard lock(mutex_);
  show_if_due();
}

void ProgressLogSink::show_if_due() {
  if (settings_.quiet) return;
  const double t = now_();
  if (t - start_ < settings_.delay) return;
  if (last_shown_ >= 0 && t - last_shown_ < settings_.interval) return;
  last_shown_ = t;
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.1f s", t - start_);
  std::string line = phase_.empty() ? std::string(seconds) : phase_ + " " + seconds;
  if (!status_.empty()) line += ": " + status_;
  if (settings_.terminal) {
    out_ << '\r' << line;
    if (line.size() < line_width_) out_ << std::string(line_width_ - line.size(), ' ');
    out_ << std::flush;
    line_open_ = true;
    line_width_ = line.size();
  } else {
    out_ << line << '\n' << std::flush;
  }
}

void ProgressLogSink::write(LogLevel level, std::string_view message) {
  const std::lock_guard lock(mutex_);
  switch (level) {
    case LogLevel::Progress:
      status_ = message;
      show_if_due();
      return;
    case LogLevel::Warning:
      end_line();
      out_ << "warning: " << message << '\n';
      return;
    case LogLevel::Info:
      status_ = message;
      if (settings_.quiet || !settings_.verbose) return;
      end_line();
      out_ << message << '\n';
      return;
    case LogLevel::Debug:
      if (settings_.quiet || !settings_.verbose) return;
      end_line();
      out_ << message << '\n';
      return;
  }
}

namespace {

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

ProgressLogSink::Settings stderr_settings(bool quiet, bool verbose) {
  ProgressLogSink::Settings settings;
  settings.quiet = quiet;
  settings.verbose = verbose;
  settings.terminal = isatty(STDERR_FILENO) != 0;
  return settings;
}

}  // namespace

StderrProgress::StderrProgress(bool quiet, bool verbose)
    : sink_(std::cerr, stderr_settings(quiet, verbose), steady_seconds),
      ticker_([this](std::stop_token stop) {
        while (!stop.stop_requested()) {
          std::this_thread::sleep_for(std::chrono::milliseconds(100));
          sink_.tick();
        }
      }) {}

void StderrProgress::stop() {
  if (ticker_.joinable()) {
    ticker_.request_stop();
    ticker_.join();
  }
  sink_.finish_line();
}

StderrProgress::~StderrProgress() { stop(); }

}  // namespace delmesh::cli
