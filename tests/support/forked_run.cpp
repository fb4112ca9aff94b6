// Forked test runs with a hang guard (see forked_run.h).
#include "tests/support/forked_run.h"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <sstream>

namespace delmesh::test {
namespace {
constexpr int kExitThrew = 3;  ///< the child's exit status when the work threw
}  // namespace

ForkedRun run_forked(const std::function<std::string()>& work, int hang_seconds) {
  ForkedRun run;
  int fds[2];
  if (pipe(fds) != 0) {
    run.crashed = true;
    run.text = "pipe() failed";
    return run;
  }
  std::fflush(nullptr);
  const pid_t child = fork();
  if (child < 0) {
    close(fds[0]);
    close(fds[1]);
    run.crashed = true;
    run.text = "fork() failed";
    return run;
  }
  if (child == 0) {
    close(fds[0]);
    std::string text;
    int exit_status = 0;
    try {
      text = work();
    } catch (const std::exception& e) {
      text = std::string("exception from the library: ") + e.what();
      exit_status = kExitThrew;
    } catch (...) {
      text = "unknown exception from the library";
      exit_status = kExitThrew;
    }
    for (std::size_t done = 0; done < text.size();) {
      const ssize_t n = write(fds[1], text.data() + done, text.size() - done);
      if (n <= 0) break;
      done += static_cast<std::size_t>(n);
    }
    close(fds[1]);
    _exit(exit_status);
  }
  close(fds[1]);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(hang_seconds);
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    pollfd p{fds[0], POLLIN, 0};
    if (poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
    char buffer[4096];
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n <= 0) {
      run.finished = true;  // end of file: the child is done
      break;
    }
    run.text.append(buffer, static_cast<std::size_t>(n));
  }
  close(fds[0]);
  if (!run.finished) kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  if (run.finished && WIFEXITED(status) && WEXITSTATUS(status) == kExitThrew) {
    run.threw = true;
  } else if (run.finished && !(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
    run.crashed = true;
    run.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  }
  return run;
}

void report_findings(const std::string& input, const ForkedRun& run, int hang_seconds) {
  if (!run.finished) {
    ADD_FAILURE() << input << ": did not terminate within " << hang_seconds << " s";
    return;
  }
  if (run.crashed) {
    ADD_FAILURE() << input << ": the run crashed (signal " << run.signal << ")";
    return;
  }
  if (run.threw) {
    // Internal errors (DELMESH_CHECK) must not reach the caller as exceptions.
    ADD_FAILURE() << input << ": " << run.text;
    return;
  }
  std::istringstream lines(run.text);
  std::string summary;
  std::getline(lines, summary);
  std::printf("%-38s %s\n", input.c_str(), summary.c_str());
  ::testing::Test::RecordProperty("summary", summary);
  for (std::string finding; std::getline(lines, finding);) ADD_FAILURE() << input << ": " << finding;
}

}  // namespace delmesh::test
