#include "exporters/zip_writer.h"

#include <array>
#include <cstdint>
#include <vector>

#include "core/atomic_file.h"
#include "templates/blender_addon.h"

namespace wangscape {

namespace {

constexpr std::array<std::uint32_t, 256> make_crc_table() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
  return table;
}

void put16(std::string& out, std::uint32_t value) {
  out.push_back(static_cast<char>(value & 0xff));
  out.push_back(static_cast<char>((value >> 8) & 0xff));
}

void put32(std::string& out, std::uint32_t value) {
  put16(out, value & 0xffff);
  put16(out, value >> 16);
}

// 1980-01-01 00:00 in MS-DOS format: the same bytes on every run.
constexpr std::uint32_t kDosTime = 0;
constexpr std::uint32_t kDosDate = (0u << 9) | (1u << 5) | 1u;
constexpr std::uint32_t kVersionNeeded = 20;
constexpr std::uint32_t kVersionMadeByUnix = (3u << 8) | 20u;
constexpr std::uint32_t kRegularFileMode = 0100644u;

}  // namespace

std::uint32_t crc32(std::string_view bytes) {
  static constexpr auto table = make_crc_table();
  std::uint32_t c = 0xffffffffu;
  for (const char byte : bytes) c = table[(c ^ static_cast<std::uint8_t>(byte)) & 0xff] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

std::string make_zip(std::span<const ZipEntry> entries) {
  std::string archive;
  std::string directory;
  for (const ZipEntry& entry : entries) {
    if (entry.contents.size() >= 0xffffffffu || entry.path.size() >= 0xffffu) {
      throw Error("zip entry '" + std::string(entry.path) + "' is too large for a zip without zip64");
    }
    const auto offset = static_cast<std::uint32_t>(archive.size());
    const std::uint32_t crc = crc32(entry.contents);
    const auto size = static_cast<std::uint32_t>(entry.contents.size());
    const auto name_size = static_cast<std::uint32_t>(entry.path.size());

    put32(archive, 0x04034b50);  // local file header
    put16(archive, kVersionNeeded);
    put16(archive, 0);  // flags
    put16(archive, 0);  // method: stored
    put16(archive, kDosTime);
    put16(archive, kDosDate);
    put32(archive, crc);
    put32(archive, size);  // compressed
    put32(archive, size);  // uncompressed
    put16(archive, name_size);
    put16(archive, 0);  // extra field
    archive += entry.path;
    archive += entry.contents;

    put32(directory, 0x02014b50);  // central directory header
    put16(directory, kVersionMadeByUnix);
    put16(directory, kVersionNeeded);
    put16(directory, 0);
    put16(directory, 0);
    put16(directory, kDosTime);
    put16(directory, kDosDate);
    put32(directory, crc);
    put32(directory, size);
    put32(directory, size);
    put16(directory, name_size);
    put16(directory, 0);  // extra
    put16(directory, 0);  // comment
    put16(directory, 0);  // disk
    put16(directory, 0);  // internal attributes
    put32(directory, kRegularFileMode << 16);
    put32(directory, offset);
    directory += entry.path;
  }
  const auto directory_offset = static_cast<std::uint32_t>(archive.size());
  archive += directory;
  put32(archive, 0x06054b50);  // end of central directory
  put16(archive, 0);
  put16(archive, 0);
  put16(archive, static_cast<std::uint32_t>(entries.size()));
  put16(archive, static_cast<std::uint32_t>(entries.size()));
  put32(archive, static_cast<std::uint32_t>(directory.size()));
  put32(archive, directory_offset);
  put16(archive, 0);  // comment
  return archive;
}

std::string blender_addon_zip() {
  std::vector<ZipEntry> entries;
  for (const EmbeddedFile& file : blender_addon_files()) entries.push_back({file.path, file.contents});
  return make_zip(entries);
}

}  // namespace wangscape
