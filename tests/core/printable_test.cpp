// valid_utf8: well-formed UTF-8 passes unchanged; every ill-formed byte becomes U+FFFD.
#include "core/printable.h"

#include <gtest/gtest.h>

namespace wangscape {
namespace {

constexpr char kReplacement[] = "\xef\xbf\xbd";

TEST(ValidUtf8, KeepsWellFormedText) {
  for (const std::string text : {"", "GCS_WGS_1984", "Z\xc3\xbcrich", "\xe2\x82\xac 5", "\xf0\x9f\x8c\xbb sunflower",
                                 "\xf4\x8f\xbf\xbf", "\xed\x9f\xbf"})
    EXPECT_EQ(valid_utf8(text), text);
}

TEST(ValidUtf8, ReplacesEachIllFormedByte) {
  EXPECT_EQ(valid_utf8("GCS_\xff"
                       "1984"),
            std::string("GCS_") + kReplacement + "1984");                                          // Latin-1 0xFF
  EXPECT_EQ(valid_utf8("\xc3"), kReplacement);                                                     // cut short
  EXPECT_EQ(valid_utf8("\xc0\xaf"), std::string(kReplacement) + kReplacement);                     // overlong '/'
  EXPECT_EQ(valid_utf8("\xed\xa0\x80"), std::string(kReplacement) + kReplacement + kReplacement);  // surrogate
  EXPECT_EQ(valid_utf8("\xf4\x90\x80\x80").size(), 4 * std::string(kReplacement).size());          // > U+10FFFF
  EXPECT_EQ(valid_utf8("a\x80z"), std::string("a") + kReplacement + "z");                          // lone continuation
}

TEST(ValidUtf8, OutputIsAlwaysWellFormed) {
  // Every byte pair and a few triples: the output round-trips (valid_utf8 of it is itself).
  for (int a = 0; a < 256; ++a)
    for (int b = 0; b < 256; b += 3) {
      const std::string text{static_cast<char>(a), static_cast<char>(b), static_cast<char>((a * 7 + b) & 0xff)};
      const std::string out = valid_utf8(text);
      ASSERT_EQ(valid_utf8(out), out) << a << " " << b;
    }
}

}  // namespace
}  // namespace wangscape
