#include "core/binary_file.h"

#include <algorithm>
#include <cstring>

#include "core/error.h"

namespace wangscape {

void put_u32(std::ostream& out, std::uint32_t value) {
  const unsigned char b[4] = {std::uint8_t(value), std::uint8_t(value >> 8), std::uint8_t(value >> 16),
                              std::uint8_t(value >> 24)};
  out.write(reinterpret_cast<const char*>(b), 4);
}

void put_binary_header(std::ostream& out, const BinaryMagic& magic, std::uint32_t version) {
  out.write(magic, sizeof magic);
  put_u32(out, version);
}

BinaryReader::BinaryReader(const std::filesystem::path& path, const BinaryMagic& magic, std::uint32_t version,
                           const std::string& kind)
    : path_(path), in_(path, std::ios::binary) {
  if (!in_) fail("cannot be read");
  in_.seekg(0, std::ios::end);
  size_ = std::uint64_t(std::max<std::streamoff>(0, in_.tellg()));
  in_.seekg(0);
  char start[sizeof magic];
  // (The magic's printable part: it ends in "\r\n", which catches text-mode transfers.)
  if (!in_.read(start, sizeof start) || std::memcmp(start, magic, sizeof magic) != 0)
    fail("not a " + kind + " file (expected it to start with " + std::string(magic, sizeof magic - 2) + ")");
  if (const std::uint32_t found = u32("the " + kind + " header"); found != version)
    fail("version " + std::to_string(found) + ": expected " + std::to_string(version));
}

void BinaryReader::fail(const std::string& what) const { throw Error(path_, "", what); }

std::uint32_t BinaryReader::u32(const std::string& what) {
  unsigned char b[4];
  if (!in_.read(reinterpret_cast<char*>(b), 4)) fail("truncated: expected " + what);
  return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
}

void BinaryReader::read(void* to, std::size_t bytes, const std::string& what) {
  if (!in_.read(static_cast<char*>(to), std::streamsize(bytes))) fail("truncated in " + what);
}

void BinaryReader::expect_end(const std::string& what) {
  if (in_.peek() != std::ifstream::traits_type::eof()) fail("longer than " + what);
}

}  // namespace wangscape
