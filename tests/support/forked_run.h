// Runs a piece of test work in a child process with a hang guard, for corpus-wide tests:
// a hang (no answer within the time given) or a crash fails that input alone instead of
// stalling or killing the suite. The work returns its findings as text (GoogleTest's
// assertions do not cross fork()); an exception escaping the work is caught in the child
// and reported as `threw` with its message as the text.
#pragma once

#include <functional>
#include <string>

namespace delmesh::test {

struct ForkedRun {
  bool finished = false;  ///< answered within the time given
  bool crashed = false;   ///< killed by a signal or an unexpected exit status
  bool threw = false;     ///< the work threw; `text` is the exception's message
  int signal = 0;
  std::string text;  ///< what the work returned (or the exception message)
};

/// Runs `work` in a forked child; kills it after `hang_seconds`.
ForkedRun run_forked(const std::function<std::string()>& work, int hang_seconds);

/// GoogleTest verdict on the run of one corpus input whose text is a summary line and then
/// one finding per line: a hang, a crash or an exception is a failure; otherwise the
/// summary is printed and recorded and every finding is a failure.
void report_findings(const std::string& input, const ForkedRun& run, int hang_seconds);

}  // namespace delmesh::test
