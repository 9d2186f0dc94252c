// The flowers' sky shares kept in a scene folder (renders/trace/field_sky.h, issue 40's first
// frame): read back as written, the view's frames the same as with its own estimate, and a damaged
// file refused naming itself.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "core/error.h"
#include "renders/trace/field_sky.h"
#include "renders/view/ldi_renderer.h"
#include "tests/renders/view_test_world.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;
using view_test::looking;
using view_test::scratch;
using view_test::tiny_scene;

Scene tiny_field() {
  return make_scene(
      parse_scene_config(tiny_scene("[-12.0, -12.0, 12.0, 12.0]"), "sky.toml", fs::temp_directory_path()));
}

ShadingSettings with_sky_rays() {
  ShadingSettings shading;
  shading.ao_rays = 8;
  return shading;
}

TEST(FieldSky, TheFolderFileDrawsTheFramesOfTheViewsOwnEstimate) {
  Scene scene = tiny_field();
  const SceneTracer::SkyShares shares = bake_field_sky(scene, with_sun(with_sky_rays(), scene.sun));
  ASSERT_EQ(shares.size(), scene.models.size());
  double sum = 0, count = 0;
  for (const auto& model : shares)
    for (const auto& vertex : model) sum += vertex[0] + vertex[1], count += 2;
  EXPECT_GT(sum / count, 0.2);  // the flowers see some sky, and not all of it
  EXPECT_LT(sum / count, 0.99);
  const fs::path file = scratch("sky.bin");
  write_sky_shares(file, shares);
  EXPECT_EQ(read_sky_shares(file, scene), shares);

  // A pack to view them with, and two worlds: the folder's shares, and the view's own estimate.
  LdiBuildOptions options;
  options.view.levels = 3;
  options.view.directions = 4;
  options.view.image_width = 128;
  options.shading = with_sky_rays();
  const fs::path pack = scratch("sky.ldi");
  build_scene_ldi_pack(scene, pack, options);
  const auto own = std::make_shared<const ViewWorld>(tiny_field(), pack, options.shading);
  const auto kept = std::make_shared<const ViewWorld>(std::move(scene), pack, options.shading, nullptr,
                                                      ViewWorld::Prepared{{}, file, {}});
  EXPECT_EQ(own->sky_shares(), kept->sky_shares());
  const Camera in_field = looking(0.3, -6, 1.7, 0.3, 10, 1.0);
  std::vector<std::uint8_t> frames[2];
  for (int k = 0; k < 2; ++k) {
    LdiRenderer renderer(k ? kept : own, 160, 90);
    renderer.render(in_field);
    frames[k] = renderer.image().pixels;
  }
  EXPECT_EQ(frames[0], frames[1]);
}

// Damaged files: each refused with an Error naming the file and what is wrong.
TEST(FieldSky, ADamagedFileIsRefusedNamingIt) {
  const Scene scene = tiny_field();
  const fs::path file = scratch("damaged_sky.bin");
  write_sky_shares(file, bake_field_sky(scene, with_sun(with_sky_rays(), scene.sun)));
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto refused = [&](const std::string& damaged, const std::string& expected) {
    {
      std::ofstream out(file, std::ios::binary | std::ios::trunc);
      out << damaged;
    }
    try {
      read_sky_shares(file, scene);
      ADD_FAILURE() << "accepted: " << expected;
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("damaged_sky.bin"), std::string::npos) << what;
      EXPECT_NE(what.find(expected), std::string::npos) << what;
    }
  };
  refused(bytes.substr(0, bytes.size() - 3), "truncated");
  refused(bytes + "x", "longer than");
  refused("WSCSKZ\r\n" + bytes.substr(8), "not a sky shares file");
  std::string other_version = bytes;
  other_version[8] = 2;
  refused(other_version, "version 2: expected 1");
  std::string other_models = bytes;
  other_models[12] = char(other_models[12] + 1);
  refused(other_models, "models: expected the scene's");
  std::string nan_share = bytes;
  const float nan = std::nanf("");
  nan_share.replace(nan_share.size() - 4, 4, reinterpret_cast<const char*>(&nan), 4);
  refused(nan_share, "outside [0, 1]");
}

}  // namespace
}  // namespace wangscape
