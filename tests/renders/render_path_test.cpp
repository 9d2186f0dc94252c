// `wangscape render --path`'s frames (renders/render_path.h) against the view's (renders/view/
// view_frames.h) on the tiny field of view_test_world.h: frame k of the path is the same camera
// in both, bit for bit, so the same pinhole; the Embree reference of that camera and the view's
// frame agree within a loose PSNR; one Embree build traced for many frames gives the bytes of a
// build per frame; a frame left by an earlier run is complete only when whole and of the size.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "exporters/image_io.h"
#include "renders/render_path.h"
#include "renders/trace/embree_reference.h"
#include "renders/trace/image_compare.h"
#include "renders/view/view_frames.h"
#include "tests/renders/view_test_world.h"

namespace wangscape {
namespace {

using namespace view_test;

// 0.3 s toward the middle of the field, heights above the ground: 4 frames at 10 frames/s.
const ViewPath& walk() {
  static const ViewPath path = parse_view_path(
      R"({"keyframes": [{"time": 0, "position": [0, -16], "height_above_ground": 2.2,
                         "look_at": [0, 0], "look_at_height_above_ground": 1.2},
                        {"time": 0.3, "position": [2, -10], "height_above_ground": 2.0,
                         "look_at": [0, 4], "look_at_height_above_ground": 1.0}]})",
      "walk.json");
  return path;
}

TEST(render_path, FrameKIsTheViewsFrameK) {
  const auto& world = field();
  const std::vector<Camera> cameras = path_cameras(world->scene(), walk(), 10, "walk.json");
  ASSERT_EQ(cameras.size(), 4u);
  PathPlayback playback;
  playback.width = 64;
  playback.height = 36;
  playback.fps = 10;
  playback.fov_degrees = world->scene().camera.fov_degrees;
  playback.cached = false;  // every frame drawn whole, as a still of its camera
  std::vector<ImageRgb8> view_frames;
  play_view_path(world, walk(), "walk.json", playback, [&](const PathFrame& frame) {
    const Camera& mine = cameras[std::size_t(frame.index)];
    EXPECT_EQ(frame.camera.position, mine.position) << "frame " << frame.index;
    EXPECT_EQ(frame.camera.target, mine.target) << "frame " << frame.index;
    EXPECT_EQ(frame.camera.fov_degrees, mine.fov_degrees);
    // The same camera, so the same pinhole (the one both renderers frame with).
    const CameraFrame a = reference_camera_frame(frame.camera, 64, 36), b = reference_camera_frame(mine, 64, 36);
    EXPECT_EQ(a.origin, b.origin);
    EXPECT_EQ(a.forward, b.forward);
    EXPECT_EQ(a.right, b.right);
    EXPECT_EQ(a.up, b.up);
    view_frames.push_back(*frame.image);
  });
  ASSERT_EQ(view_frames.size(), cameras.size());

  // The Embree reference of frame k, as `render --engine embree --path` traces it.
  const ReferenceFrames traced(world->scene(), cameras.front().position);
  ReferenceOptions options;
  options.width = 64;
  options.height = 36;
  options.samples_per_pixel = 4;
  options.shading = world->shading();
  std::vector<ImageRgb8> embree_frames;
  for (std::size_t k = 0; k < cameras.size(); ++k) {
    options.camera = cameras[k];
    embree_frames.push_back(traced.render(options).image);
  }
  // Each view frame is nearest its own frame's reference: the PSNR sees the camera.
  for (std::size_t k = 0; k < cameras.size(); ++k) {
    const std::size_t other = k == 0 ? cameras.size() - 1 : 0;
    const double psnr = psnr_db(view_frames[k], embree_frames[k]);
    const double across = psnr_db(view_frames[k], embree_frames[other]);
    std::printf("frame %zu: view against embree %.1f dB, against embree's frame %zu %.1f dB\n", k, psnr, other, across);
    EXPECT_GT(psnr, 15.0) << "frame " << k;
    EXPECT_GT(psnr, across) << "frame " << k << " against " << other;
  }
}

TEST(render_path, OneBuildForManyFramesGivesTheBytesOfABuildPerFrame) {
  const Scene& scene = field()->scene();
  const std::vector<Camera> cameras = path_cameras(scene, walk(), 10, "walk.json");
  ReferenceOptions options;
  options.width = 48;
  options.height = 32;
  options.samples_per_pixel = 1;
  options.camera = cameras.front();
  const ReferenceFrames traced(scene, cameras.front().position);
  EXPECT_EQ(traced.render(options).image.pixels, render_reference(scene, options).image.pixels);
}

TEST(render_path, AFrameIsCompleteOnlyWhenWholeAndOfTheSize) {
  const auto file = scratch("frame-00000.png");
  ImageRgb8 image(8, 6);
  write_image(file, image);
  EXPECT_TRUE(complete_png(file, 8, 6));
  EXPECT_FALSE(complete_png(file, 8, 7));
  EXPECT_FALSE(complete_png(scratch("missing.png"), 8, 6));
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto cut = scratch("frame-00001.png");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() - 5);
  EXPECT_FALSE(complete_png(cut, 8, 6));
}

}  // namespace
}  // namespace wangscape
