// Bucketed worst-first queue of tets for quality refinement (ARCHITECTURE.md §4.6):
// a tet is filed under a bucket chosen from the logarithm of its badness and popped
// from the worst non-empty bucket, LIFO within a bucket (good locality, no heap). Entries
// carry the tet's four vertices; an entry whose tet slot no longer holds them is stale
// and is dropped when popped (lazy deletion: the queue is never searched for a tet).
//
// Memory: on large inputs most entries go stale before they are popped (the tet dies in
// the cavity of a nearby insertion), and with lazy deletion alone they would pile up to
// several entries per live tet. drop_stale() sweeps them out whenever the queue has
// doubled since the last sweep (amortized constant time per push), keeping the order of
// the other entries, so the pops are the same as without sweeps. Buckets are deques:
// they grow by fixed blocks and give blocks back as they drain, where a vector would keep
// up to twice its largest size.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <vector>

namespace delmesh::tet3d {

struct QueuedTet {
  std::uint32_t tet;
  std::array<std::uint32_t, 4> v;
};

class RefinementQueue {
 public:
  static constexpr int kBuckets = 256;

  RefinementQueue() : buckets_(kBuckets) {}

  /// Files a tet with badness `key` (>= 0, larger is worse).
  void push(const QueuedTet& entry, double key) {
    int b = key > 0.0 ? static_cast<int>(16.0 * std::log2(1.0 + key)) : 0;
    if (b < 0) b = 0;
    if (b >= kBuckets) b = kBuckets - 1;
    buckets_[b].push_back(entry);
    if (b > top_) top_ = b;
    ++size_;
  }

  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }

  /// Removes and returns the entry of the worst bucket. Requires !empty().
  QueuedTet pop() {
    while (buckets_[top_].empty()) --top_;
    QueuedTet e = buckets_[top_].back();
    buckets_[top_].pop_back();
    --size_;
    return e;
  }

  /// Once the queue has doubled since the last sweep: erases every entry for which
  /// `stale(entry)` holds, keeping the others in order. Staleness must be permanent (an
  /// entry found stale would never be popped as live later): true of tets destroyed by
  /// Bowyer–Watson insertions, which never come back.
  template <class Stale>
  void drop_stale(Stale stale) {
    if (size_ < sweep_at_) return;
    size_ = 0;
    for (auto& bucket : buckets_) {
      bucket.erase(std::remove_if(bucket.begin(), bucket.end(), stale), bucket.end());
      size_ += bucket.size();
    }
    sweep_at_ = std::max(kFirstSweep, 2 * size_);
  }

 private:
  static constexpr std::size_t kFirstSweep = 1u << 16;

  std::vector<std::deque<QueuedTet>> buckets_;
  int top_ = 0;
  std::size_t size_ = 0;
  std::size_t sweep_at_ = kFirstSweep;
};

}  // namespace delmesh::tet3d
