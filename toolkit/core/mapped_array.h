// MappedArray<T>: a growable array of trivially copyable elements that grows without
// copying. std::vector grows by allocating a buffer twice as large and copying into it,
// so at that moment the old buffer and the copied half of the new one are both resident:
// for the tet store of 3D refinement (32 bytes per tet slot, the largest array of a run)
// that transient alone is the size of the whole store, and the freed old buffers stay
// behind as holes in the heap. Here a large array lives in its own anonymous memory
// mapping that the kernel enlarges or moves by its page tables (mremap, Linux), so
// growing costs no copy and no second buffer, pages never written take no memory, and
// freeing returns the pages to the system at once. Small arrays (and every array on
// systems without mremap) use malloc / realloc.
//
// The interface is the subset of std::vector that TetMesh and its kernels use.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <new>
#include <type_traits>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace delmesh {

/// MapBytes: arrays of at least this many bytes live in their own mapping (rounded up to
/// whole pages). The default keeps small arrays in malloc; an array that must never leave
/// holes in the heap when it grows and shrinks (the refinement queue's buckets) maps from
/// a page.
template <class T, std::size_t MapBytes = std::size_t{1} << 20>
class MappedArray {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>,
                "MappedArray moves its elements as bytes");

 public:
  using value_type = T;
  using iterator = T*;
  using const_iterator = const T*;

  MappedArray() = default;
  MappedArray(const MappedArray& other) { *this = other; }
  MappedArray(MappedArray&& other) noexcept { swap(other); }
  MappedArray& operator=(const MappedArray& other) {
    if (this != &other) {
      clear();
      reserve(other.size_);
      if (other.size_) std::memcpy(static_cast<void*>(data_), other.data_, other.size_ * sizeof(T));
      size_ = other.size_;
    }
    return *this;
  }
  MappedArray& operator=(MappedArray&& other) noexcept {
    MappedArray moved(std::move(other));
    swap(moved);
    return *this;
  }
  ~MappedArray() { release(); }

  void swap(MappedArray& other) noexcept {
    std::swap(data_, other.data_);
    std::swap(size_, other.size_);
    std::swap(capacity_, other.capacity_);
    std::swap(mapped_bytes_, other.mapped_bytes_);
  }

  std::size_t size() const { return size_; }
  std::size_t capacity() const { return capacity_; }
  bool empty() const { return size_ == 0; }
  /// True when the elements live in their own memory mapping (large arrays, Linux).
  bool mapped() const { return mapped_bytes_ != 0; }

  T* data() { return data_; }
  const T* data() const { return data_; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T& front() { return data_[0]; }
  const T& front() const { return data_[0]; }
  T& back() { return data_[size_ - 1]; }
  const T& back() const { return data_[size_ - 1]; }
  iterator begin() { return data_; }
  iterator end() { return data_ + size_; }
  const_iterator begin() const { return data_; }
  const_iterator end() const { return data_ + size_; }

  void push_back(const T& value) {
    if (size_ == capacity_) {
      const T copy = value;  // value may be an element of this array
      grow(std::max<std::size_t>(16, 2 * capacity_));
      data_[size_++] = copy;
      return;
    }
    data_[size_++] = value;
  }
  void pop_back() { --size_; }
  /// New elements are value-initialized (zero for TetRecord and integers).
  void resize(std::size_t n) { resize(n, T{}); }
  void resize(std::size_t n, const T& value) {
    if (n > capacity_) grow(std::max(n, 2 * capacity_));
    for (std::size_t i = size_; i < n; ++i) data_[i] = value;
    size_ = n;
  }
  void reserve(std::size_t n) {
    if (n > capacity_) grow(n);
  }
  /// n copies of value (the storage is reused when its capacity suffices).
  void assign(std::size_t n, const T& value) {
    if (n > capacity_) grow(n);
    std::fill(data_, data_ + n, value);
    size_ = n;
  }
  void clear() { size_ = 0; }
  /// Gives back the storage beyond size().
  void shrink_to_fit() { shrink_capacity(size_); }
  /// Lowers the capacity to max(n, size()) when it is larger, giving the storage beyond
  /// back: a mapped array is shortened in place (mremap; no copy while it stays at least
  /// kMapBytes), a malloc'ed one is realloc'ed.
  void shrink_capacity(std::size_t n) {
    n = std::max(n, size_);
    if (n >= capacity_) return;
    if (n == 0) {
      release();
      return;
    }
    const std::size_t bytes = n * sizeof(T);
#if defined(__linux__)
    if (mapped_bytes_) {
      const std::size_t page = 4096;
      const std::size_t mapped = (bytes + page - 1) / page * page;
      if (bytes >= kMapBytes) {
        if (mapped < mapped_bytes_) {
          void* p = mremap(data_, mapped_bytes_, mapped, 0);
          if (p == MAP_FAILED) return;  // keeps the larger mapping
          mapped_bytes_ = mapped;
          capacity_ = mapped / sizeof(T);
        }
        return;
      }
      void* p = std::malloc(bytes);
      if (!p) return;  // keeps the mapping
      if (size_) std::memcpy(p, static_cast<const void*>(data_), size_ * sizeof(T));
      munmap(data_, mapped_bytes_);
      data_ = static_cast<T*>(p);
      mapped_bytes_ = 0;
      capacity_ = n;
      return;
    }
#endif
    if (void* p = std::realloc(static_cast<void*>(data_), bytes)) {
      data_ = static_cast<T*>(p);
      capacity_ = n;
    }
  }
  /// Gives the storage back: an empty array with no capacity.
  void release() {
    if (mapped_bytes_) {
#if defined(__linux__)
      munmap(data_, mapped_bytes_);
#endif
    } else {
      std::free(data_);
    }
    data_ = nullptr;
    size_ = capacity_ = mapped_bytes_ = 0;
  }

  friend bool operator==(const MappedArray& x, const MappedArray& y) {
    if (x.size_ != y.size_) return false;
    for (std::size_t i = 0; i < x.size_; ++i)
      if (std::memcmp(&x.data_[i], &y.data_[i], sizeof(T)) != 0) return false;
    return true;
  }

  /// Arrays of at least this many bytes get their own mapping.
  static constexpr std::size_t kMapBytes = MapBytes;

 private:
  void grow(std::size_t new_capacity) {
    const std::size_t bytes = new_capacity * sizeof(T);
#if defined(__linux__)
    if (bytes >= kMapBytes) {
      const std::size_t page = 4096;
      const std::size_t mapped = (bytes + page - 1) / page * page;
      void* p;
      if (mapped_bytes_) {
        p = mremap(data_, mapped_bytes_, mapped, MREMAP_MAYMOVE);
      } else {
        p = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (p != MAP_FAILED && size_) std::memcpy(p, static_cast<const void*>(data_), size_ * sizeof(T));
        if (p != MAP_FAILED) std::free(data_);
      }
      if (p == MAP_FAILED) throw std::bad_alloc();
      data_ = static_cast<T*>(p);
      mapped_bytes_ = mapped;
      capacity_ = mapped / sizeof(T);
      return;
    }
#endif
    void* p = std::realloc(static_cast<void*>(data_), bytes);
    if (!p) throw std::bad_alloc();
    data_ = static_cast<T*>(p);
    capacity_ = new_capacity;
  }

  T* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
  std::size_t mapped_bytes_ = 0;  ///< size of the mapping, 0 when malloc'ed
};

}  // namespace delmesh
