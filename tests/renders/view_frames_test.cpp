// The view's frames as typed calls (renders/view/view_frames.h) on the tiny field of
// view_test_world.h: a path played frame by frame hands every frame in order, its first cached
// frame the renderer's own, the compared frames with their truth; a path off the ground or too
// long is refused before the first frame; the camera takes the parts given and refuses the rest
// in words that name no flag. Suites are named ldi_view_frames so `ctest -R ldi` runs them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "renders/view/view_frames.h"
#include "tests/generator/test_support.h"
#include "tests/renders/view_test_world.h"

namespace wangscape {
namespace {

using namespace view_test;

// 0.3 s from the south edge of the field toward its middle: 4 frames at 10 frames/s.
const ViewPath& walk() {
  static const ViewPath path = parse_view_path(
      R"({"keyframes": [{"time": 0, "position": [0, -16, 2.2], "look_at": [0, 0, 1.2]},
                        {"time": 0.3, "position": [2, -10, 2.0], "look_at": [0, 4, 1.0]}]})",
      "walk.json");
  return path;
}

PathPlayback small_playback() {
  PathPlayback playback;
  playback.width = 48;
  playback.height = 32;
  playback.fps = 10;
  return playback;
}

using wangscape::testing::error_of;

TEST(ldi_view_frames, APathIsPlayedFrameByFrameInOrder) {
  PathPlayback playback = small_playback();
  playback.compare_every = 2;
  playback.truth_samples = 2;
  std::vector<long long> frames, compared;
  std::vector<std::uint8_t> first;
  Camera first_camera;
  play_view_path(field(), walk(), "walk.json", playback, [&](const PathFrame& frame) {
    EXPECT_EQ(frame.count, 4);
    EXPECT_EQ(frame.image->width, 48);
    EXPECT_EQ(frame.image->height, 32);
    ASSERT_NE(frame.cached, nullptr);
    EXPECT_EQ(frame.cached->cold, frame.index == 0);
    EXPECT_DOUBLE_EQ(frame.fresh_share, frame.cached->fresh_share());
    const GroundHeightAt ground = [](double e, double n) { return field()->scene().field->ground.height(e, n); };
    const Camera expected = camera_along(walk(), double(frame.index) / 10, 60, ground, "walk.json");
    EXPECT_EQ(frame.camera.position, expected.position);
    frames.push_back(frame.index);
    if (frame.comparison) {
      compared.push_back(frame.index);
      EXPECT_EQ(frame.comparison->truth.width, 48);
      EXPECT_GT(frame.comparison->comparison.psnr_db, 10);
    }
    if (frame.index == 0) {
      first = frame.image->pixels;
      first_camera = frame.camera;
    }
  });
  EXPECT_EQ(frames, (std::vector<long long>{0, 1, 2, 3}));
  EXPECT_EQ(compared, (std::vector<long long>{0, 2}));
  // The first frame is cold: the renderer's own bytes.
  LdiRenderer renderer(field(), 48, 32);
  renderer.apply(playback.settings);
  renderer.render(first_camera);
  EXPECT_EQ(renderer.image().pixels, first);
}

TEST(ldi_view_frames, AnUncachedPathDrawsEveryFrameWhole) {
  PathPlayback playback = small_playback();
  playback.cached = false;
  int frames = 0;
  play_view_path(field(), walk(), "walk.json", playback, [&](const PathFrame& frame) {
    EXPECT_EQ(frame.cached, nullptr);
    EXPECT_EQ(frame.fresh_share, 1);
    EXPECT_EQ(frame.comparison, nullptr);
    ++frames;
  });
  EXPECT_EQ(frames, 4);
}

TEST(ldi_view_frames, APathOffTheGroundIsRefusedBeforeTheFirstFrame) {
  const ViewPath off = parse_view_path(
      R"({"keyframes": [{"time": 0, "position": [0, -16], "height_above_ground": 2, "look_at": [0, 0, 1]},
                        {"time": 1, "position": [5000, -10], "height_above_ground": 2, "look_at": [0, 0, 1]}]})",
      "off.json");
  int frames = 0;
  const std::string message = error_of(
      [&] { play_view_path(field(), off, "off.json", small_playback(), [&](const PathFrame&) { ++frames; }); });
  EXPECT_NE(message.find("off.json: at 1.000 s the eye"), std::string::npos) << message;
  EXPECT_EQ(frames, 0);
}

TEST(ldi_view_frames, TooManyFramesAreRefusedNamingWhatSetsTheRate) {
  ViewPath hour = walk();
  hour.keys.back().time = 3600;
  EXPECT_EQ(path_frame_count(hour, 24, "hour.json"), 86401);
  const std::string library = error_of([&] { path_frame_count(hour, 240, "hour.json"); });
  EXPECT_NE(library.find("hour.json: lasts 3600 s: 864001 frames at 240 frames/s; at most 100000 are rendered "
                         "(lower the frame rate or cut the path in parts)"),
            std::string::npos)
      << library;
  EXPECT_NE(error_of([&] { path_frame_count(hour, 240, "hour.json", "--fps"); }).find("(lower --fps or"),
            std::string::npos);
}

TEST(ldi_view_frames, TheCameraTakesThePartsGivenAndTheScenesOthers) {
  const Camera& scene = field()->scene().camera;
  EXPECT_EQ(view_camera(*field(), {}).position, scene.position);
  EXPECT_EQ(view_camera(*field(), {}).fov_degrees, scene.fov_degrees);
  const double head = std::numeric_limits<double>::quiet_NaN();
  CameraChoice choice;
  choice.position = {1, -16, head};
  choice.look_at = {0, 0, 1.2};
  choice.fov_degrees = 40;
  const Camera camera = view_camera(*field(), choice);
  EXPECT_EQ(camera.fov_degrees, 40);
  EXPECT_EQ(camera.target, (std::array<double, 3>{0, 0, 1.2}));
  const double ground = *field()->scene().field->ground.height(1, -16);
  EXPECT_DOUBLE_EQ(camera.position[2], ground + field()->pack().info().head_height);
}

TEST(ldi_view_frames, TheCamerasRefusalsNameNoFlag) {
  const double head = std::numeric_limits<double>::quiet_NaN();
  CameraChoice wide;
  wide.fov_degrees = 200;
  CameraChoice off;
  off.position = {5000, 0, head};
  CameraChoice above;
  above.position = {0, -16, 10};
  above.look_at = {0, -16, 0};
  for (const auto& [choice, words] :
       {std::pair{wide, "field of view 200: expected degrees in (0, 179]"},
        std::pair{off, "eye at 5000,0: not over the ground"}, std::pair{above, "must lie sideways of the eye"}}) {
    const std::string message = error_of([&] { view_camera(*field(), choice); });
    EXPECT_NE(message.find(words), std::string::npos) << message;
    EXPECT_EQ(message.find("--"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace wangscape
