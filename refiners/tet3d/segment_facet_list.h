// The facets having one input segment on their boundary (SegmentData::facets, notes
// §4.2.1: a subsegment split updates the triangulation of every facet through it).
//
// A segment of a surface lies on two facets and almost never on more, so the list keeps
// up to two facet ids in place and moves to the heap only beyond that: 16 bytes per
// segment, where a std::vector took 24 bytes plus a 32-byte heap block of its own
// (surfaces have one segment per input triangle edge: 113112 on cgal-bunny00).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace delmesh::tet3d {

class SegmentFacetList {
 public:
  static constexpr std::uint32_t kInlineCapacity = 2;

  SegmentFacetList() = default;
  SegmentFacetList(const SegmentFacetList& other) { append_all(other); }
  SegmentFacetList(SegmentFacetList&& other) noexcept { take(other); }
  SegmentFacetList& operator=(const SegmentFacetList& other) {
    if (this != &other) {
      clear();
      append_all(other);
    }
    return *this;
  }
  SegmentFacetList& operator=(SegmentFacetList&& other) noexcept {
    if (this != &other) {
      release();
      take(other);
    }
    return *this;
  }
  ~SegmentFacetList() { release(); }

  const std::uint32_t* data() const { return on_heap() ? heap_ : inline_; }
  const std::uint32_t* begin() const { return data(); }
  const std::uint32_t* end() const { return data() + size_; }
  std::uint32_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::uint32_t operator[](std::size_t i) const { return data()[i]; }
  std::uint32_t front() const { return data()[0]; }

  void push_back(std::uint32_t facet) {
    if (size_ == capacity_) grow();
    (on_heap() ? heap_ : inline_)[size_++] = facet;
  }
  void clear() { size_ = 0; }

 private:
  bool on_heap() const { return capacity_ > kInlineCapacity; }

  void grow() {
    const std::uint32_t capacity = capacity_ * 2;
    auto* grown = new std::uint32_t[capacity];
    std::copy(begin(), end(), grown);
    if (on_heap()) delete[] heap_;
    heap_ = grown;
    capacity_ = capacity;
  }
  void append_all(const SegmentFacetList& other) {
    for (const std::uint32_t f : other) push_back(f);
  }
  /// Frees the heap block, if any; the list is left empty with its inline capacity.
  void release() {
    if (on_heap()) delete[] heap_;
    capacity_ = kInlineCapacity;
    size_ = 0;
  }
  /// Moves other's facets here (this list holds none) and leaves other empty.
  void take(SegmentFacetList& other) {
    size_ = other.size_;
    capacity_ = other.capacity_;
    if (other.on_heap())
      heap_ = other.heap_;
    else
      std::copy(other.inline_, other.inline_ + other.size_, inline_);
    other.capacity_ = kInlineCapacity;
    other.size_ = 0;
  }

  std::uint32_t size_ = 0;
  std::uint32_t capacity_ = kInlineCapacity;
  union {
    std::uint32_t inline_[kInlineCapacity] = {};
    std::uint32_t* heap_;
  };
};
static_assert(sizeof(SegmentFacetList) == 16);

}  // namespace delmesh::tet3d
