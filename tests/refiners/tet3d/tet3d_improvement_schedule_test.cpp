// Passes and tries of the improvement pass (refiners/tet3d/improvement_schedule.h): the
// stopping rule, the per-step budgets, insertion tried once per four vertices, and on a
// corpus input the pass's own figures (passes, tries) within the bounds the schedule sets,
// in each of its runs (improvement_rounds.h).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "importers/import.h"
#include "refiners/tet3d/improvement_rounds.h"
#include "refiners/tet3d/improvement_schedule.h"
#include "refiners/tet3d/mesh_plc.h"
#include "tests/support/test_paths.h"
#include "toolkit/core/log.h"

namespace delmesh::tet3d {
namespace {

TEST(Tet3dImprovementSchedule, NoPassAfterOneThatChangedNothingOrLeftNothing) {
  const ImprovementSchedule schedule(100);
  EXPECT_TRUE(schedule.another_pass(1, 100, 40, true));
  EXPECT_FALSE(schedule.another_pass(1, 100, 40, false));  // nothing changed: it would do the same
  EXPECT_FALSE(schedule.another_pass(1, 100, 0, true));    // nothing left to improve
}

TEST(Tet3dImprovementSchedule, LaterPassesNeedTheMinimumGain) {
  const ImprovementSchedule schedule(1000);
  // A pass that started with 200 bad tets must end with at most 190 (5%).
  EXPECT_TRUE(schedule.another_pass(2, 200, 190, true));
  EXPECT_FALSE(schedule.another_pass(2, 200, 191, true));
  EXPECT_FALSE(schedule.another_pass(3, 200, 230, true));  // the pass made more bad tets
  EXPECT_TRUE(schedule.another_pass(3, 200, 100, true));
  EXPECT_FALSE(schedule.another_pass(kMaxPasses, 200, 100, true));
}

TEST(Tet3dImprovementSchedule, EachStepHasItsOwnBudget) {
  ImprovementSchedule schedule(3);
  const std::size_t budget = 3 * kTriesPerBadTet;
  for (std::size_t k = 0; k < budget; ++k) ASSERT_TRUE(schedule.take(ImprovementStep::Insertion)) << k;
  EXPECT_FALSE(schedule.take(ImprovementStep::Insertion));
  EXPECT_EQ(schedule.taken(ImprovementStep::Insertion), budget);
  EXPECT_TRUE(schedule.take(ImprovementStep::Flips));
  EXPECT_TRUE(schedule.take(ImprovementStep::Smoothing));
  EXPECT_TRUE(schedule.take(ImprovementStep::Deletion));
  EXPECT_EQ(schedule.taken(ImprovementStep::Flips), 1u);

  ImprovementSchedule none(0);
  EXPECT_FALSE(none.take(ImprovementStep::Flips));
  EXPECT_EQ(none.taken(ImprovementStep::Flips), 0u);
}

TEST(Tet3dImprovementSchedule, InsertionTriedOncePerFourVertices) {
  ImprovementSchedule schedule(10);
  EXPECT_FALSE(schedule.insertion_tried({4, 9, 2, 7}));
  schedule.record_insertion({4, 9, 2, 7});
  EXPECT_TRUE(schedule.insertion_tried({4, 9, 2, 7}));
  EXPECT_TRUE(schedule.insertion_tried({7, 2, 9, 4}));  // the same tet, vertices in another order
  EXPECT_FALSE(schedule.insertion_tried({4, 9, 2, 8}));
}

/// Keeps the improvement pass's summary lines ("mesh: slivers B -> A tets ..."), one per
/// run (improvement_rounds.h runs it up to kMaxImprovementRounds times with a window).
class SliverLineSink : public LogSink {
 public:
  void write(LogLevel, std::string_view message) override {
    if (message.starts_with("mesh: slivers ") && message.find(" -> ") != std::string_view::npos)
      lines.emplace_back(message);
  }
  std::vector<std::string> lines;
};

/// The number just before `word` in `line` ("..., 4 passes, ..."), or -1.
long long number_before(const std::string& line, const std::string& word) {
  const std::size_t at = line.find(" " + word);
  if (at == std::string::npos) return -1;
  std::size_t start = at;
  while (start > 0 && line[start - 1] >= '0' && line[start - 1] <= '9') --start;
  return start == at ? -1 : std::stoll(line.substr(start, at - start));
}

TEST(Tet3dImprovementSchedule, CorpusRunStaysWithinTheSchedule) {
  // gmsh-part.step with the 20 / 150 window: some 2800 tets outside the window before the
  // pass; the pass ends within kMaxPasses and at most kTriesPerBadTet tries of each of
  // its four steps per bad tet, and it stops early when a pass gains little (fewer than
  // kMaxPasses passes here: the later passes gain a few tets each).
  auto plc = import_file(test::corpus_dir() / "step" / "gmsh-part.step", ImportOptions{});
  ASSERT_TRUE(plc.has_value()) << plc.error().message;
  SliverLineSink sink;
  MeshOptions options;
  options.min_dihedral_deg = 20.0;
  options.max_dihedral_deg = 150.0;
  options.log = &sink;
  auto r = mesh_plc(*plc, options);
  ASSERT_TRUE(r.has_value()) << r.error().message;
  ASSERT_FALSE(sink.lines.empty());
  ASSERT_LE(sink.lines.size(), static_cast<std::size_t>(kMaxImprovementRounds));
  long long after = -1;
  for (std::size_t k = 0; k < sink.lines.size(); ++k) {
    const std::string& line = sink.lines[k];
    std::printf("%s\n", line.c_str());
    const long long before = std::stoll(line.substr(std::string("mesh: slivers ").size()));
    const long long passes = number_before(line, "passes"), tries = number_before(line, "tries");
    ASSERT_GT(before, 0);
    ASSERT_GE(passes, 1);
    ASSERT_GE(tries, 0);
    // Each run starts from the tets the one before left.
    if (k > 0) {
      EXPECT_EQ(before, after);
    }
    after = std::stoll(line.substr(line.find(" -> ") + 4));
    if (k == 0) {
      EXPECT_LT(after, before / 10);
    }
    EXPECT_LT(passes, kMaxPasses);
    EXPECT_LE(tries, static_cast<long long>(4 * kTriesPerBadTet) * before);
  }
  EXPECT_EQ(static_cast<std::size_t>(after), r->stats.outside_dihedral_at_small_angles +
                                                  r->stats.outside_dihedral_elsewhere);
}

}  // namespace
}  // namespace delmesh::tet3d
