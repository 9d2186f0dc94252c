#include "core/disk_space.h"

#include <system_error>

#include "core/error.h"
#include "core/number_text.h"

namespace wangscape {

void check_disk_estimate(const std::filesystem::path& file, const std::string& what, double estimated_bytes,
                         const std::string& way_out) {
  const std::filesystem::path folder = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  std::error_code error;
  const std::filesystem::space_info space = std::filesystem::space(folder, error);
  if (error || space.available == static_cast<std::uintmax_t>(-1)) return;
  const auto available = static_cast<double>(space.available);
  if (!(estimated_bytes <= available))
    throw Error(folder, "",
                what + " would need about " + byte_text(estimated_bytes) + "; the folder has " + byte_text(available) +
                    " free: " + way_out);
}

}  // namespace wangscape
