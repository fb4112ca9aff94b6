// Progress of a running mesh_plc (MeshOptions::progress and Progress-level log lines): the
// stage in progress and how far it has got (vertices, tets, Steiner points, queue sizes).
// Every vertex insertion polls the reporter; it reads the clock once every kPollStride
// polls and reports at most every kInterval seconds, so the cost is a counter increment
// per insertion.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

#include "refiners/tet3d/mesh_plc.h"

namespace delmesh::tet3d {

struct RefineState;

class ProgressReporter {
 public:
  static constexpr unsigned kPollStride = 64;
  static constexpr double kInterval = 0.25;

  explicit ProgressReporter(const MeshOptions& options);

  /// Enters a stage and reports at once.
  void begin_stage(const char* stage, const RefineState& state);
  /// Reports if kInterval has passed since the last report.
  void poll(const RefineState& state) {
    if (++polls_ % kPollStride == 0) poll_clock(state);
  }
  /// The snapshot of `state` now.
  MeshProgress snapshot(const RefineState& state) const;

 private:
  void poll_clock(const RefineState& state);
  void report(const RefineState& state);

  const MeshOptions& options_;
  bool enabled_;
  const char* stage_ = "";
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_;
  unsigned polls_ = 0;
};

/// One line of text for a snapshot: "quality: 1200 vertices, 6100 tets, ...".
std::string describe(const MeshProgress& progress);

}  // namespace delmesh::tet3d
