// The state a scene folder's build keeps for its readers (folder/folder_state.h): written and
// read back, it gives the same tile set, the same ground bake and the same placed tiles (with the
// set's tile at each) as making the scene again, over several seeds; it is refused when it does not belong to the scene
// file.
#include "folder/folder_state.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "scene/ground_look.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;

std::string field_text(int seed) {
  return "name = \"state\"\n[terrain]\nflat_size = 80.0\n[tiles]\nset = \"cohen8\"\ntile_size = 4.0\n"
         "points_per_tile = 12\nseed = " +
         std::to_string(seed) +
         "\nrelaxation_rounds = 4\narea = [-20.0, -20.0, 20.0, 16.0]\n[models]\nvariants = 2\n"
         "triangle_budget = 400\n[masks]\nmax_slope = 40.0\n[ground]\nbake_pixels = 64\n";
}

class FolderStateTest : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() /
                 ("wangscape-folder-state-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }
};

TEST_F(FolderStateTest, ReadBackItIsTheSceneMadeAgain) {
  for (int seed : {1, 2, 3, 4, 5}) {
    const std::string text = field_text(seed);
    const SceneConfig config = parse_scene_config(text, FolderFiles(dir).scene_file(), dir);
    const Scene made = make_scene(config);
    const PlacedTiles placed = place_tiles(*made.field);
    ASSERT_FALSE(placed.cells.empty());
    write_folder_state(FolderFiles(dir), text, made, placed);

    FolderState state = read_folder_state(FolderFiles(dir), text);
    const PlacedTiles& read_placed = state.placed;
    const Scene opened = make_scene(config, {}, &state.prebuilt);
    EXPECT_EQ(read_placed.cells, placed.cells) << "seed " << seed;
    EXPECT_EQ(read_placed.i0, placed.i0);
    EXPECT_EQ(read_placed.j0, placed.j0);
    EXPECT_EQ(read_placed.width, placed.width);
    EXPECT_EQ(read_placed.height, placed.height);
    // The set's tile at each placed cell, as running the tiling gives it (what the view did).
    EXPECT_EQ(read_placed.set_tiles, placed_set_tiles(*made.field, placed)) << "seed " << seed;
    EXPECT_EQ(read_placed.set_tiles.size(), placed.cells.size());
    EXPECT_EQ(opened.field->filled.tiles, made.field->filled.tiles) << "seed " << seed;
    EXPECT_EQ(opened.field->filled.radius_packing, made.field->filled.radius_packing);
    ASSERT_TRUE(opened.ground_texture && made.ground_texture);
    EXPECT_EQ(opened.ground_texture->image.pixels, made.ground_texture->image.pixels);
    EXPECT_EQ(opened.ground_texture->extent.min_x, made.ground_texture->extent.min_x);
    EXPECT_EQ(opened.ground_texture->extent.max_y, made.ground_texture->extent.max_y);
    EXPECT_EQ(place_tiles(*opened.field).cells, placed.cells) << "the opened scene places the same tiles";
  }
}

TEST_F(FolderStateTest, AnotherSceneFileIsRefused) {
  const std::string text = field_text(1);
  const SceneConfig config = parse_scene_config(text, FolderFiles(dir).scene_file(), dir);
  const Scene made = make_scene(config);
  write_folder_state(FolderFiles(dir), text, made, place_tiles(*made.field));
  try {
    read_folder_state(FolderFiles(dir), field_text(2));
    FAIL() << "a state of another scene file was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("was changed after the build"), std::string::npos) << e.what();
  }
}

TEST_F(FolderStateTest, EveryTruncationIsRefused) {
  const std::string text = field_text(3);
  const SceneConfig config = parse_scene_config(text, FolderFiles(dir).scene_file(), dir);
  const Scene made = make_scene(config);
  write_folder_state(FolderFiles(dir), text, made, place_tiles(*made.field));
  std::ifstream in(FolderFiles(dir).state(), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  for (std::size_t size = 0; size < bytes.size(); size += 1 + size / 3) {
    std::ofstream(FolderFiles(dir).state(), std::ios::binary | std::ios::trunc) << bytes.substr(0, size);
    EXPECT_THROW(read_folder_state(FolderFiles(dir), text), Error) << "cut to " << size << " bytes";
  }
}

}  // namespace
}  // namespace wangscape
