// The log of the deferred-split trials (refiners/tet3d/deferred_split.h) follows the
// result: every polish run whose line is on the log is a round of the result (the
// improvement's "N rounds" line counts them), so neither the polish alone a trial is
// judged against nor the splits and polish of an undone trial leave a line; an undone
// trial leaves one line with its counts, a kept one its polish's line and the "kept" line.
//   * tests/data/mesh/tetgen_example.poly with the window [25, 145] alone (as `delmesh
//     mesh F --min-dihedral 25 --max-dihedral 145`): one trial, 1 split,
//     undone (3 tets outside the window away from small angles before it, 3 after the
//     splits and the polish).
//   * cgal-boeing from the corpus with [20, 150] (default radius-edge 2, as the
//     polish's corpus tests run it): two trials kept (4 -> 2 -> 0); skipped
//     without the corpus.
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "importers/import.h"
#include "refiners/tet3d/mesh_plc.h"
#include "tests/support/test_paths.h"

namespace delmesh::test {
namespace {

class InfoLines final : public LogSink {
 public:
  void write(LogLevel level, std::string_view message) override {
    if (level == LogLevel::Info) lines.emplace_back(message);
  }
  std::vector<std::string> lines;
};

struct TrialLog {
  std::size_t polish_lines = 0;  ///< "mesh: slivers N -> M tets outside ..." (one per polish run)
  std::size_t rounds = 0;        ///< from "mesh: slivers: N rounds, ..."
  std::size_t kept = 0, undone = 0;
  std::vector<std::string> undone_lines;
};

/// Meshes `path` with `options` and the window [low, high], and reads the log.
TrialLog mesh_and_read_log(const std::filesystem::path& path, MeshOptions options, double low, double high) {
  TrialLog result;
  auto plc = import_file(path, ImportOptions{});
  EXPECT_TRUE(plc.has_value()) << path;
  if (!plc) return result;
  InfoLines sink;
  options.min_dihedral_deg = low;
  options.max_dihedral_deg = high;
  options.log = &sink;
  const auto r = mesh_plc(*plc, options);
  EXPECT_TRUE(r.has_value()) << path;
  const std::string rounds = "mesh: slivers: ";
  for (const std::string& line : sink.lines) {
    if (line.rfind("mesh: slivers ", 0) == 0 && line.find(" tets outside the dihedral window (") != std::string::npos)
      ++result.polish_lines;
    if (line.rfind(rounds, 0) == 0 && line.find(" rounds, ") != std::string::npos)
      result.rounds = std::stoul(line.substr(rounds.size()));
    if (line == "mesh: slivers: subsegment splits kept after the polish") ++result.kept;
    if (line.rfind("mesh: slivers: subsegment splits undone after the polish (", 0) == 0) {
      ++result.undone;
      result.undone_lines.push_back(line);
    }
  }
  return result;
}

TEST(Tet3dDeferredSplitLog, AnUndoneTrialLeavesOneLineAndNoneOfItsSteps) {
  MeshOptions window_alone;  // as `delmesh mesh` without --radius-edge (-q) and -a
  window_alone.quality = false;
  window_alone.region_max_volume = false;
  const TrialLog log =
      mesh_and_read_log(test_data_dir() / "mesh" / "tetgen_example.poly", window_alone, 25.0, 145.0);
  EXPECT_EQ(log.kept, 0u);
  // The splits at every tet together, then at each tet alone where a split is made at all
  // (tet 2 of 3 only): each trial undone leaves its line.
  ASSERT_EQ(log.undone, 2u);
  EXPECT_EQ(log.undone_lines[0],
            "mesh: slivers: subsegment splits undone after the polish (1 splits at every tet; tets outside the window "
            "away from small angles 3 before the trial, 3 after the polish alone, 3 after the splits and the polish)");
  EXPECT_EQ(log.undone_lines[1],
            "mesh: slivers: subsegment splits undone after the polish (1 splits at tet 2 of 3; tets outside the "
            "window away from small angles 3 before the trial, 3 after the polish alone, 3 after the splits and the "
            "polish)");
  EXPECT_EQ(log.polish_lines, log.rounds) << "a polish run of the undone trial is on the log";
}

TEST(Tet3dDeferredSplitLog, KeptTrialsLeaveTheirPolishButNotThePolishAlone) {
  const auto path = corpus_dir() / "surface" / "cgal-boeing.off";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no corpus at " << corpus_dir();
  const TrialLog log = mesh_and_read_log(path, MeshOptions{}, 20.0, 150.0);
  EXPECT_EQ(log.kept, 2u);
  EXPECT_EQ(log.undone, 0u);
  EXPECT_EQ(log.polish_lines, log.rounds) << "the polish alone of a kept trial is on the log";
}

}  // namespace
}  // namespace delmesh::test
