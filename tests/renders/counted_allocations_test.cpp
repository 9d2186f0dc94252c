// The renders test program's global operator new, counted while counting_allocations is set
// (counted_allocations.h). In a file of its own: where the replacement's body is seen beside
// allocations, GCC warns that free() meets memory from operator new.
#include <cstdlib>
#include <new>

#include "tests/renders/counted_allocations.h"

namespace wangscape::test {
std::atomic<bool> counting_allocations{false};
std::atomic<long> allocations{0};
}  // namespace wangscape::test

void* operator new(std::size_t bytes) {
  if (wangscape::test::counting_allocations.load(std::memory_order_relaxed)) ++wangscape::test::allocations;
  if (void* p = std::malloc(bytes ? bytes : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
