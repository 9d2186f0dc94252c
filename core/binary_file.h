// The small binary files a scene folder keeps beside its packs (the flowers' sky shares, the
// ground light): an 8-byte magic, a u32 format version, then u32 counts and the data, little
// endian. One writer's header and one reader, so that each file's reader checks the same things
// with the same words: every failure is an Error naming the file and what was expected.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>

namespace wangscape {

using BinaryMagic = char[8];

void put_u32(std::ostream& out, std::uint32_t value);
// The magic and the format version.
void put_binary_header(std::ostream& out, const BinaryMagic& magic, std::uint32_t version);

class BinaryReader {
 public:
  // Opens `path` and reads its header: throws Error naming the file when it cannot be read, does
  // not start with `magic` ("not a <kind> file"), or is of another version than `version`.
  BinaryReader(const std::filesystem::path& path, const BinaryMagic& magic, std::uint32_t version,
               const std::string& kind);

  [[noreturn]] void fail(const std::string& what) const;
  const std::filesystem::path& path() const { return path_; }
  std::uint64_t size() const { return size_; }  // the file's, in bytes
  // The next u32; a file ending before it is "truncated: expected <what>".
  std::uint32_t u32(const std::string& what);
  // The next `bytes` bytes into `to`; a file ending before them is "truncated in <what>".
  void read(void* to, std::size_t bytes, const std::string& what);
  // A file with more after the data is "longer than <what>".
  void expect_end(const std::string& what);

 private:
  std::filesystem::path path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

}  // namespace wangscape
