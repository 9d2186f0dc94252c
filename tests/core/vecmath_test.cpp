// The vector and colour module: dot/cross/normalized keep float as float and double as double,
// the camera basis is right-handed and refuses what cannot frame a horizon, the sRGB transfer
// round-trips every 8-bit code.
#include "core/vecmath.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <type_traits>

#include "core/color.h"

namespace wangscape {
namespace {

TEST(Vecmath, DotCrossAndLengthKeepTheirType) {
  const Vector3f a{1, 2, 3}, b{4, 5, 6};
  static_assert(std::is_same_v<decltype(dot(a, b)), float>);
  static_assert(std::is_same_v<decltype(cross(Vector3d{}, Vector3d{})), Vector3d>);
  EXPECT_EQ(dot(a, b), 32.0f);
  EXPECT_EQ(cross(a, b), (Vector3f{-3, 6, -3}));
  EXPECT_EQ(cross(Vector3d{1, 0, 0}, Vector3d{0, 1, 0}), (Vector3d{0, 0, 1}));
  EXPECT_DOUBLE_EQ(length(Vector3d{3, 4, 12}), 13.0);
  EXPECT_EQ(normalized(Vector3d{0, 3, 4}), (Vector3d{0, 0.6, 0.8}));
  EXPECT_EQ(Vector3d({1, 2, 3}) - Vector3d({1, 1, 1}) + 2.0 * Vector3d({1, 0, 0}), (Vector3d{2, 1, 2}));
}

TEST(Vecmath, CameraBasisIsRightHandedWithAHorizontalRight) {
  const auto b = camera_basis({0, 0, 2}, {0, 10, 2});
  ASSERT_TRUE(b);
  EXPECT_EQ(b->forward, (Vector3d{0, 1, 0}));
  EXPECT_EQ(b->right, (Vector3d{1, 0, 0}));  // east when looking north
  EXPECT_EQ(b->up, (Vector3d{0, 0, 1}));
  const auto tilted = camera_basis({0, 0, 0}, {3, 4, -5});
  ASSERT_TRUE(tilted);
  EXPECT_NEAR(length(tilted->forward), 1, 1e-15);
  EXPECT_EQ(tilted->right[2], 0);
  EXPECT_NEAR(dot(tilted->up, tilted->forward), 0, 1e-15);
}

TEST(Vecmath, CameraBasisRefusesWhatCannotFrameAHorizon) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(camera_basis({0, 0, 10}, {0, 0, 0}));  // straight down
  EXPECT_FALSE(camera_basis({0, 0, 0}, {0, 0, 5}));   // straight up
  EXPECT_FALSE(camera_basis({1, 2, 3}, {1, 2, 3}));   // at its own position
  EXPECT_FALSE(camera_basis({nan, 0, 0}, {1, 0, 0}));
  EXPECT_FALSE(camera_basis({0, 0, 0}, {inf, 0, 0}));
  EXPECT_TRUE(valid_field_of_view(50));
  EXPECT_FALSE(valid_field_of_view(0));
  EXPECT_TRUE(valid_field_of_view(kMaxFieldOfViewDegrees));
  EXPECT_FALSE(valid_field_of_view(kMaxFieldOfViewDegrees + 0.5));
  EXPECT_FALSE(valid_field_of_view(nan));
  try {
    check_field_of_view(200, "--fov");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "--fov 200: expected degrees in (0, 179]");
  }
}

TEST(Color, SrgbRoundTripsEveryCode) {
  for (int i = 0; i < 256; ++i) EXPECT_EQ(linear_to_srgb8(srgb8_to_linear(std::uint8_t(i))), i) << i;
  EXPECT_EQ(linear_to_srgb8(-1.0f), 0);
  EXPECT_EQ(linear_to_srgb8(2.0f), 255);
  EXPECT_FLOAT_EQ(srgb_to_linear(0.5f), 0.21404114f);
}

}  // namespace
}  // namespace wangscape
