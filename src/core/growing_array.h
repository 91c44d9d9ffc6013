// An array for the engine's largest arrays (the contacts, the solver's rows), grown in place: a
// block of kMappedBytes or more is pages mapped for it alone, which the kernel grows by remapping the
// pages it holds (mremap) instead of copying them into a new block touched for the first time. The
// push that grows a std::vector of 8,192 / 65,536 364-byte elements (a contact) took 7.8 / 67 ms on
// the 2-core VM, remapped 0.02 / 1.1 ms (tests/bench/growth_bench.cpp). realloc does not promise
// it: glibc keeps a block of a size it has seen freed in its heap, and copies it.
//
// Its elements are moved by their bytes: only for types with no member that points into the object
// and nothing to do on destruction (a contact: its manifold, cache and impulses).
#pragma once

#include <sys/mman.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <new>
#include <type_traits>
#include <utility>

namespace haif {

namespace growing_array_detail {
inline std::atomic<size_t> mappedBytes{0};
}  // namespace growing_array_detail

/// Bytes every GrowingArray holds in mappings of its own: malloc's counts (mallinfo2) leave them
/// out, so a tool that measures memory through them adds these.
inline size_t growingArrayMappedBytes() { return growing_array_detail::mappedBytes.load(std::memory_order_relaxed); }

template <class T>
class GrowingArray {
  static_assert(std::is_trivially_destructible_v<T>, "elements are moved by their bytes and never destroyed");
  static_assert(alignof(T) <= alignof(std::max_align_t), "realloc aligns to max_align_t only");

 public:
  GrowingArray() = default;
  GrowingArray(const GrowingArray& other) { *this = other; }
  GrowingArray(GrowingArray&& other) noexcept { swap(other); }
  GrowingArray& operator=(const GrowingArray& other) {
    if (this == &other) return *this;
    clear();
    reserve(other.size_);
    for (const T& v : other) new (data_ + size_++) T(v);
    return *this;
  }
  GrowingArray& operator=(GrowingArray&& other) noexcept {
    swap(other);
    return *this;
  }
  ~GrowingArray() { release(); }

  void swap(GrowingArray& other) noexcept {
    std::swap(data_, other.data_);
    std::swap(size_, other.size_);
    std::swap(capacity_, other.capacity_);
    std::swap(mappedBytes_, other.mappedBytes_);
  }

  size_t size() const { return size_; }
  size_t capacity() const { return capacity_; }
  bool empty() const { return size_ == 0; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  T* begin() { return data_; }
  T* end() { return data_ + size_; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }
  T& operator[](size_t i) { return data_[i]; }
  const T& operator[](size_t i) const { return data_[i]; }
  T& back() { return data_[size_ - 1]; }
  const T& back() const { return data_[size_ - 1]; }

  void push_back(const T& v) {
    if (size_ == capacity_) {
      T copy(v);  // v may be one of the elements the growth moves
      grow(size_ + 1);
      new (data_ + size_) T(std::move(copy));
    } else {
      new (data_ + size_) T(v);
    }
    ++size_;
  }
  void pop_back() { --size_; }
  /// Elements past the old size are value-initialised, as std::vector's.
  void resize(size_t n) {
    if (n > capacity_) grow(n);
    for (size_t i = size_; i < n; ++i) new (data_ + i) T();
    size_ = n;
  }
  void clear() { size_ = 0; }
  void reserve(size_t n) {
    if (n > capacity_) grow(n);
  }

 private:
  /// Blocks from this size on are mapped pages of their own; smaller ones come from malloc.
  static constexpr size_t kMappedBytes = size_t(64) << 10;
  static constexpr size_t kPage = 4096;

  void grow(size_t atLeast) {
    // Half again, not twice: a mapped block grows without a copy, so growing often costs little,
    // and less of it lies unused.
    size_t capacity = std::max({atLeast, capacity_ + capacity_ / 2, size_t(16)});
    const size_t bytes = capacity * sizeof(T);
    if (bytes < kMappedBytes) {
      void* p = std::realloc(static_cast<void*>(data_), bytes);
      if (!p) throw std::bad_alloc();
      data_ = static_cast<T*>(p);
      capacity_ = capacity;
      return;
    }
    const size_t mapped = (bytes + kPage - 1) / kPage * kPage;
    char* base;
    if (mappedBytes_ > 0) {
      void* p = mremap(static_cast<void*>(data_), mappedBytes_, mapped, MREMAP_MAYMOVE);
      if (p == MAP_FAILED) throw std::bad_alloc();
      base = static_cast<char*>(p);
    } else {
      void* p = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (p == MAP_FAILED) throw std::bad_alloc();
      base = static_cast<char*>(p);
      if (size_ > 0) std::memcpy(base, static_cast<const void*>(data_), size_ * sizeof(T));
      std::free(static_cast<void*>(data_));
    }
    growing_array_detail::mappedBytes.fetch_add(mapped - mappedBytes_, std::memory_order_relaxed);
    mappedBytes_ = mapped;
    data_ = reinterpret_cast<T*>(base);
    capacity_ = mapped / sizeof(T);
  }

  void release() {
    if (mappedBytes_ > 0) {
      munmap(static_cast<void*>(data_), mappedBytes_);
      growing_array_detail::mappedBytes.fetch_sub(mappedBytes_, std::memory_order_relaxed);
    } else {
      std::free(static_cast<void*>(data_));
    }
    data_ = nullptr;
    size_ = capacity_ = mappedBytes_ = 0;
  }

  T* data_ = nullptr;
  size_t size_ = 0, capacity_ = 0;
  size_t mappedBytes_ = 0;  // the length of its own mapping; 0: the block is malloc's
};

}  // namespace haif
