// The renders test program replaces the global allocation functions (counted_allocations_test.cpp,
// for counted_allocations.h). Every form is counted, and what each form gives goes back through
// the deletes the code calls. Before: only operator new(size_t) was replaced; under
// AddressSanitizer the nothrow and array forms came from ASan's allocator, were not counted, and
// met the replacement's free() (alloc-dealloc-mismatch in std::stable_sort's temporary buffer and
// in GDAL and PROJ).
#include <gtest/gtest.h>

#include <new>

#include "tests/renders/counted_allocations.h"

namespace wangscape {
namespace {

TEST(CountedAllocations, EveryFormIsCountedAndGoesBackThroughItsDelete) {
  void* nothrow = nullptr;
  void* array = nullptr;
  void* nothrow_array = nullptr;
  const long allocations = test::count_allocations([&] {
    nothrow = ::operator new(24, std::nothrow);
    array = ::operator new[](24);
    nothrow_array = ::operator new[](24, std::nothrow);
  });
  EXPECT_EQ(allocations, 3);
  ::operator delete(nothrow);
  ::operator delete[](array);
  ::operator delete[](nothrow_array, std::nothrow);
}

}  // namespace
}  // namespace wangscape
