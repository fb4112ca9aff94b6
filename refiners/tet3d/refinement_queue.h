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
// the other entries, so the pops are the same as without sweeps. Buckets are
// MappedArrays (toolkit/core/mapped_array.h) with their own mapping from 4 KB, which grow
// and shrink by remapping, without copying, and give their storage back as they drain:
// a bucket whose entries fill half its capacity or less is shrunk to 3/2 of its size
// (amortized constant time per pop, as for growth by doubling; the slack keeps a bucket
// that hovers at a size from growing and shrinking at every step). The queue is largest
// at the start of the stage (every tet is considered once) and drains while the mesh
// grows, so memory the queue kept would add to the peak at the end of the run. Deque
// buckets (512-byte blocks from the heap) left their freed blocks scattered among other
// small allocations: on cgal-bear at radius-edge 1.414 the heap ended the stage with
// 8.7 MB free but resident (heap 15.6 MB; malloc_trim could give back only about 4 MB of
// it), while a bucket here sits in a mapping of its own from 4 KB that goes back to the
// system when it is freed or shrunk.
// (From 1 MB only, the MappedArray default, small buckets grew by realloc in the heap and
// left holes there too: cgal-fandisk's peak went up by 0.9 MB instead of down.) Peak RSS
// of `delmesh mesh --radius-edge 1.414` with deque buckets -> these (with the other
// end-of-run savings of result_extraction.h and small_angles.cpp; MB = 2^20 bytes):
// cgal-bear 121.7 -> 116.4 MB, cgal-bunny00 355.4 -> 331.2 MB, cgal-fandisk 72.2 ->
// 70.4 MB. Pages given back are faulted in again when a bucket regrows: cgal-bear 49447 ->
// 55680 page faults for the whole run.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "toolkit/core/mapped_array.h"

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
    Bucket& bucket = buckets_[top_];
    const QueuedTet e = bucket.back();
    bucket.pop_back();
    --size_;
    shrink_if_sparse(bucket);
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
      bucket.resize(static_cast<std::size_t>(std::remove_if(bucket.begin(), bucket.end(), stale) - bucket.begin()));
      shrink_if_sparse(bucket);
      size_ += bucket.size();
    }
    sweep_at_ = std::max(kFirstSweep, 2 * size_);
  }

 private:
  static constexpr std::size_t kFirstSweep = 1u << 16;
  /// A bucket of 4 KB or more has its own mapping: growing and shrinking leave no holes
  /// in the heap.
  using Bucket = MappedArray<QueuedTet, 4096>;
  /// Buckets below this capacity keep their storage (small blocks, no churn).
  static constexpr std::size_t kShrinkCapacity = 1u << 8;

  /// Shrinks a bucket filled to half its capacity or less to 3/2 of its size.
  static void shrink_if_sparse(Bucket& bucket) {
    if (bucket.capacity() < kShrinkCapacity || 2 * bucket.size() > bucket.capacity()) return;
    bucket.shrink_capacity(bucket.size() + bucket.size() / 2);
  }

  std::vector<Bucket> buckets_;
  int top_ = 0;
  std::size_t size_ = 0;
  std::size_t sweep_at_ = kFirstSweep;
};

}  // namespace delmesh::tet3d
