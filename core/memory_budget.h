// Large buffers (a DEM raster, a painted mask, an image) are estimated before they are
// allocated and refused above a limit, with the estimate and the limit in the message, so an
// absurd input fails at once with a message instead of `bad_alloc` or the OOM killer.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace wangscape {

// The most one such buffer may take: half the machine's physical memory, at most 8 GiB
// (kMaxBufferBytes), so the rest of the run (meshes, the field, the writers) still fits.
inline constexpr std::uint64_t kMaxBufferBytes = std::uint64_t{8} << 30;
std::uint64_t memory_limit_bytes();

// Lowers the limit for this process (0 restores the machine's). The DEM fuzzer sets 16 MiB so
// that an input declaring a large raster is refused at once instead of costing seconds per
// execution; the large-raster paths are covered by the tests at the real limit.
void set_memory_limit_bytes_for_process(std::uint64_t bytes);

// Throws Error(file, "", "<what> would need about N GB ...; the limit is L GB ...") when
// `estimated_bytes` (a double: products of sizes never wrap) exceeds memory_limit_bytes().
void check_memory_estimate(const std::filesystem::path& file, const std::string& what, double estimated_bytes);

// The same message without the file ("<what> would need about N GB ...; the limit is L GB ..."),
// or nothing within the limit: for callers that name the place themselves (a scene file's key
// and line, a flag).
std::optional<std::string> memory_estimate_excess(const std::string& what, double estimated_bytes);

}  // namespace wangscape
