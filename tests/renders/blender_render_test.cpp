// The real Blender: the add-on imports an exported scene (checked inside Blender by
// tests/blender/check_import.py), and `render_blender` renders it with Cycles to a PNG that
// is not blank. Errors name what is missing.
#include "renders/external/blender_render.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "core/atomic_file.h"
#include "exporters/blender_export.h"
#include "renders/external/child_process.h"
#include "tests/blender/test_scene.h"

namespace wangscape {
namespace {

std::filesystem::path scratch(const std::string& name) {
  const auto path =
      std::filesystem::temp_directory_path() / ("wangscape_blender_render_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(path);
  std::filesystem::create_directories(path);
  return path;
}

TEST(BlenderRender, AddonImportMatchesManifestInsideBlender) {
  ASSERT_FALSE(find_blender().empty()) << "the real blender is required (apt install blender)";
  const auto dir = scratch("check");
  const auto summary = export_blender(testing::make_test_scene(2500, 16, 30.0f, 1000), dir / "blender");
  const auto log = dir / "check.log";
  const ChildExit exit =
      run_logged({find_blender().string(), "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                  std::string(WANGSCAPE_SOURCE_DIR) + "/tests/blender/check_import.py", "--",
                  (dir / "blender" / "wangscape_import.zip").string(), summary.manifest.string(), "5"},
                 log);
  EXPECT_TRUE(exit.exited && exit.status == 0) << exit.describe() << last_log_lines(log, 30);
  EXPECT_NE(last_log_lines(log, 200).find("wangscape-check: OK: 2500 instances"), std::string::npos)
      << last_log_lines(log, 30);
  std::filesystem::remove_all(dir);
}

TEST(BlenderRender, AddonZipInstallsInStockBlender) {
  // The zip beside every export, installed the way Preferences > Add-ons > Install does,
  // into an empty user scripts folder (BLENDER_USER_SCRIPTS) so the user's setup is untouched.
  const auto dir = scratch("install");
  export_blender(testing::make_test_scene(10, 4, 10.0f), dir / "blender");
  const auto log = dir / "install.log";
  const ChildExit exit = run_logged({"/usr/bin/env", "BLENDER_USER_SCRIPTS=" + (dir / "user_scripts").string(),
                                     find_blender().string(), "-b", "--factory-startup", "--python-exit-code", "1",
                                     "--python", std::string(WANGSCAPE_SOURCE_DIR) + "/tests/blender/install_addon.py",
                                     "--", (dir / "blender" / "wangscape_import.zip").string()},
                                    log);
  EXPECT_TRUE(exit.exited && exit.status == 0) << exit.describe() << last_log_lines(log, 20);
  EXPECT_NE(last_log_lines(log, 50).find("wangscape-install: OK"), std::string::npos) << last_log_lines(log, 20);
  EXPECT_TRUE(std::filesystem::exists(dir / "user_scripts" / "addons" / "wangscape_import" / "scene_builder.py"));
  std::filesystem::remove_all(dir);
}

TEST(BlenderRender, CyclesRendersANonBlankImage) {
  const auto dir = scratch("cycles");
  export_blender(testing::make_test_scene(1500, 16, 30.0f), dir / "blender");
  BlenderRenderOptions options;
  options.width = 160;
  options.height = 120;
  options.samples = 4;
  const BlenderRenderResult result = render_blender(dir, options);
  EXPECT_EQ(result.image, dir / "render_blender.png");
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "scene.blend"));
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "blender.log"));

  OIIO::ImageBuf image(result.image.string());
  ASSERT_TRUE(image.read()) << image.geterror();
  EXPECT_EQ(image.spec().width, 160);
  EXPECT_EQ(image.spec().height, 120);
  const auto stats = OIIO::ImageBufAlgo::computePixelStats(image);
  ASSERT_GE(stats.avg.size(), 3u);
  const float mean = (stats.avg[0] + stats.avg[1] + stats.avg[2]) / 3.0f;
  const float deviation = (stats.stddev[0] + stats.stddev[1] + stats.stddev[2]) / 3.0f;
  EXPECT_GT(mean, 0.05f) << "too dark";
  EXPECT_LT(mean, 0.95f) << "blown out";
  EXPECT_GT(deviation, 0.03f) << "flat image: no terrain or flowers visible";
  // Sunflowers are yellow: red and green clearly above blue on average.
  EXPECT_GT(stats.avg[1], stats.avg[2]);
  // No temporary files left behind.
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  }
  std::filesystem::remove_all(dir);
}

TEST(BlenderRender, MissingManifestIsNamed) {
  const auto dir = scratch("empty");
  try {
    render_blender(dir);
    FAIL() << "expected Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("manifest.json"), std::string::npos) << error.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(BlenderRender, MissingBlenderIsNamed) {
  const auto dir = scratch("noblender");
  export_blender(testing::make_test_scene(10, 4, 10.0f), dir);
  BlenderRenderOptions options;
  options.executable = "/nonexistent/blender-9";
  try {
    render_blender(dir, options);
    FAIL() << "expected Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/blender-9"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("not installed"), std::string::npos) << error.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(BlenderRender, BlenderFailureQuotesItsLog) {
  const auto dir = scratch("broken");
  export_blender(testing::make_test_scene(10, 4, 10.0f), dir);
  // A manifest Blender's add-on refuses: the error must come back with the add-on's words.
  write_file_atomically(dir / "manifest.json", R"({"format": {"name": "wangscape-blender", "version": 99}})");
  try {
    render_blender(dir);
    FAIL() << "expected Error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("exited with status"), std::string::npos) << message;
    EXPECT_NE(message.find("version 99"), std::string::npos) << message;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "render_blender.png"));
  EXPECT_FALSE(std::filesystem::exists(dir / "scene.blend"));
  EXPECT_TRUE(std::filesystem::exists(dir / "blender.log"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace wangscape
