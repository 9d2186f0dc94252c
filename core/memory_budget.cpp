#include "core/memory_budget.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>

#include "core/error.h"
#include "core/number_text.h"

namespace wangscape {

namespace {
std::string gigabytes(double bytes) { return fixed_text(bytes / 1e9, 2) + " GB"; }

std::atomic<std::uint64_t> process_limit_bytes{0};

// Half of what this process may hold: the physical memory, and the address-space limit when
// one is set (`ulimit -v`, `prlimit --as`), where an allocation past it fails at once.
std::uint64_t machine_limit_bytes() {
  std::uint64_t limit = kMaxBufferBytes;
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGESIZE);
  if (pages > 0 && page_size > 0) limit = std::min(limit, std::uint64_t(pages) * std::uint64_t(page_size) / 2);
  rlimit address_space{};
  if (::getrlimit(RLIMIT_AS, &address_space) == 0 && address_space.rlim_cur != RLIM_INFINITY)
    limit = std::min(limit, std::uint64_t(address_space.rlim_cur) / 2);
  return limit;
}
}  // namespace

std::uint64_t memory_limit_bytes() {
  const std::uint64_t lowered = process_limit_bytes.load(std::memory_order_relaxed);
  return lowered != 0 ? lowered : machine_limit_bytes();
}

void set_memory_limit_bytes_for_process(std::uint64_t bytes) {
  process_limit_bytes.store(bytes, std::memory_order_relaxed);
}

std::optional<std::string> memory_estimate_excess(const std::string& what, double estimated_bytes) {
  const auto limit = double(memory_limit_bytes());
  if (estimated_bytes <= limit) return std::nullopt;
  return what + " would need about " + gigabytes(estimated_bytes) + " of memory; the limit is " + gigabytes(limit) +
         " (half the physical memory or of the address-space limit, at most 8 GiB; see docs/limits.md)";
}

void check_memory_estimate(const std::filesystem::path& file, const std::string& what, double estimated_bytes) {
  if (auto excess = memory_estimate_excess(what, estimated_bytes)) throw Error(file, "", *excess);
}

}  // namespace wangscape
