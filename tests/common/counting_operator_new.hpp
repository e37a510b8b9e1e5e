// Replaces the global operator new/delete of a test program to count allocations made
// between start_counting_allocations() and allocations_counted(). Include it in exactly one
// source file of a test program (replacement functions may be defined only once).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace a3::test {

inline std::atomic<bool> g_counting_allocations{false};
inline std::atomic<long> g_allocations{0};

inline void start_counting_allocations() {
  g_allocations = 0;
  g_counting_allocations = true;
}
// Stops counting; returns how many allocations were made since start_counting_allocations().
inline long allocations_counted() {
  g_counting_allocations = false;
  return g_allocations.load();
}

inline void* counted_allocation(std::size_t size, std::size_t alignment) {
  if (g_counting_allocations.load(std::memory_order_relaxed)) ++g_allocations;
  if (size == 0) size = 1;
  void* p = alignment <= alignof(std::max_align_t)
                ? std::malloc(size)
                : std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

}  // namespace a3::test

void* operator new(std::size_t size) { return a3::test::counted_allocation(size, 0); }
void* operator new[](std::size_t size) { return a3::test::counted_allocation(size, 0); }
void* operator new(std::size_t size, std::align_val_t a) {
  return a3::test::counted_allocation(size, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t size, std::align_val_t a) {
  return a3::test::counted_allocation(size, static_cast<std::size_t>(a));
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
