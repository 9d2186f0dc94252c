// Streamed files (a scatter's points) are not held in memory, so what limits them is the disk:
// their size is estimated before the first byte and refused when the folder they go into has
// less room, with the folder and both sizes in the message.
#pragma once

#include <filesystem>
#include <string>

namespace wangscape {

// Throws Error("<folder>: <what> would need about N GB; the folder has F GB free: <way_out>") when
// `estimated_bytes` exceeds the space free to this user in the folder `file` is written into.
// A folder whose free space cannot be read (missing, no permission) is not checked: writing
// there fails with its own message.
void check_disk_estimate(const std::filesystem::path& file, const std::string& what, double estimated_bytes,
                         const std::string& way_out);

}  // namespace wangscape
