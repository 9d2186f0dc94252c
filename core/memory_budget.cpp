#include "core/memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "core/error.h"

namespace wangscape {

namespace {
std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f GB", bytes / 1e9);
  return text;
}
}  // namespace

std::uint64_t memory_limit_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page_size <= 0) return kMaxBufferBytes;
  return std::min(kMaxBufferBytes, std::uint64_t(pages) * std::uint64_t(page_size) / 2);
}

void check_memory_estimate(const std::filesystem::path& file, const std::string& what, double estimated_bytes) {
  const auto limit = double(memory_limit_bytes());
  if (!(estimated_bytes <= limit))
    throw Error(file, "",
                what + " would need about " + gigabytes(estimated_bytes) + " of memory; the limit is " +
                    gigabytes(limit) +
                    " (half the physical memory, at most 8 GiB; see docs/limits.md): use a smaller raster");
}

}  // namespace wangscape
