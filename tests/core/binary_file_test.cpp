// core/binary_file.h, the fields of a folder's binary files: every value read back as written,
// floats bit for bit, little endian whatever the value; a header of another magic or version, a
// file cut anywhere, a count past the bytes left and bytes after the end each refused with an
// Error naming the file and what was expected.
#include "core/binary_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;

constexpr BinaryMagic kMagic = {'W', 'S', 'T', 'E', 'S', 'T', '\r', '\n'};

fs::path scratch(const std::string& name) {
  return fs::temp_directory_path() / ("wangscape_binary_file_" + std::to_string(::getpid()) + "_" + name);
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

std::string refusal(const fs::path& file, std::uint32_t version = 7) {
  try {
    BinaryReader in(file, kMagic, version, "test");
    in.u64("the u64");
    in.text("the text");
    in.array<float>(in.u32("the count"), "the floats");
    in.expect_end("the floats");
  } catch (const Error& e) {
    return e.what();
  }
  return "read";
}

TEST(BinaryFile, EveryValueReadsBackAsWritten) {
  std::ostringstream out;
  put_binary_header(out, kMagic, 7);
  put_u8(out, 0xab);
  put_u16(out, 0xbeef);
  put_u32(out, 0xdeadbeef);
  put_u64(out, 0x0123456789abcdefull);
  put_i32(out, -5);
  put_i64(out, std::numeric_limits<std::int64_t>::min());
  const float nan = std::bit_cast<float>(0x7fc01234u);
  put_f32(out, nan);
  put_f32(out, -0.0f);
  put_f64(out, 0.1);
  put_text(out, "tulip_3 proxy");
  put_text(out, "");
  const std::vector<std::array<float, 3>> positions{{1, 2, 3}, {-4, 5.5f, 1e-30f}};
  put_u32(out, std::uint32_t(positions.size()));
  put_array<std::array<float, 3>>(out, positions);
  const std::string bytes = out.str();
  // Little endian: the u16 after the 12 bytes of header and the u8.
  EXPECT_EQ(std::uint8_t(bytes[13]), 0xef);
  EXPECT_EQ(std::uint8_t(bytes[14]), 0xbe);
  const fs::path file = scratch("values.bin");
  write_bytes(file, bytes);

  BinaryReader in(file, kMagic, "test");
  EXPECT_EQ(in.version(), 7u);
  EXPECT_EQ(in.size(), bytes.size());
  EXPECT_EQ(in.u8("u8"), 0xab);
  EXPECT_EQ(in.u16("u16"), 0xbeef);
  EXPECT_EQ(in.u32("u32"), 0xdeadbeefu);
  EXPECT_EQ(in.u64("u64"), 0x0123456789abcdefull);
  EXPECT_EQ(in.i32("i32"), -5);
  EXPECT_EQ(in.i64("i64"), std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(std::bit_cast<std::uint32_t>(in.f32("f32")), 0x7fc01234u) << "a NaN keeps its payload";
  EXPECT_TRUE(std::signbit(in.f32("f32")));
  EXPECT_EQ(in.f64("f64"), 0.1);
  EXPECT_EQ(in.text("text"), "tulip_3 proxy");
  EXPECT_EQ(in.text("text"), "");
  const std::uint32_t count = in.u32("count");
  EXPECT_EQ(in.left(), count * sizeof(positions[0]));
  const auto read = in.array<std::array<float, 3>>(count, "positions");
  EXPECT_EQ(read, positions);
  EXPECT_EQ(in.left(), 0u);
  in.expect_end("the positions");
  fs::remove(file);
}

TEST(BinaryFile, ADamagedFileIsRefusedNamingItAndWhatWasExpected) {
  std::ostringstream out;
  put_binary_header(out, kMagic, 7);
  put_u64(out, 1);
  put_text(out, "abc");
  put_u32(out, 3);
  put_array<float>(out, std::vector<float>{1, 2, 3});
  const std::string bytes = out.str();
  const fs::path file = scratch("damaged.bin");
  const std::string name = file.string() + ": ";
  write_bytes(file, bytes);
  EXPECT_EQ(refusal(file), "read");
  EXPECT_EQ(refusal(file, 8), name + "version 7: expected 8");
  write_bytes(file, "WSCACHE\n" + bytes.substr(8));
  EXPECT_EQ(refusal(file), name + "not a test file (expected it to start with WSTEST)");
  for (std::size_t size = 8; size < bytes.size(); ++size) {
    write_bytes(file, bytes.substr(0, size));
    const std::string what = refusal(file);
    EXPECT_EQ(what.rfind(name + "truncated", 0), 0u) << "cut to " << size << ": " << what;
  }
  std::string many = bytes;
  const std::uint32_t count = 1u << 30;  // floats far past the bytes left: refused before allocating
  std::memcpy(many.data() + bytes.size() - 16, &count, 4);
  write_bytes(file, many);
  EXPECT_EQ(refusal(file), name + "truncated: expected the floats");
  write_bytes(file, bytes + "x");
  EXPECT_EQ(refusal(file), name + "longer than the floats");
  fs::remove(file);
  EXPECT_EQ(refusal(file), name + "cannot be read");
}

}  // namespace
}  // namespace wangscape
