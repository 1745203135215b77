// Replaces the global operator new/delete of a test executable with versions that count
// allocations, for the "no allocation per event/fact in the steady state" tests. Include it in
// exactly one translation unit of an executable (each test_*.cpp is its own executable).
#pragma once

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace testcommon {
inline std::atomic<std::uint64_t> allocationCount{0};
inline std::uint64_t allocations() { return allocationCount.load(std::memory_order_relaxed); }
}  // namespace testcommon

void* operator new(std::size_t n) {
  testcommon::allocationCount.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
// These replace the global operators, so free() is the right partner of the malloc() above; GCC's
// -Wmismatched-new-delete cannot see that once the replacement is inlined.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
// Every other unaligned form too, so that no memory from the default operators (or a sanitizer's)
// reaches free() here: std::stable_sort's temporary buffer uses the nothrow form, for one.
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  testcommon::allocationCount.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(n ? n : 1);
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
