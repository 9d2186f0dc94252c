// Numbers from command-line text: whole strings only, finite. (std::from_chars reads the "C"
// format whatever the locale; this machine has no other locale to show it.)
#include "core/number_text.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace wangscape {
namespace {

TEST(NumberText, PairsAreWholeNumbersAroundTheSeparator) {
  int w = 0, h = 0;
  EXPECT_TRUE(parse_number_pair(std::string("640x360"), 'x', w, h));
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 360);
  std::int64_t i = 0, j = 0;
  EXPECT_TRUE(parse_number_pair(std::string("-10,5"), ',', i, j));
  EXPECT_EQ(i, -10);
  for (const char* bad : {"640", "640x", "x360", "640x360x2", "64.5x3", " 64x3", "99999999999x1"})
    EXPECT_FALSE(parse_number_pair(std::string(bad), 'x', w, h)) << bad;
}

TEST(NumberText, ListsAreFiniteNumbersInTheirCountRange) {
  const auto v = parse_number_list("0,6300.5,-1e3", ',', 2, 3);
  ASSERT_TRUE(v);
  EXPECT_EQ(*v, (std::vector<double>{0, 6300.5, -1000}));
  EXPECT_EQ(parse_number_list("1,2", ',', 2, 3)->size(), 2u);
  for (const char* bad : {"1", "1,2,3,4", "1,,2", "1,b", "nan,1", "inf,1", "1,2,", "1, 2"})
    EXPECT_FALSE(parse_number_list(bad, ',', 2, 3)) << bad;
}

TEST(NumberText, WritesTheShortestTextThatReadsBack) {
  EXPECT_EQ(number_text(0.1), "0.1");
  EXPECT_EQ(number_text(1e300), "1e+300");
  EXPECT_EQ(number_text(-0.0), "-0");
  EXPECT_EQ(number_text(0.1f), "0.1");
  EXPECT_EQ(number_text(std::uint64_t(18446744073709551615ull)), "18446744073709551615");
  std::string line = "x=";
  append_number(line, 42);
  EXPECT_EQ(line, "x=42");
}

TEST(NumberText, WritesFixedDecimalsAndSignificantDigits) {
  EXPECT_EQ(fixed_text(12.5, 2), "12.50");
  EXPECT_EQ(fixed_text(0.125, 2), "0.12");  // 0.125 exactly: round half to even
  EXPECT_EQ(fixed_text(-0.04, 1), "-0.0");
  EXPECT_EQ(fixed_text(1e20, 0), "100000000000000000000");
  EXPECT_EQ(significant_text(1200, 6), "1200");
  EXPECT_EQ(significant_text(0.1234567, 6), "0.123457");
  EXPECT_EQ(significant_text(1.5e7, 2), "1.5e+07");
}

TEST(NumberText, WritesSizesInDecimalUnits) {
  EXPECT_EQ(byte_text(0), "0 B");
  EXPECT_EQ(byte_text(812), "812 B");
  EXPECT_EQ(byte_text(999.6), "1 kB");
  EXPECT_EQ(byte_text(4500), "4.5 kB");
  EXPECT_EQ(byte_text(61.24e6), "61.2 MB");
  EXPECT_EQ(byte_text(3.084e9), "3.08 GB");
  EXPECT_EQ(byte_text(6.28e18), "6280 PB");  // never an exponent
}

}  // namespace
}  // namespace wangscape
