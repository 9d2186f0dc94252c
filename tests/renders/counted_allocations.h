// Counts the program's operator new calls, on every thread, while a piece of work runs
// (counted_allocations_test.cpp replaces the global operator new of the renders test program).
#pragma once

#include <atomic>
#include <functional>

namespace wangscape::test {

extern std::atomic<bool> counting_allocations;
extern std::atomic<long> allocations;

// The operator new calls made while `work` ran.
inline long count_allocations(const std::function<void()>& work) {
  allocations = 0;
  counting_allocations = true;
  work();
  counting_allocations = false;
  return allocations.load();
}

}  // namespace wangscape::test
