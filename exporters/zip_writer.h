// A minimal zip archive writer (method 0, "stored": no compression), enough for the
// Blender add-on zip. Deterministic: fixed timestamps, entries in the given order.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace wangscape {

struct ZipEntry {
  std::string_view path;  // forward slashes, e.g. "wangscape_import/__init__.py"
  std::string_view contents;
};

// The bytes of a zip archive holding `entries` (each below 4 GiB; no zip64).
std::string make_zip(std::span<const ZipEntry> entries);

// The Blender add-on (templates/blender_addon) as the installable wangscape_import.zip.
std::string blender_addon_zip();

// CRC-32 (IEEE 802.3, as zip and PNG use it) of `bytes`.
std::uint32_t crc32(std::string_view bytes);

}  // namespace wangscape
