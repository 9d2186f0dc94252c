// The nesting check before parsing (issue 25): depth is brackets and keys, never the decimal
// points of numbers, so JSON written on one line (as json.dump writes it) reads as on many.
#include "core/text_file.h"

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"

namespace wangscape {
namespace {

std::string repeat(const std::string& part, int times) {
  std::string out;
  for (int k = 0; k < times; ++k) out += part;
  return out;
}

// The message of check_nesting's refusal, or "" when it passes.
std::string refusal(const std::string& text) {
  try {
    check_nesting(text, "f", kMaxNesting);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CheckNesting, NumbersOnOneLineAreNotKeys) {
  const std::string points = std::string("[") + repeat("0.5, ", 200) + "0.25]";
  EXPECT_EQ(refusal(std::string("{\"name\": \"c\", \"tiles\": [{\"x\": 0.5, \"points\": ") + points + "}]}\n"), "");
  EXPECT_EQ(refusal(points), "");                                                       // a top-level JSON array
  EXPECT_EQ(refusal(std::string("a = ") + points + "\nb = {c = 1.5, d = 2.5}\n"), "");  // TOML values
  EXPECT_EQ(refusal(std::string("a = [\n") + repeat("1.5, ", 100) + "\n]\n"), "");      // a multi-line array
}

TEST(CheckNesting, DeepKeysAndBracketsAreRefusedWithTheirLine) {
  EXPECT_EQ(refusal(std::string("x = 1\na") + repeat(".a", 100) + " = 1\n"),
            "f:2: a key of more than 64 dotted parts; tables nest at most that deep");
  EXPECT_EQ(refusal(std::string("[a") + repeat(".a", 65) + "]\n"),
            "f:1: a key of more than 64 dotted parts; tables nest at most that deep");
  EXPECT_EQ(refusal(std::string("x = {a") + repeat(".a", 65) + " = 1}\n"),
            "f:1: a key of more than 64 dotted parts; tables nest at most that deep");
  EXPECT_EQ(refusal(std::string("a") + repeat(".a", 63) + " = 1\n"), "");  // 64 parts
  EXPECT_EQ(refusal(std::string("{\"a\": ") + repeat("[", 65) + repeat("]", 65) + "}"),
            "f:1: brackets nest deeper than 64 levels; that is not a scene or tile set");
  EXPECT_EQ(refusal(repeat("[", 64) + repeat("]", 64)), "");
}

}  // namespace
}  // namespace wangscape
