// The ground light kept in a scene folder (renders/ldi/ground_light.h, write_ground_light): a
// folder built as `wangscape build` builds it holds the bytes the view would bake, its frames are
// those of a folder without the file (which still opens, and bakes the same light), and a damaged
// file is refused naming itself.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/error.h"
#include "folder/scene_folder.h"
#include "renders/scene_build.h"
#include "renders/view/ldi_renderer.h"
#include "tests/renders/view_test_world.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;
using view_test::bytes_of;
using view_test::looking;
using view_test::scratch;

// A tiny field built by build_scene with the LDI export: sky rays on (the sky's share varies), four
// levels (the steep sets' pack is written: the view does not sample them on a frame from above).
const fs::path& built_folder() {
  static const fs::path dir = view_test::built_ldi_folder("ground_light_field", "[-12.0, -12.0, 12.0, 12.0]",
                                                          "levels = 4\ndirections = 2\nsky_rays = 4\n");
  return dir;
}

// A copy of the built folder as `name`, without its ground light file.
fs::path copy_without_ground_light(const std::string& name) {
  const fs::path copy = scratch(name);
  fs::remove_all(copy);
  fs::copy(built_folder(), copy, fs::copy_options::recursive);
  fs::remove(FolderFiles(copy).ground_light());
  return copy;
}

std::vector<std::uint8_t> frame_from_above(const std::shared_ptr<const ViewWorld>& world) {
  LdiRenderer renderer(world, 160, 90);
  renderer.render(looking(0.3, -1, 9, 0.3, -0.5, 0, 60));
  return renderer.image().pixels;
}

TEST(GroundLightFile, TheFolderHoldsTheBytesTheViewWouldBake) {
  const FolderFiles files(built_folder());
  const SceneFolder folder = SceneFolder::open(files.root(), SceneFolder::Parts::pack);
  ASSERT_EQ(folder.ground_light(), files.ground_light());
  const Scene scene = folder.make_scene();
  const std::size_t tiles = scene.field->filled.tiles.size();
  EXPECT_EQ(fs::file_size(files.ground_light()), 20 + 2 * tiles * kGroundLightResolution * kGroundLightResolution);
  const TileGroundLight baked = bake_scene_ground_light(scene, folder.light(), kGroundLightResolution);
  const TileGroundLight read = read_ground_light(files.ground_light(), tiles, kGroundLightResolution);
  EXPECT_TRUE(read == baked);  // every level: the coarser ones made again on reading
  // Not all open: the plants shade the ground, from the sun and from the sky.
  int sun_shaded = 0, sky_shaded = 0;
  for (const TileGroundLight::Texel& texel : read.texels(0, 0))
    sun_shaded += texel.sun < 255, sky_shaded += texel.sky < 255;
  EXPECT_GT(sun_shaded, 100);
  EXPECT_GT(sky_shaded, 100);
  // Written again, the same bytes.
  const fs::path again = scratch("ground_light_again.bin");
  write_ground_light(again, read);
  EXPECT_TRUE(bytes_of(again) == bytes_of(files.ground_light()));
}

TEST(GroundLightFile, AFolderWithoutItOpensWithTheSameLightAndFrames) {
  const auto kept = ViewWorld::load(built_folder());
  const auto baked = ViewWorld::load(copy_without_ground_light("ground_light_none"));
  EXPECT_TRUE(kept->ground_light() == baked->ground_light());
  const std::vector<std::uint8_t> frame = frame_from_above(kept);
  EXPECT_EQ(frame, frame_from_above(baked));
  // The view reads the file: a folder whose file says the ground is all in shade draws another frame.
  const fs::path dark = copy_without_ground_light("ground_light_dark");
  TileGroundLight shade = kept->ground_light();
  for (std::size_t t = 0; t < shade.tiles(); ++t)
    for (TileGroundLight::Texel& texel : shade.texels(t, 0)) texel = {0, 0};
  write_ground_light(FolderFiles(dark).ground_light(), shade);
  EXPECT_NE(frame_from_above(ViewWorld::load(dark)), frame);
}

// Damaged files: each refused with an Error naming the file and what was expected, by the reader
// and by the view opening a folder that holds it.
TEST(GroundLightFile, ADamagedFileIsRefusedNamingIt) {
  const std::string bytes = bytes_of(FolderFiles(built_folder()).ground_light());
  const fs::path folder = copy_without_ground_light("ground_light_damaged");
  const fs::path file = FolderFiles(folder).ground_light();
  const std::size_t tiles = (bytes.size() - 20) / (2 * kGroundLightResolution * kGroundLightResolution);
  const auto refused = [&](const std::string& damaged, const std::string& expected) {
    {
      std::ofstream out(file, std::ios::binary | std::ios::trunc);
      out << damaged;
    }
    for (int view = 0; view < 2; ++view) try {
        if (view)
          ViewWorld::load(folder);
        else
          read_ground_light(file, tiles, kGroundLightResolution);
        ADD_FAILURE() << "accepted: " << expected;
      } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("ground_light_damaged/ground_light.bin: "), std::string::npos) << what;
        EXPECT_NE(what.find(expected), std::string::npos) << what;
      }
  };
  const auto with_u32 = [&](std::size_t at, std::uint32_t value) {
    std::string out = bytes;
    for (int k = 0; k < 4; ++k) out[at + std::size_t(k)] = char(value >> (8 * k));
    return out;
  };
  refused(bytes.substr(0, bytes.size() - 3),
          "truncated: " + std::to_string(bytes.size() - 3) + " bytes, expected " + std::to_string(bytes.size()));
  refused(bytes.substr(0, 14), "truncated: expected the ground light header");
  refused(bytes + "x", "longer than its texels");
  refused("WSCSKY\r\n" + bytes.substr(8), "not a ground light file (expected it to start with WSCGLT)");
  refused(with_u32(8, 2), "version 2: expected 1");
  refused(with_u32(12, 32), "a resolution of 32 texels across a tile: expected 64");
  refused(with_u32(16, std::uint32_t(tiles + 1)),
          std::to_string(tiles + 1) + " tiles: expected the tile set's " + std::to_string(tiles));
}

}  // namespace
}  // namespace wangscape
