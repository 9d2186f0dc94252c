// The state a scene folder's build keeps for its readers (folder/folder_state.h): written and
// read back, it gives the same tile set, the same ground bake, the same placed tiles (with the
// set's tile at each) and the same models, bit for bit (their proxies, a user's models with their
// images and stand-ins, species), as making the scene again, over several seeds; it is refused
// when it does not belong to the scene file or is damaged, naming the file; a cache of version 2
// (without the models) still opens, its models made again.
#include "folder/folder_state.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <span>
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

// Two vectors of plain values, bit for bit (a NaN equal to itself, -0 not to 0).
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// Every field of every model, bit for bit, and the images shared as the made ones share them.
void expect_same_models(const std::vector<Mesh>& read, const std::vector<Mesh>& made) {
  ASSERT_EQ(read.size(), made.size());
  std::map<const TextureImage*, const TextureImage*> image_of;  // made -> read
  for (std::size_t v = 0; v < made.size(); ++v) {
    const Mesh &a = read[v], &b = made[v];
    EXPECT_EQ(a.name, b.name) << v;
    EXPECT_TRUE(same_bits(a.positions, b.positions)) << v;
    EXPECT_TRUE(same_bits(a.normals, b.normals)) << v;
    EXPECT_TRUE(same_bits(a.uvs, b.uvs)) << v;
    EXPECT_TRUE(same_bits(a.triangles, b.triangles)) << v;
    EXPECT_TRUE(same_bits(a.triangle_material, b.triangle_material)) << v;
    ASSERT_EQ(a.materials.size(), b.materials.size()) << v;
    for (std::size_t m = 0; m < b.materials.size(); ++m) {
      const Material &x = a.materials[m], &y = b.materials[m];
      EXPECT_EQ(x.name, y.name);
      EXPECT_TRUE(same_bits(x.base_color, y.base_color));
      EXPECT_TRUE(same_bits(x.roughness, y.roughness));
      EXPECT_TRUE(same_bits(x.translucency, y.translucency));
      EXPECT_TRUE(same_bits(x.alpha_cutoff, y.alpha_cutoff));
      ASSERT_EQ(bool(x.base_color_map), bool(y.base_color_map)) << v << " " << m;
      if (!y.base_color_map) continue;
      const auto [at, first] = image_of.emplace(y.base_color_map.get(), x.base_color_map.get());
      EXPECT_EQ(at->second, x.base_color_map.get()) << "an image shared by the made models is shared when read";
      EXPECT_EQ(x.base_color_map->name, y.base_color_map->name);
      EXPECT_EQ(x.base_color_map->width, y.base_color_map->width);
      EXPECT_EQ(x.base_color_map->height, y.base_color_map->height);
      EXPECT_EQ(x.base_color_map->rgba, y.base_color_map->rgba);
    }
  }
  std::map<const TextureImage*, int> read_images;
  for (const auto& [made_image, read_image] : image_of) ++read_images[read_image];
  for (const auto& [image, count] : read_images) EXPECT_EQ(count, 1) << "two made images read as one";
}

void expect_same_stand_ins(const std::vector<StandInFigures>& read, const std::vector<StandInFigures>& made) {
  ASSERT_EQ(read.size(), made.size());
  for (std::size_t k = 0; k < made.size(); ++k) {
    EXPECT_EQ(read[k].name, made[k].name);
    EXPECT_EQ(read[k].triangles, made[k].triangles);
    EXPECT_EQ(read[k].model_triangles, made[k].model_triangles);
    EXPECT_TRUE(same_bits(read[k].error, made[k].error));
  }
}

// Camera-aware, three species: a plant kind (its proxies made again at a lower budget), the
// tulips' folder (a user's models and their stand-ins) and a leaf card (a material with an image
// and a cutout).
std::string species_text(int seed) {
  const std::string models = std::string(WANGSCAPE_SOURCE_DIR) + "/tests/data/models/";
  return "name = \"kept\"\n[terrain]\nflat_size = 80.0\n[tiles]\nset = \"cohen8\"\ntile_size = 4.0\n"
         "points_per_tile = 12\nseed = " +
         std::to_string(seed) +
         "\narea = [-20.0, -20.0, 20.0, 16.0]\n[camera_aware]\nenabled = true\nnear = 6.0\nfar = 30.0\n"
         "[[species]]\nname = \"grass\"\nvariants = 2\ntriangle_budget = 100\nshare = 3\n"
         "[[species]]\nname = \"tulip\"\nmodel = \"" +
         models + "tulips\"\n[[species]]\nname = \"card\"\nmodel = \"" + models + "leaf_card.gltf\"\n";
}

// scene.cache's layout (docs/scene-folder.md): where its models section starts.
std::size_t models_at(const std::string& cache) {
  std::uint64_t count = 0;
  std::memcpy(&count, cache.data() + 52, sizeof count);
  std::size_t at = 60 + 6 * count;  // the placed cells, the set's tiles
  if (cache[at++] == 0) return at;
  std::int32_t width = 0, height = 0;
  std::memcpy(&width, cache.data() + at + 32, 4);
  std::memcpy(&height, cache.data() + at + 36, 4);
  return at + 40 + std::size_t(width) * std::size_t(height) * 3;
}

// A version 3 cache as a version 2 build wrote it: without the models.
std::string as_version_2(const std::string& cache) {
  std::string older = cache.substr(0, models_at(cache));
  const std::uint32_t version = 2;
  std::memcpy(older.data() + 8, &version, sizeof version);
  return older;
}

std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
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
    ASSERT_TRUE(state.prebuilt.models);
    expect_same_models(opened.models, made.models);
  }
}

// The models, their proxies and stand-ins, a user's models' images: read back, the Scene made
// with them is the one made from the files.
TEST_F(FolderStateTest, TheModelsReadBackAreTheOnesMade) {
  for (int seed : {1, 2}) {
    const std::string text = species_text(seed);
    const SceneConfig config = parse_scene_config(text, FolderFiles(dir).scene_file(), dir);
    const Scene made = make_scene(config);
    ASSERT_GT(made.field->proxy_offset, 0u);
    ASSERT_GT(made.models.size(), made.field->proxy_offset);
    ASSERT_FALSE(made.stand_ins.empty());
    write_folder_state(FolderFiles(dir), text, made, place_tiles(*made.field));

    const FolderState state = read_folder_state(FolderFiles(dir), text);
    ASSERT_TRUE(state.prebuilt.models);
    EXPECT_EQ(state.prebuilt.models->full_models, made.field->proxy_offset);
    expect_same_models(state.prebuilt.models->models, made.models);
    const Scene opened = make_scene(config, {}, &state.prebuilt);
    expect_same_models(opened.models, made.models);
    expect_same_stand_ins(opened.stand_ins, made.stand_ins);
    EXPECT_EQ(opened.field->proxy_offset, made.field->proxy_offset);
    ASSERT_TRUE(opened.field->species && made.field->species);
    EXPECT_EQ(opened.field->species->names(), made.field->species->names());
    // The same flowers, of the same models and proxies.
    std::vector<std::uint16_t> made_variants, opened_variants;
    made.field->place(
        [&](const InstanceBatch& b) { made_variants.insert(made_variants.end(), b.variant.begin(), b.variant.end()); });
    opened.field->place([&](const InstanceBatch& b) {
      opened_variants.insert(opened_variants.end(), b.variant.begin(), b.variant.end());
    });
    EXPECT_EQ(opened_variants, made_variants);
    bool proxies = false;
    for (const auto v : made_variants) proxies |= v >= made.field->proxy_offset;
    EXPECT_TRUE(proxies) << "seed " << seed;
  }
}

// A folder of scene.cache version 2 opens, its models made again as before version 3.
TEST_F(FolderStateTest, AVersion2CacheOpensAndMakesTheModels) {
  const std::string text = species_text(3);
  const SceneConfig config = parse_scene_config(text, FolderFiles(dir).scene_file(), dir);
  const Scene made = make_scene(config);
  write_folder_state(FolderFiles(dir), text, made, place_tiles(*made.field));
  write_bytes(FolderFiles(dir).state(), as_version_2(bytes_of(FolderFiles(dir).state())));
  const FolderState state = read_folder_state(FolderFiles(dir), text);
  EXPECT_FALSE(state.prebuilt.models);
  EXPECT_FALSE(state.placed.set_tiles.empty());
  const Scene opened = make_scene(config, {}, &state.prebuilt);
  expect_same_models(opened.models, made.models);
  expect_same_stand_ins(opened.stand_ins, made.stand_ins);
  EXPECT_EQ(opened.field->proxy_offset, made.field->proxy_offset);
}

// A damaged models section: every cut and a model's indices past its vertices, materials or the
// images are refused, naming the file and what was expected, without a crash.
TEST_F(FolderStateTest, ADamagedModelsSectionIsRefusedNamingTheFile) {
  const std::string text = species_text(4);
  const SceneConfig config = parse_scene_config(text, FolderFiles(dir).scene_file(), dir);
  const Scene made = make_scene(config);
  write_folder_state(FolderFiles(dir), text, made, place_tiles(*made.field));
  const std::string cache = bytes_of(FolderFiles(dir).state());
  const std::string file = FolderFiles(dir).state().string();
  const auto refusal = [&](const std::string& bytes) {
    write_bytes(FolderFiles(dir).state(), bytes);
    try {
      read_folder_state(FolderFiles(dir), text);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  const std::size_t at = models_at(cache);
  ASSERT_LT(at, cache.size());
  for (std::size_t size = at; size < cache.size(); size += 1 + (size - at) / 5) {
    const std::string what = refusal(cache.substr(0, size));
    EXPECT_EQ(what.rfind(file + ": truncated", 0), 0u) << "cut to " << size << " bytes: " << what;
  }
  EXPECT_EQ(refusal(cache + "x"), file + ": longer than its last section");
  // The models' count, then the full models' count: more full models than models.
  std::string damaged = cache;
  const std::uint32_t many = 1000;
  std::memcpy(damaged.data() + at + 4, &many, 4);
  EXPECT_NE(refusal(damaged).find("1000 full models: expected at most the "), std::string::npos) << refusal(damaged);
  // The first model (after the images) is a grass: its first triangle's first vertex out of range.
  std::uint32_t images = 0;
  std::memcpy(&images, cache.data() + at + 8, 4);
  ASSERT_EQ(images, 1u) << "the leaf card's image, shared by its model and its stand-in";
  std::size_t p = at + 12;
  const auto skip_text = [&] {
    std::uint32_t n = 0;
    std::memcpy(&n, cache.data() + p, 4);
    p += 4 + n;
  };
  skip_text();
  std::uint64_t texels = 0;
  std::memcpy(&texels, cache.data() + p + 8, 8);
  p += 16 + texels;
  skip_text();  // model 0's name
  const Mesh& grass = made.models[0];
  p += 4 + 12 * grass.positions.size() + 4 + 12 * grass.normals.size() + 4 + 8 * grass.uvs.size() + 4;
  damaged = cache;
  const std::uint32_t outside = std::uint32_t(grass.positions.size());
  std::memcpy(damaged.data() + p, &outside, 4);
  EXPECT_EQ(refusal(damaged), file + ": model 0: triangle 0 has vertex " + std::to_string(outside) +
                                  ": expected one of the " + std::to_string(outside) + " vertices");
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
