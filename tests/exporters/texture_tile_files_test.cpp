// Noise and texture tiles written as PNG + JSON, read back.
#include "exporters/texture_tile_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "core/atomic_file.h"
#include "exporters/image_io.h"
#include "scene/tileset_file.h"

namespace wangscape {
namespace {

std::filesystem::path scratch(const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("wangscape_texture_tile_files_" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  return dir;
}

Json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return Json::parse(in);
}

TEST(TextureTileFiles, NoiseTilesRoundTripAs16BitPngs) {
  const TileSet set = builtin_tileset("corner-2");
  const NoiseTileSet tiles(set, {.lattice = 16, .seed = 7});
  const auto dir = scratch("noise");
  write_noise_tile_files(dir, tiles, 48, NoisePattern::turbulence);
  const Json doc = read_json(dir / "noise_tiles.json");
  EXPECT_EQ(doc["kind"], "noise");
  EXPECT_EQ(doc["lattice"], 16);
  EXPECT_EQ(doc["octaves"], 3);
  EXPECT_EQ(doc["pattern"], "turbulence");
  EXPECT_EQ(tileset_from_json(doc["set"], "noise_tiles.json").tiles, set.tiles);
  ASSERT_EQ(doc["tiles"].size(), set.size());
  for (std::uint32_t t = 0; t < set.size(); ++t) {
    const std::string file = doc["tiles"][t]["file"];
    const ImageGray16 back = read_image_gray16(dir / file);
    EXPECT_EQ(back.pixels, rasterize_noise_tile(tiles, t, 48, NoisePattern::turbulence).pixels) << file;
    Json colors = doc["tiles"][t];
    colors.erase("file");
    EXPECT_EQ(tile_colors_from_json(colors, "noise_tiles.json", t, false, true), set.tiles[t]);
  }
}

TEST(TextureTileFiles, TextureTilesFromTheShippedExemplarsRoundTripAsPngs) {
  const std::filesystem::path exemplars = std::filesystem::path(WANGSCAPE_SOURCE_DIR) / "templates" / "exemplars";
  const std::vector<ImageRgb8> images = {read_image(exemplars / "meadow.png"), read_image(exemplars / "pumice.png")};
  ASSERT_EQ(images[0].width, 512);
  const TileSet set = builtin_tileset("corner-2");
  TextureTileOptions options;
  options.tile_size = 64;
  options.rounds = 1;
  options.candidates = 4;
  const TextureTileSet tiles = make_texture_tiles(set, images, options);
  const auto dir = scratch("texture");
  write_texture_tile_files(dir, tiles);
  const Json doc = read_json(dir / "texture_tiles.json");
  EXPECT_EQ(doc["kind"], "texture");
  EXPECT_EQ(doc["tile_size"], 64);
  EXPECT_EQ(doc["total_error"], tiles.total_error());
  ASSERT_EQ(doc["windows"].size(), tiles.windows.size());
  EXPECT_EQ(doc["windows"][1]["x"], tiles.windows[1].x);
  for (std::size_t t = 0; t < set.size(); ++t) {
    const std::string file = doc["tiles"][t]["file"];
    EXPECT_EQ(read_image(dir / file).pixels, tiles.tiles[t].image.pixels) << file;
    EXPECT_EQ(doc["tiles"][t]["error"], tiles.tiles[t].error);
  }
}

TEST(TextureTileFiles, AnUnwritableFolderIsNamed) {
  const auto file = scratch("blocker");
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << "not a folder";
  const NoiseTileSet tiles(builtin_tileset("cohen8"), {});
  try {
    write_noise_tile_files(file / "sub", tiles, 8);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("blocker"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace wangscape
