// The binary files a scene folder keeps beside its packs (scene.cache, the flowers' sky shares,
// the ground light): an 8-byte magic, a u32 format version, then little-endian fields. One set of
// writers and one reader, so that each file's reader checks the same things with the same words:
// every failure is an Error naming the file and what was expected.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace wangscape {

// Arrays are written and read as the machine holds them: little endian, as every field here.
static_assert(std::endian::native == std::endian::little, "the binary files are little endian");

using BinaryMagic = char[8];

void put_u8(std::ostream& out, std::uint8_t value);
void put_u16(std::ostream& out, std::uint16_t value);
void put_u32(std::ostream& out, std::uint32_t value);
void put_u64(std::ostream& out, std::uint64_t value);
inline void put_i32(std::ostream& out, std::int32_t value) { put_u32(out, std::uint32_t(value)); }
inline void put_i64(std::ostream& out, std::int64_t value) { put_u64(out, std::uint64_t(value)); }
// Floats bit for bit (a NaN's payload, a negative zero).
inline void put_f32(std::ostream& out, float value) { put_u32(out, std::bit_cast<std::uint32_t>(value)); }
inline void put_f64(std::ostream& out, double value) { put_u64(out, std::bit_cast<std::uint64_t>(value)); }
// A u32 byte count, then the bytes. Throws Error for a text of 4 GiB or more.
void put_text(std::ostream& out, const std::string& text);
// The elements' bytes, as the machine holds them (no count: write it first).
template <class T>
void put_array(std::ostream& out, std::span<const T> values) {
  static_assert(std::is_trivially_copyable_v<T>);
  out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size_bytes()));
}
// The magic and the format version.
void put_binary_header(std::ostream& out, const BinaryMagic& magic, std::uint32_t version);

class BinaryReader {
 public:
  // Opens `path` and reads its header: throws Error naming the file when it cannot be read or does
  // not start with `magic` ("not a <kind> file"). The caller checks version().
  BinaryReader(const std::filesystem::path& path, const BinaryMagic& magic, const std::string& kind);
  // The same, and throws Error when the file is of another version than `version`.
  BinaryReader(const std::filesystem::path& path, const BinaryMagic& magic, std::uint32_t version,
               const std::string& kind);

  [[noreturn]] void fail(const std::string& what) const;
  const std::filesystem::path& path() const { return path_; }
  std::uint32_t version() const { return version_; }
  std::uint64_t size() const { return size_; }  // the file's, in bytes
  std::uint64_t left();                         // the bytes after those read
  // The next value; a file ending before it is "truncated: expected <what>".
  std::uint8_t u8(const std::string& what);
  std::uint16_t u16(const std::string& what);
  std::uint32_t u32(const std::string& what);
  std::uint64_t u64(const std::string& what);
  std::int32_t i32(const std::string& what) { return std::int32_t(u32(what)); }
  std::int64_t i64(const std::string& what) { return std::int64_t(u64(what)); }
  float f32(const std::string& what) { return std::bit_cast<float>(u32(what)); }
  double f64(const std::string& what) { return std::bit_cast<double>(u64(what)); }
  // put_text's text.
  std::string text(const std::string& what);
  // The next `bytes` bytes into `to`; a file ending before them is "truncated in <what>".
  void read(void* to, std::size_t bytes, const std::string& what);
  // `count` elements of put_array; a file with fewer bytes left is "truncated: expected <what>"
  // (checked before anything is allocated).
  template <class T>
  std::vector<T> array(std::uint64_t count, const std::string& what) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (count > left() / sizeof(T)) fail("truncated: expected " + what);
    std::vector<T> values(count);
    read(values.data(), values.size() * sizeof(T), what);
    return values;
  }
  // A file with more after the data is "longer than <what>".
  void expect_end(const std::string& what);

 private:
  std::filesystem::path path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  std::uint32_t version_ = 0;
};

}  // namespace wangscape
