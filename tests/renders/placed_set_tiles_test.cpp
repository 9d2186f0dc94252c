// The set's tile at each placed cell, kept in a scene folder's scene.cache (since version 2,
// folder/folder_state.h): a folder built as `wangscape build` builds it holds the tiles placement
// lays and the view would find by running the tiling, the view reads them (other tiles kept, other
// frames), a version 1 folder without them opens with the same tiles and frames, and a damaged
// record is refused naming the file.
#include <gtest/gtest.h>

#include <cstring>
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

// A tiny field built by build_scene with the LDI export (a grid of 7 x 6 tiles).
const fs::path& built_folder() {
  static const fs::path dir =
      view_test::built_ldi_folder("set_tiles_field", "[-12.0, -12.0, 12.0, 8.0]", "levels = 3\ndirections = 2\n");
  return dir;
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

// scene.cache's layout (docs/scene-folder.md): the version at byte 8, the placed count at 52, the
// placed cells from 60, then (version 2) the set's tile of each, the ground and (version 3) the
// models.
constexpr std::size_t kVersionAt = 8, kCountAt = 52, kCellsAt = 60;
std::size_t placed_count(const std::string& cache) {
  std::uint64_t count = 0;
  std::memcpy(&count, cache.data() + kCountAt, sizeof count);
  return std::size_t(count);
}
std::size_t set_tiles_at(const std::string& cache) { return kCellsAt + 4 * placed_count(cache); }

std::string with_version(std::string cache, std::uint32_t version) {
  std::memcpy(cache.data() + kVersionAt, &version, sizeof version);
  return cache;
}

// A copy of the built folder as `name`, its scene.cache given `cache` (the built one when empty).
fs::path copy_folder(const std::string& name, const std::string& cache = {}) {
  const fs::path copy = scratch(name);
  fs::remove_all(copy);
  fs::copy(built_folder(), copy, fs::copy_options::recursive);
  if (!cache.empty()) write_bytes(FolderFiles(copy).state(), cache);
  return copy;
}

// Where the models section starts: after the ground flag and the ground.
std::size_t models_at(const std::string& cache) {
  std::size_t at = set_tiles_at(cache) + 2 * placed_count(cache);
  if (cache[at++] == 0) return at;
  std::int32_t width = 0, height = 0;
  std::memcpy(&width, cache.data() + at + 32, 4);
  std::memcpy(&height, cache.data() + at + 36, 4);
  return at + 40 + std::size_t(width) * std::size_t(height) * 3;
}

// The built folder's scene.cache as a version 1 build wrote it: without the set's tiles and the
// models.
std::string as_version_1(const std::string& cache) {
  const std::size_t at = set_tiles_at(cache);
  return with_version(
      cache.substr(0, at) + cache.substr(at + 2 * placed_count(cache), models_at(cache) - at - 2 * placed_count(cache)),
      1);
}

std::vector<std::vector<std::uint8_t>> frames(const std::shared_ptr<const ViewWorld>& world) {
  std::vector<std::vector<std::uint8_t>> out;
  LdiRenderer renderer(world, 160, 90);
  for (const Camera& camera : {looking(0.3, -1, 9, 0.3, -0.5, 0, 60), looking(-14, -14, 2.5, 0, 0, 0.5, 60),
                               looking(0, -30, 12, 0, 0, 0, 50)}) {
    renderer.render(camera);
    out.push_back(renderer.image().pixels);
  }
  return out;
}

TEST(PlacedSetTiles, TheFolderKeepsTheTilesPlacementLays) {
  const SceneFolder folder = SceneFolder::open(built_folder(), SceneFolder::Parts::pack);
  const PlacedTiles& placed = folder.placed();
  ASSERT_FALSE(placed.cells.empty());
  ASSERT_EQ(placed.set_tiles.size(), placed.cells.size());
  const Scene scene = folder.make_scene();
  // What the view would find by running the tiling (a version 1 folder's path).
  EXPECT_EQ(placed.set_tiles, placed_set_tiles(*scene.field, placed));
  // What placement lays: every flower stands in its cell's kept tile.
  std::uint64_t flowers = 0, wrong = 0;
  const double size = scene.field->placement.tile_size;
  scene.field->place([&](const InstanceBatch& batch) {
    for (std::size_t k = 0; k < batch.size(); ++k, ++flowers) {
      const auto i = std::int64_t(std::floor(batch.x[k] / size)) - placed.i0;
      const auto j = std::int64_t(std::floor(batch.y[k] / size)) - placed.j0;
      const auto cell = std::uint32_t(j * placed.width + i);
      const auto at = std::lower_bound(placed.cells.begin(), placed.cells.end(), cell);
      wrong += at == placed.cells.end() || *at != cell ||
               placed.set_tiles[std::size_t(at - placed.cells.begin())] != batch.tile[k];
    }
  });
  EXPECT_GT(flowers, 200u);
  EXPECT_EQ(wrong, 0u);
  // And the view lays them.
  const auto world = ViewWorld::load(built_folder());
  EXPECT_EQ(world->tiles().tile, std::vector<std::uint32_t>(placed.set_tiles.begin(), placed.set_tiles.end()));
}

TEST(PlacedSetTiles, AVersion1FolderOpensWithTheSameTilesAndFrames) {
  const std::string cache = bytes_of(FolderFiles(built_folder()).state());
  const fs::path older = copy_folder("set_tiles_version_1", as_version_1(cache));
  EXPECT_TRUE(SceneFolder::open(older).placed().set_tiles.empty());
  const auto kept = ViewWorld::load(built_folder()), tiled = ViewWorld::load(older);
  EXPECT_EQ(kept->tiles().tile, tiled->tiles().tile);
  EXPECT_EQ(kept->tiles().cell, tiled->tiles().cell);
  const auto kept_frames = frames(kept);
  EXPECT_EQ(kept_frames, frames(tiled));
  // The view reads the record: a folder whose record lays other tiles draws other frames.
  std::string other = cache;
  const std::size_t tiles = kept->pack().info().tiles;
  for (std::size_t at = set_tiles_at(cache); at < cache.size() && at < set_tiles_at(cache) + 2 * placed_count(cache);
       at += 2)
    other[at] = char((std::uint8_t(other[at]) + 1) % tiles);
  const auto moved = ViewWorld::load(copy_folder("set_tiles_other", other));
  EXPECT_NE(moved->tiles().tile, kept->tiles().tile);
  EXPECT_NE(frames(moved), kept_frames);
}

// Damaged records: each refused with an Error naming the file and what was expected, by the
// folder and by the view opening it.
TEST(PlacedSetTiles, ADamagedRecordIsRefusedNamingIt) {
  const std::string cache = bytes_of(FolderFiles(built_folder()).state());
  const fs::path folder = copy_folder("set_tiles_damaged");
  const auto refused = [&](const std::string& damaged, const std::string& expected) {
    write_bytes(FolderFiles(folder).state(), damaged);
    for (int view = 0; view < 2; ++view) try {
        if (view)
          ViewWorld::load(folder);
        else
          SceneFolder::open(folder);
        ADD_FAILURE() << "accepted: " << expected;
      } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("set_tiles_damaged/scene.cache:"), std::string::npos) << what;
        EXPECT_NE(what.find(expected), std::string::npos) << what;
      }
  };
  std::string outside = cache;
  const std::size_t last = set_tiles_at(cache) + 2 * (placed_count(cache) - 1);
  outside[last] = char(8);
  refused(outside, "placed tile " + std::to_string(placed_count(cache) - 1) +
                       " is the set's tile 8: expected one of the 8 tiles of tiles.json");
  refused(cache.substr(0, last), "truncated: expected the set's tile of each placed tile");
  refused(with_version(cache, 4), "version 4, this wangscape reads versions 1 to 3");
  refused(with_version(cache, 1), "");  // a version 2 record said to be 1: read as one, it does not end
}

}  // namespace
}  // namespace wangscape
