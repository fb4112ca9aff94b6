// The lookup tables of the boundary elements of 3D Delaunay refinement: subsegment edge
// key -> segment id (RefineState::subsegments) and subfacet face key -> facet id
// (RefineState::subfaces). Every insertion asks them about every edge and face of its
// cavity (notes §4.2.1: the queues must hold every element that may be missing or
// encroached), so they are the hottest lookups of the refinement.
//
// Two measures make those lookups cheap:
//   - a per-vertex flag, set for every vertex of every key ever stored and never
//     cleared: an edge or face with an unflagged vertex (a vertex inserted in the
//     interior for quality, or one on a facet when asking for a subsegment) is answered
//     "absent" from a byte array without hashing;
//   - a flat open-addressing table with linear probing (load factor at most 3/4: 17
//     bytes per slot with its tag, so 23 to 45 bytes per stored key; a miss reads a few
//     more tag bytes than at 1/2, in one cache line, for half the memory) and
//     the home slot chosen from the smallest vertex of the key only, so the subsegments
//     and subfacets of one vertex lie next to each other (the edges and faces of a
//     cavity share few vertices: their lookups share cache lines), and
//     backward-shift deletion (no tombstones, so probe sequences stay short however many
//     subfacets are split and replaced), instead of node-based std::unordered_map; the
//     probes read a parallel array of one-byte hash tags (as in SwissTable), so a lookup
//     of an absent key, the common case, reads no slot.
// The interface is the subset of std::unordered_map the refinement uses (find, count,
// at, operator[], emplace, erase, iteration over std::pair<Key, id>). Iteration order
// depends only on the sequence of insertions and erasures: deterministic.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "toolkit/core/error.h"

namespace delmesh::tet3d {

/// Edge keys: (min << 32) | max of the two vertex ids.
struct EdgeKeyTraits {
  using Key = std::uint64_t;
  static constexpr int kVertices = 2;
  static Key empty() { return ~std::uint64_t{0}; }
  static bool equal(Key x, Key y) { return x == y; }
  /// Home: from the smaller vertex only (times kHomeMultiplier). Tag: from the other.
  static constexpr std::uint64_t kHomeMultiplier = 0x9E3779B97F4A7C15ULL;
  static std::uint64_t home_hash(Key k) { return (k >> 32) * kHomeMultiplier; }
  static std::uint8_t tag_hash(Key k) { return static_cast<std::uint8_t>(((k & 0xFFFFFFFFu) * 0xD6E8FEB86659FD93ULL) >> 57); }
  static std::uint32_t vertex(Key k, int i) {
    return i == 0 ? static_cast<std::uint32_t>(k >> 32) : static_cast<std::uint32_t>(k);
  }
};

/// Face keys: the three vertex ids in increasing order.
struct FaceKeyTraits {
  using Key = std::array<std::uint32_t, 3>;
  static constexpr int kVertices = 3;
  static Key empty() { return {~0u, ~0u, ~0u}; }
  /// Member-wise (std::array's operator== may become a memcmp call).
  static bool equal(const Key& x, const Key& y) { return x[0] == y[0] && x[1] == y[1] && x[2] == y[2]; }
  /// Home: from the smallest vertex only (times kHomeMultiplier). Tag: from the other two.
  static constexpr std::uint64_t kHomeMultiplier = 0x9E3779B97F4A7C15ULL;
  static std::uint64_t home_hash(const Key& k) { return k[0] * kHomeMultiplier; }
  static std::uint8_t tag_hash(const Key& k) {
    return static_cast<std::uint8_t>((((k[1] * 0x9E3779B97F4A7C15ULL) ^ k[2]) * 0xD6E8FEB86659FD93ULL) >> 57);
  }
  static std::uint32_t vertex(const Key& k, int i) { return k[static_cast<std::size_t>(i)]; }
};

template <class Traits>
class BoundaryTable {
 public:
  using Key = typename Traits::Key;
  using value_type = std::pair<Key, std::uint32_t>;

  template <bool Const>
  class Iter {
   public:
    using Slot = std::conditional_t<Const, const value_type, value_type>;
    Iter() = default;
    Iter(Slot* at, Slot* end) : at_(at), end_(end) { skip(); }
    Slot& operator*() const { return *at_; }
    Slot* operator->() const { return at_; }
    Iter& operator++() {
      ++at_;
      skip();
      return *this;
    }
    friend bool operator==(const Iter& x, const Iter& y) { return x.at_ == y.at_; }
    operator Iter<true>() const { return Iter<true>(at_, end_); }

   private:
    void skip() {
      while (at_ != end_ && Traits::equal(at_->first, Traits::empty())) ++at_;
    }
    Slot* at_ = nullptr;
    Slot* end_ = nullptr;
  };
  using iterator = Iter<false>;
  using const_iterator = Iter<true>;

  BoundaryTable() { rehash(64); }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  /// Changes with every insertion and erasure (for caches of lookups).
  std::uint64_t version() const { return version_; }

  iterator begin() { return {slots_.data(), slots_.data() + slots_.size()}; }
  iterator end() { return {slots_.data() + slots_.size(), slots_.data() + slots_.size()}; }
  const_iterator begin() const { return {slots_.data(), slots_.data() + slots_.size()}; }
  const_iterator end() const { return {slots_.data() + slots_.size(), slots_.data() + slots_.size()}; }

  /// False when some vertex of `key` was never a vertex of a stored key: then the key is
  /// absent, and the caller need not build or look it up.
  bool may_hold(std::uint32_t v) const { return v < flags_.size() && flags_[v]; }

  /// Starts fetching the tag and slot where the keys whose smallest vertex is v begin
  /// their probes (every key's home slot comes from its smallest vertex), so that lookups
  /// of several such keys soon after find them in cache.
  void prefetch_home(std::uint32_t v) const {
    const std::size_t i = static_cast<std::size_t>((v * Traits::kHomeMultiplier) >> shift_);
    __builtin_prefetch(&tags_[i]);
    __builtin_prefetch(&slots_[i]);
  }

  iterator find(const Key& key) {
    const std::size_t i = slot_of(key);
    return i == kNoSlot ? end() : iterator(slots_.data() + i, slots_.data() + slots_.size());
  }
  const_iterator find(const Key& key) const {
    const std::size_t i = slot_of(key);
    return i == kNoSlot ? end() : const_iterator(slots_.data() + i, slots_.data() + slots_.size());
  }
  /// The stored id of `key`, or nullptr.
  const std::uint32_t* lookup(const Key& key) const {
    const std::size_t i = slot_of(key);
    return i == kNoSlot ? nullptr : &slots_[i].second;
  }
  std::size_t count(const Key& key) const { return slot_of(key) != kNoSlot; }
  bool contains(const Key& key) const { return slot_of(key) != kNoSlot; }

  std::uint32_t at(const Key& key) const {
    const std::size_t i = slot_of(key);
    DELMESH_CHECK(i != kNoSlot, "boundary table: key not present");
    return slots_[i].second;
  }

  std::pair<iterator, bool> emplace(const Key& key, std::uint32_t value) {
    DELMESH_CHECK(!Traits::equal(key, Traits::empty()), "boundary table: reserved key");
    if (const std::size_t found = slot_of(key); found != kNoSlot)
      return {iterator(slots_.data() + found, slots_.data() + slots_.size()), false};
    if (4 * (size_ + 1) > 3 * slots_.size()) rehash(2 * slots_.size());
    std::size_t i = home_of(key);
    while (tags_[i] != 0) i = (i + 1) & mask_;
    tags_[i] = tag_of(key);
    slots_[i] = {key, value};
    ++size_;
    ++version_;
    for (int k = 0; k < Traits::kVertices; ++k) flag(Traits::vertex(key, k));
    return {iterator(slots_.data() + i, slots_.data() + slots_.size()), true};
  }

  std::uint32_t& operator[](const Key& key) { return emplace(key, 0).first->second; }

  std::size_t erase(const Key& key) {
    std::size_t i = slot_of(key);
    if (i == kNoSlot) return 0;
    // Backward-shift deletion: pull later entries of the probe run into the hole unless
    // their home lies cyclically after the hole.
    std::size_t j = i;
    while (true) {
      j = (j + 1) & mask_;
      if (tags_[j] == 0) break;
      const std::size_t h = home_of(slots_[j].first);
      const bool stays = i <= j ? (i < h && h <= j) : (i < h || h <= j);
      if (stays) continue;
      slots_[i] = slots_[j];
      tags_[i] = tags_[j];
      i = j;
    }
    slots_[i].first = Traits::empty();
    tags_[i] = 0;
    --size_;
    ++version_;
    return 1;
  }

  void clear() {
    for (auto& s : slots_) s.first = Traits::empty();
    std::fill(tags_.begin(), tags_.end(), std::uint8_t{0});
    size_ = 0;
    ++version_;
  }

 private:
  static constexpr std::size_t kNoSlot = ~std::size_t{0};

  /// Home slot: the top bits of the home hash. Tag: 7 bits of the tag hash, with the high
  /// bit set (0 marks an empty slot).
  std::size_t home_of(const Key& key) const { return static_cast<std::size_t>(Traits::home_hash(key) >> shift_); }
  static std::uint8_t tag_of(const Key& key) { return static_cast<std::uint8_t>(0x80u | Traits::tag_hash(key)); }

  /// Probes the tag bytes (a small array that stays in cache) and reads a slot only on a
  /// matching tag: most lookups are for absent keys and touch no slot at all.
  std::size_t slot_of(const Key& key) const {
    const std::uint8_t tag = tag_of(key);
    std::size_t i = home_of(key);
    while (true) {
      const std::uint8_t t = tags_[i];
      if (t == 0) return kNoSlot;
      if (t == tag && Traits::equal(slots_[i].first, key)) return i;
      i = (i + 1) & mask_;
    }
  }

  void flag(std::uint32_t v) {
    if (v >= flags_.size()) flags_.resize(std::max<std::size_t>(2 * flags_.size(), v + 1024), 0);
    flags_[v] = 1;
  }

  void rehash(std::size_t capacity) {
    std::vector<value_type> old = std::move(slots_);
    slots_.assign(capacity, value_type{Traits::empty(), 0});
    tags_.assign(capacity, 0);
    mask_ = capacity - 1;
    shift_ = 64 - static_cast<int>(std::countr_zero(capacity));
    for (const value_type& s : old) {
      if (Traits::equal(s.first, Traits::empty())) continue;
      std::size_t i = home_of(s.first);
      while (tags_[i] != 0) i = (i + 1) & mask_;
      tags_[i] = tag_of(s.first);
      slots_[i] = s;
    }
  }

  std::vector<value_type> slots_;
  std::vector<std::uint8_t> tags_;
  std::vector<std::uint8_t> flags_;
  std::size_t size_ = 0;
  std::uint64_t version_ = 0;
  std::size_t mask_ = 0;
  int shift_ = 64;
};

using SubsegmentTable = BoundaryTable<EdgeKeyTraits>;
using SubfaceTable = BoundaryTable<FaceKeyTraits>;

}  // namespace delmesh::tet3d
