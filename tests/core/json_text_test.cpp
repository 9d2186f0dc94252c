// What reaches the user of a JSON library's exception (issue 25): its text without the
// "[json.exception.NAME] " id; other exceptions as they are.
#include "core/json_text.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace wangscape {
namespace {

TEST(JsonErrorText, DropsTheLibraryIdAndKeepsWhereAndWhat) {
  EXPECT_EQ(json_error_text(
                std::runtime_error("[json.exception.parse_error.101] parse error at line 1, column 2: syntax error")),
            "parse error at line 1, column 2: syntax error");
  EXPECT_EQ(json_error_text(std::runtime_error("[json.exception.out_of_range.406] number overflow parsing '1e5456'")),
            "number overflow parsing '1e5456'");
  EXPECT_EQ(json_error_text(std::runtime_error("plan.json: task 3: [x] kept")), "plan.json: task 3: [x] kept");
}

}  // namespace
}  // namespace wangscape
