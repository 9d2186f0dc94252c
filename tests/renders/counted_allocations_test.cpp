// The renders test program's global allocation functions, counted while counting_allocations is
// set (counted_allocations.h). Every form that allocates without an alignment is replaced, so each
// pointer goes back to free() whichever of them frees it: under AddressSanitizer a form left out
// comes from ASan's allocator and meets this free() (alloc-dealloc-mismatch;
// allocation_forms_test.cpp). In a file of its own: where the replacement's body is seen beside
// allocations, GCC warns that free() meets memory from operator new.
#include <cstdlib>
#include <new>

#include "tests/renders/counted_allocations.h"

namespace wangscape::test {
std::atomic<bool> counting_allocations{false};
std::atomic<long> allocations{0};
}  // namespace wangscape::test

namespace {

void* counted_malloc(std::size_t bytes) noexcept {
  if (wangscape::test::counting_allocations.load(std::memory_order_relaxed)) ++wangscape::test::allocations;
  return std::malloc(bytes ? bytes : 1);
}

void* counted_new(std::size_t bytes) {
  if (void* p = counted_malloc(bytes)) return p;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t bytes) { return counted_new(bytes); }
void* operator new[](std::size_t bytes) { return counted_new(bytes); }
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept { return counted_malloc(bytes); }
void* operator new[](std::size_t bytes, const std::nothrow_t&) noexcept { return counted_malloc(bytes); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
