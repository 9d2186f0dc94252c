#include "core/binary_file.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "core/error.h"

namespace wangscape {

namespace {

template <class T>
void put_le(std::ostream& out, T value) {
  unsigned char b[sizeof value];
  for (std::size_t k = 0; k < sizeof value; ++k) b[k] = std::uint8_t(value >> (8 * k));
  out.write(reinterpret_cast<const char*>(b), sizeof b);
}

}  // namespace

void put_u8(std::ostream& out, std::uint8_t value) { put_le(out, value); }
void put_u16(std::ostream& out, std::uint16_t value) { put_le(out, value); }
void put_u32(std::ostream& out, std::uint32_t value) { put_le(out, value); }
void put_u64(std::ostream& out, std::uint64_t value) { put_le(out, value); }

void put_text(std::ostream& out, const std::string& text) {
  if (text.size() > std::numeric_limits<std::uint32_t>::max())
    throw Error("a text of " + std::to_string(text.size()) + " bytes: at most 4 GiB fit a binary file's field");
  put_u32(out, std::uint32_t(text.size()));
  out.write(text.data(), std::streamsize(text.size()));
}

void put_binary_header(std::ostream& out, const BinaryMagic& magic, std::uint32_t version) {
  out.write(magic, sizeof magic);
  put_u32(out, version);
}

BinaryReader::BinaryReader(const std::filesystem::path& path, const BinaryMagic& magic, const std::string& kind)
    : path_(path), in_(path, std::ios::binary) {
  if (!in_) fail("cannot be read");
  in_.seekg(0, std::ios::end);
  size_ = std::uint64_t(std::max<std::streamoff>(0, in_.tellg()));
  in_.seekg(0);
  char start[sizeof magic];
  // (The magic's printable part: it ends in "\r\n" or "\n", which catch text-mode transfers.)
  std::size_t printable = sizeof magic;
  while (printable > 0 && (magic[printable - 1] == '\n' || magic[printable - 1] == '\r')) --printable;
  if (!in_.read(start, sizeof start) || std::memcmp(start, magic, sizeof magic) != 0)
    fail("not a " + kind + " file (expected it to start with " + std::string(magic, printable) + ")");
  version_ = u32("the " + kind + " header");
}

BinaryReader::BinaryReader(const std::filesystem::path& path, const BinaryMagic& magic, std::uint32_t version,
                           const std::string& kind)
    : BinaryReader(path, magic, kind) {
  if (version_ != version) fail("version " + std::to_string(version_) + ": expected " + std::to_string(version));
}

void BinaryReader::fail(const std::string& what) const { throw Error(path_, "", what); }

std::uint64_t BinaryReader::left() {
  const std::streamoff at = in_.tellg();
  return at < 0 ? 0 : size_ - std::min(size_, std::uint64_t(at));
}

std::uint8_t BinaryReader::u8(const std::string& what) {
  std::uint8_t value = 0;
  if (!in_.read(reinterpret_cast<char*>(&value), 1)) fail("truncated: expected " + what);
  return value;
}

std::uint16_t BinaryReader::u16(const std::string& what) {
  unsigned char b[2];
  if (!in_.read(reinterpret_cast<char*>(b), 2)) fail("truncated: expected " + what);
  return std::uint16_t(b[0] | b[1] << 8);
}

std::uint32_t BinaryReader::u32(const std::string& what) {
  unsigned char b[4];
  if (!in_.read(reinterpret_cast<char*>(b), 4)) fail("truncated: expected " + what);
  return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
}

std::uint64_t BinaryReader::u64(const std::string& what) {
  const std::uint64_t low = u32(what);
  return low | std::uint64_t(u32(what)) << 32;
}

std::string BinaryReader::text(const std::string& what) {
  const std::uint32_t size = u32(what);
  if (size > left()) fail("truncated: expected " + what);
  std::string text(size, '\0');
  read(text.data(), size, what);
  return text;
}

void BinaryReader::read(void* to, std::size_t bytes, const std::string& what) {
  if (!in_.read(static_cast<char*>(to), std::streamsize(bytes))) fail("truncated in " + what);
}

void BinaryReader::expect_end(const std::string& what) {
  if (in_.peek() != std::ifstream::traits_type::eof()) fail("longer than " + what);
}

}  // namespace wangscape
