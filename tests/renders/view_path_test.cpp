// The path file of `view --path`: heights above the ground, the spline over the ground, and
// refusals of what a hostile or careless file holds (each naming the place at fault).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "scene/view_path.h"

namespace wangscape {
namespace {

// A ground that rises 1 m per 10 m east, and has no ground west of E = -100.
std::optional<double> sloped_ground(double east, double) {
  if (east < -100) return std::nullopt;
  return 1000 + 0.1 * east;
}

std::string refusal(const std::string& text) {
  try {
    parse_view_path(text, "walk.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ViewPath, HeightsAboveTheGroundFollowTheTerrain) {
  const ViewPath path = parse_view_path(
      R"({"keyframes": [
        {"time": 0, "position": [0, 0], "height_above_ground": 1.7, "look_at": [0, 50], "look_at_height_above_ground": 1},
        {"time": 2, "position": [20, 0], "height_above_ground": 1.7, "look_at": [20, 50], "look_at_height_above_ground": 1},
        {"time": 4, "position": [40, 0], "height_above_ground": 1.7, "look_at": [40, 50], "look_at_height_above_ground": 1}]})",
      "walk.json");
  ASSERT_TRUE(path.position_above_ground);
  ASSERT_TRUE(path.look_at_above_ground);
  EXPECT_EQ(path.frame_count(24), 97);
  for (double t = 0; t <= 4; t += 0.25) {
    const Camera c = camera_along(path, t, 50, sloped_ground, "walk.json");
    EXPECT_NEAR(c.position[2] - *sloped_ground(c.position[0], 0), 1.7, 1e-9) << t;
    EXPECT_NEAR(c.target[2] - *sloped_ground(c.target[0], 0), 1.0, 1e-9) << t;
    if (std::fmod(t, 2) == 0) {
      EXPECT_NEAR(c.position[0], 10 * t, 1e-9) << t;  // the spline passes the keys
    }
  }
}

TEST(ViewPath, AbsoluteHeightsAreKeptAndTheJsonRoundTrips) {
  const std::string text =
      R"({"keyframes": [{"time": 0, "position": [1, 2, 1500], "look_at": [1, 80, 1490]},
                        {"time": 3.5, "position": [4, 5, 1510], "look_at": [4, 90, 1495]}]})";
  const ViewPath path = parse_view_path(text, "walk.json");
  EXPECT_FALSE(path.position_above_ground);
  const Camera c = camera_along(path, 3.5, 50, sloped_ground, "walk.json");
  EXPECT_DOUBLE_EQ(c.position[2], 1510);
  const ViewPath again = parse_view_path(view_path_json(path), "again.json");
  ASSERT_EQ(again.keys.size(), 2u);
  EXPECT_EQ(again.keys[1].look_at, path.keys[1].look_at);
  EXPECT_EQ(again.keys[1].time, 3.5);

  ViewPath recorded = path;
  recorded.position_above_ground = true;
  recorded.keys[0].position[2] = recorded.keys[1].position[2] = 1.7;
  const ViewPath recorded_again = parse_view_path(view_path_json(recorded), "recorded.json");
  EXPECT_TRUE(recorded_again.position_above_ground);
  EXPECT_FALSE(recorded_again.look_at_above_ground);
  EXPECT_EQ(recorded_again.keys[0].position[2], 1.7);
}

// Two equal keyframes hold the camera still between them: the spline's tangents, taken from the
// keys around, swung a walk meant to stand still at its end past the key and back (issue 40).
TEST(ViewPath, ARepeatedKeyframeHoldsTheCameraStill) {
  const std::string text =
      R"({"keyframes": [{"time": 0, "position": [0, 0, 1500], "look_at": [0, 50, 1500]},
                        {"time": 2, "position": [10, 3, 1500], "look_at": [10, 60, 1498]},
                        {"time": 4, "position": [10, 3, 1500], "look_at": [10, 60, 1498]},
                        {"time": 6, "position": [30, 9, 1502], "look_at": [40, 60, 1498]}]})";
  const ViewPath path = parse_view_path(text, "stop.json");
  for (double t = 2; t <= 4; t += 0.125) {
    const Camera c = camera_along(path, t, 50, sloped_ground, "stop.json");
    EXPECT_EQ(c.position, (std::array<double, 3>{10, 3, 1500})) << t;
    EXPECT_EQ(c.target, (std::array<double, 3>{10, 60, 1498})) << t;
  }
  // Moving either side of the stop.
  EXPECT_NE(camera_along(path, 1.5, 50, sloped_ground, "stop.json").position[0], 10);
  EXPECT_NE(camera_along(path, 4.5, 50, sloped_ground, "stop.json").position[0], 10);
}

TEST(ViewPath, AHeightAboveNoGroundIsRefusedWithItsTime) {
  const ViewPath path = parse_view_path(
      R"({"keyframes": [{"time": 0, "position": [0, 0], "height_above_ground": 2, "look_at": [0, 50, 1000]},
                        {"time": 1, "position": [-400, 0], "height_above_ground": 2, "look_at": [0, 50, 1000]}]})",
      "walk.json");
  try {
    camera_along(path, 1, 50, sloped_ground, "walk.json");
    FAIL() << "expected a refusal";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("at 1.000 s the eye"), std::string::npos) << e.what();
  }
}

TEST(ViewPath, RefusesWhatItCannotUseNamingThePlace) {
  const std::string key = R"({"time": 0, "position": [0, 0, 10], "look_at": [0, 1, 10]})";
  struct Case {
    std::string text, expected;
  };
  const Case cases[] = {
      {"", "walk.json:1:1: not valid JSON"},
      {"{\"keyframes\": [1,\n2", "walk.json:2:2: not valid JSON"},
      {R"({"keyframes": [)" + key + "]}", "walk.json:keyframes: expected"},
      {R"({"keyframes": )" + key + "}", "walk.json: expected {\"keyframes\""},
      {R"({"keyframes": [)" + key + R"(, {"time": 0, "position": [0, 0, 10], "look_at": [0, 1, 10]}]})",
       "keyframes[1].time: is 0; times must be ascending"},
      {R"({"keyframes": [)" + key + R"(, {"time": 1, "position": [0, 0, 1e300], "look_at": [0, 1, 10]}]})",
       "keyframes[1].position[2]: is 1e+300; expected meters in -12000 .. 100000"},
      {R"({"keyframes": [)" + key + R"(, {"time": 1, "position": [0, 0, 1e400], "look_at": [0, 1, 10]}]})",
       "walk.json: a number too large"},
      {R"({"keyframes": [)" + key + R"(, {"time": 1, "position": [0, 0], "look_at": [0, 1, 10]}]})",
       "keyframes[1].position: expected [E, N, H] in meters (no \"height_above_ground\""},
      {R"({"keyframes": [)" + key +
           R"(, {"time": 1, "position": [0, 0, 1], "height_above_ground": 1, "look_at": [0, 1, 10]}]})",
       "keyframes[1]: gives its heights another way than keyframe 0"},
      {R"({"keyframes": [)" + key + R"(, {"time": 1, "position": [0, 0, "x"], "look_at": [0, 1, 10]}]})",
       "keyframes[1].position[2]: expected a number of meters"},
      {R"({"keyframes": [)" + key + R"(, {"time": 1, "position": [0, 0, 1]}]})", "keyframes[1]: expected \"look_at\""},
      {R"({"keyframes": [)" + key + R"(, {"time": 4000, "position": [0, 0, 1], "look_at": [0, 1, 10]}]})",
       "walk.json: the path lasts 4000 s; at most an hour"},
      {R"({"keyframes": [{"time": 0, "position": [0, 0], "height_above_ground": -1, "look_at": [0, 1, 10]}, 2]})",
       "keyframes[0].height_above_ground: is -1; expected meters above the ground in 0 .. 100000"},
      {std::string(100, '[') + std::string(100, ']'), "brackets nest deeper than 64"},
  };
  for (const Case& c : cases) {
    const std::string message = refusal(c.text);
    EXPECT_NE(message.find(c.expected), std::string::npos) << "text: " << c.text << "\nmessage: " << message;
    EXPECT_EQ(message.find("json.exception"), std::string::npos) << message;
  }
}

// Issue 41: a keyframe looking at its own eye (or straight down on it) reached the renderer, which
// said "the camera must look somewhere sideways" without the file or the keyframe.
TEST(ViewPath, ALookAtStraightAboveBelowOrAtTheEyeIsRefusedNamingTheKeyframe) {
  const std::string key = R"({"time": 0, "position": [0, 0, 10], "look_at": [0, 1, 10]})";
  for (const char* look_at : {"[0, 0, 10]", "[0, 0, 0]", "[0.0001, 0, 50]"}) {
    const std::string message =
        refusal(R"({"keyframes": [)" + key + R"(, {"time": 1, "position": [0, 0, 10], "look_at": )" + look_at + "}]}");
    EXPECT_NE(message.find("walk.json:keyframes[1].look_at: is straight above, below or at the position"),
              std::string::npos)
        << look_at << ": " << message;
  }
  EXPECT_NE(refusal(R"({"keyframes": [{"time": 0, "position": [5, 5], "height_above_ground": 2, "look_at": [5, 5],
                      "look_at_height_above_ground": 1}, 2]})")
                .find("walk.json:keyframes[0].look_at: is straight above"),
            std::string::npos);
  // Keyframes that look sideways, whose eye and look-at point meet between them: named with the time.
  const ViewPath crossing = parse_view_path(
      R"({"keyframes": [{"time": 0, "position": [0, -16, 2.2], "look_at": [0, 0, 1.2]},
                        {"time": 1, "position": [0, 0, 2.2], "look_at": [0, -16, 1.2]}]})",
      "cross.json");
  EXPECT_NO_THROW(camera_along(crossing, 0.25, 50, sloped_ground, "cross.json"));
  try {
    camera_along(crossing, 0.5, 50, sloped_ground, "cross.json");
    ADD_FAILURE() << "the crossing was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cross.json: at 0.500 s the look-at point (0, -8) is straight above, below or "
                                         "at the eye (0, -8)"),
              std::string::npos)
        << e.what();
  }
}

TEST(ViewPath, TooManyKeyframesAreRefusedBeforeTheyAreKept) {
  std::string text = R"({"keyframes": [)";
  for (std::size_t k = 0; k <= kMaxPathKeyframes; ++k) {
    if (k) text += ',';  // (appended char by char: GCC 12 warned -Wrestrict on "," + std::string)
    text += '0';
  }
  text += "]}";
  EXPECT_NE(refusal(text).find("holds 100001 keyframes; at most 100000"), std::string::npos) << refusal(text);
}

}  // namespace
}  // namespace wangscape
