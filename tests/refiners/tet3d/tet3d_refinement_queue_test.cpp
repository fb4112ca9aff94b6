// RefinementQueue (refiners/tet3d/refinement_queue.h): worst bucket first, LIFO within a
// bucket, and drop_stale(), which sweeps stale entries out once the queue has doubled
// and must leave the sequence of live pops unchanged.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "refiners/tet3d/refinement_queue.h"

namespace delmesh::tet3d {
namespace {

QueuedTet entry(std::uint32_t t) { return {t, {t, t + 1, t + 2, t + 3}}; }

// Badness keys spread over many buckets, with repeats (LIFO order within a bucket).
double key_of(std::uint32_t t) { return static_cast<double>((t * 7919u) % 97u) * 0.25; }

bool stale(const QueuedTet& e) { return e.tet % 3 == 1; }

std::vector<std::uint32_t> live_pops(RefinementQueue& queue) {
  std::vector<std::uint32_t> out;
  while (!queue.empty()) {
    const QueuedTet e = queue.pop();
    if (!stale(e)) out.push_back(e.tet);
  }
  return out;
}

TEST(RefinementQueue, PopsWorstBucketFirstAndLastInFirstWithinABucket) {
  RefinementQueue queue;
  queue.push(entry(1), 0.0);
  queue.push(entry(2), 5.0);
  queue.push(entry(3), 0.0);
  queue.push(entry(4), 5.0);
  queue.push(entry(5), 1.0);
  std::vector<std::uint32_t> order;
  while (!queue.empty()) order.push_back(queue.pop().tet);
  EXPECT_EQ(order, (std::vector<std::uint32_t>{4, 2, 5, 3, 1}));
}

TEST(RefinementQueue, DropStaleWaitsUntilTheQueueIsLarge) {
  RefinementQueue queue;
  for (std::uint32_t t = 0; t < 1000; ++t) queue.push(entry(t), key_of(t));
  std::size_t calls = 0;
  queue.drop_stale([&](const QueuedTet& e) {
    ++calls;
    return stale(e);
  });
  EXPECT_EQ(calls, 0u);
  EXPECT_EQ(queue.size(), 1000u);
}

TEST(RefinementQueue, DropStaleKeepsTheLivePopSequence) {
  constexpr std::uint32_t kCount = 200000;
  RefinementQueue swept, plain;
  for (std::uint32_t t = 0; t < kCount; ++t) {
    swept.push(entry(t), key_of(t));
    plain.push(entry(t), key_of(t));
    swept.drop_stale(stale);
  }
  // Sweeps ran (the queue passed 2^16 entries): only live entries and the ones pushed
  // since the last sweep remain, far fewer than were pushed.
  std::size_t live = 0;
  for (std::uint32_t t = 0; t < kCount; ++t) live += !stale(entry(t));
  EXPECT_LT(swept.size(), kCount);
  EXPECT_GE(swept.size(), live);
  EXPECT_EQ(plain.size(), kCount);
  EXPECT_EQ(live_pops(swept), live_pops(plain));
}

TEST(RefinementQueue, SweepsAgainOnlyAfterTheQueueDoubles) {
  RefinementQueue queue;
  for (std::uint32_t t = 0; t < (1u << 16); ++t) queue.push(entry(3 * t), key_of(t));  // all live
  std::size_t calls = 0;
  auto counting = [&](const QueuedTet& e) {
    ++calls;
    return stale(e);
  };
  queue.drop_stale(counting);
  EXPECT_EQ(calls, std::size_t{1} << 16);
  // 2^16 live entries stay: the next sweep waits for 2^17.
  calls = 0;
  for (std::uint32_t t = 0; t < 1000; ++t) queue.push(entry(3 * t + 1), key_of(t));
  queue.drop_stale(counting);
  EXPECT_EQ(calls, 0u);
  for (std::uint32_t t = 0; t < (1u << 16); ++t) queue.push(entry(3 * t + 1), key_of(t));
  queue.drop_stale(counting);
  EXPECT_EQ(calls, (std::size_t{1} << 17) + 1000);
  EXPECT_EQ(queue.size(), std::size_t{1} << 16);
}

}  // namespace
}  // namespace delmesh::tet3d
