#include "folder/folder_state.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/atomic_file.h"
#include "core/binary_file.h"
#include "core/error.h"
#include "core/json_text.h"
#include "core/text_file.h"
#include "generator/placement.h"
#include "scene/filled_tileset_file.h"
#include "scene/ground_look.h"

namespace wangscape {

namespace fs = std::filesystem;

namespace {

constexpr BinaryMagic kMagic = {'W', 'S', 'C', 'A', 'C', 'H', 'E', '\n'};

// FNV-1a, 64 bits: a fingerprint of the scene file, not a defence against tampering.
std::uint64_t fingerprint(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

// ---- the models section (version 3) ----------------------------------------------------------

constexpr std::uint32_t kNoImage = 0xffffffffu;

std::uint32_t count_of(std::size_t count, const fs::path& file, const std::string& what) {
  if (count > std::numeric_limits<std::uint32_t>::max())
    throw Error(file, "", std::to_string(count) + " " + what + ": at most 2^32 - 1 fit the file");
  return std::uint32_t(count);
}

// The images the models' materials map, each once (materials sharing one image share it when
// read: the exporters tell materials apart by it), in the order they are first met.
std::vector<const TextureImage*> images_of(const std::vector<Mesh>& models) {
  std::vector<const TextureImage*> images;
  for (const Mesh& model : models)
    for (const Material& material : model.materials)
      if (const TextureImage* image = material.base_color_map.get();
          image && std::find(images.begin(), images.end(), image) == images.end())
        images.push_back(image);
  return images;
}

void put_mesh(std::ostream& out, const Mesh& mesh, const std::vector<const TextureImage*>& images,
              const fs::path& file) {
  put_text(out, mesh.name);
  put_u32(out, count_of(mesh.positions.size(), file, "vertices"));
  put_array<std::array<float, 3>>(out, mesh.positions);
  put_u32(out, count_of(mesh.normals.size(), file, "normals"));
  put_array<std::array<float, 3>>(out, mesh.normals);
  put_u32(out, count_of(mesh.uvs.size(), file, "texture coordinates"));
  put_array<std::array<float, 2>>(out, mesh.uvs);
  put_u32(out, count_of(mesh.triangles.size(), file, "triangles"));
  put_array<std::array<std::uint32_t, 3>>(out, mesh.triangles);
  put_u32(out, count_of(mesh.triangle_material.size(), file, "triangle materials"));
  put_array<std::uint16_t>(out, mesh.triangle_material);
  put_u32(out, count_of(mesh.materials.size(), file, "materials"));
  for (const Material& m : mesh.materials) {
    put_text(out, m.name);
    for (const float c : m.base_color) put_f32(out, c);
    put_f32(out, m.roughness);
    put_f32(out, m.translucency);
    const auto image = std::find(images.begin(), images.end(), m.base_color_map.get());
    put_u32(out, m.base_color_map ? std::uint32_t(image - images.begin()) : kNoImage);
    put_f32(out, m.alpha_cutoff);
  }
}

void put_models(std::ostream& out, const Scene& scene, const fs::path& file) {
  put_u32(out, count_of(scene.models.size(), file, "models"));
  put_u32(out, std::uint32_t(full_model_count(scene)));
  const std::vector<const TextureImage*> images = images_of(scene.models);
  put_u32(out, std::uint32_t(images.size()));
  for (const TextureImage* image : images) {
    put_text(out, image->name);
    put_i32(out, image->width);
    put_i32(out, image->height);
    put_u64(out, image->rgba.size());
    put_array<std::uint8_t>(out, image->rgba);
  }
  for (const Mesh& model : scene.models) put_mesh(out, model, images, file);
  put_u32(out, count_of(scene.stand_ins.size(), file, "stand-ins"));
  for (const StandInFigures& s : scene.stand_ins) {
    put_text(out, s.name);
    put_u64(out, s.triangles);
    put_u64(out, s.model_triangles);
    put_f64(out, s.error);
  }
}

std::shared_ptr<const TextureImage> read_image(BinaryReader& in, std::uint32_t index) {
  const std::string what = "image " + std::to_string(index) + "'s ";
  auto image = std::make_shared<TextureImage>();
  image->name = in.text(what + "name");
  image->width = in.i32(what + "size");
  image->height = in.i32(what + "size");
  const std::uint64_t bytes = in.u64(what + "size");
  if (image->width < 0 || image->height < 0 || bytes != std::uint64_t(image->width) * std::uint64_t(image->height) * 4)
    in.fail(what + "texels: " + std::to_string(bytes) + " bytes for " + std::to_string(image->width) + " x " +
            std::to_string(image->height) + " texels (expected 4 a texel)");
  image->rgba = in.array<std::uint8_t>(bytes, what + "texels");
  return image;
}

// One of the mesh's vectors: its count, then its elements.
template <class T>
std::vector<T> read_mesh_array(BinaryReader& in, const std::string& what) {
  return in.array<T>(in.u32(what + "' count"), what);
}

Mesh read_mesh(BinaryReader& in, std::size_t index, const std::vector<std::shared_ptr<const TextureImage>>& images) {
  const std::string model = "model " + std::to_string(index);
  Mesh mesh;
  mesh.name = in.text(model + "'s name");
  mesh.positions = read_mesh_array<std::array<float, 3>>(in, model + "'s vertices");
  mesh.normals = read_mesh_array<std::array<float, 3>>(in, model + "'s normals");
  mesh.uvs = read_mesh_array<std::array<float, 2>>(in, model + "'s texture coordinates");
  mesh.triangles = read_mesh_array<std::array<std::uint32_t, 3>>(in, model + "'s triangles");
  mesh.triangle_material = read_mesh_array<std::uint16_t>(in, model + "'s triangle materials");
  const std::uint32_t materials = in.u32(model + "'s material count");
  for (std::uint32_t m = 0; m < materials; ++m) {
    const std::string what = model + "'s material " + std::to_string(m);
    Material material;
    material.name = in.text(what);
    for (float& c : material.base_color) c = in.f32(what);
    material.roughness = in.f32(what);
    material.translucency = in.f32(what);
    if (const std::uint32_t image = in.u32(what); image != kNoImage) {
      if (image >= images.size())
        in.fail(what + " maps image " + std::to_string(image) + ": expected one of the " +
                std::to_string(images.size()) + " images");
      material.base_color_map = images[image];
    }
    material.alpha_cutoff = in.f32(what);
    mesh.materials.push_back(std::move(material));
  }
  // What the renderers index without checking: one normal (and texture coordinate) a vertex,
  // vertices and materials that exist.
  const std::size_t vertices = mesh.positions.size(), triangles = mesh.triangles.size();
  const auto expected = [&](std::size_t found, const std::string& what, std::size_t of, const std::string& per) {
    in.fail(model + ": " + std::to_string(found) + " " + what + " for " + std::to_string(of) + " " + per +
            " (expected one per " + per.substr(0, per.size() - 1) + ")");
  };
  if (mesh.normals.size() != vertices) expected(mesh.normals.size(), "normals", vertices, "vertices");
  if (!mesh.uvs.empty() && mesh.uvs.size() != vertices)
    expected(mesh.uvs.size(), "texture coordinates", vertices, "vertices");
  if (!mesh.triangle_material.empty() && mesh.triangle_material.size() != triangles)
    expected(mesh.triangle_material.size(), "triangle materials", triangles, "triangles");
  for (std::size_t t = 0; t < triangles; ++t)
    for (const std::uint32_t v : mesh.triangles[t])
      if (v >= vertices)
        in.fail(model + ": triangle " + std::to_string(t) + " has vertex " + std::to_string(v) +
                ": expected one of the " + std::to_string(vertices) + " vertices");
  for (std::size_t t = 0; t < mesh.triangle_material.size(); ++t)
    if (mesh.triangle_material[t] >= mesh.materials.size())
      in.fail(model + ": triangle " + std::to_string(t) + " has material " + std::to_string(mesh.triangle_material[t]) +
              ": expected one of the " + std::to_string(mesh.materials.size()) + " materials");
  return mesh;
}

SceneModels read_models(BinaryReader& in) {
  SceneModels kept;
  const std::uint32_t models = in.u32("the models' count");
  kept.full_models = in.u32("the full models' count");
  if (kept.full_models > models)
    in.fail(std::to_string(kept.full_models) + " full models: expected at most the " + std::to_string(models) +
            " models");
  const std::uint32_t image_count = in.u32("the images' count");
  std::vector<std::shared_ptr<const TextureImage>> images;
  for (std::uint32_t k = 0; k < image_count; ++k) images.push_back(read_image(in, k));
  for (std::uint32_t k = 0; k < models; ++k) kept.models.push_back(read_mesh(in, k, images));
  const std::uint32_t stand_ins = in.u32("the stand-ins' count");
  for (std::uint32_t k = 0; k < stand_ins; ++k) {
    const std::string what = "stand-in " + std::to_string(k) + "'s figures";
    StandInFigures figures;
    figures.name = in.text(what);
    figures.triangles = in.u64(what);
    figures.model_triangles = in.u64(what);
    figures.error = in.f64(what);
    kept.stand_ins.push_back(std::move(figures));
  }
  return kept;
}

// The whole file through core/text_file.h (a regular file, at most `max_bytes`), or `missing`
// when there is none.
std::string read_file(const fs::path& file, std::uintmax_t max_bytes, std::string_view what,
                      const std::string& missing) {
  std::error_code ec;
  if (!fs::exists(file, ec)) throw Error(file, "", missing);
  return read_text_file(file, max_bytes, what);
}

const char* const kBuildAgain = "build the folder again (wangscape build SCENE.toml --out DIR)";

}  // namespace

PlacedTileCollector::PlacedTileCollector(const SceneField& field) : tile_size_(field.placement.tile_size) {
  const TileRange range = tile_range(*field.placement.area, tile_size_);
  grid_.i0 = range.i0;
  grid_.j0 = range.j0;
  grid_.width = std::max(0, range.width());
  grid_.height = std::max(0, range.height());
  kept_.assign(std::size_t(grid_.width) * std::size_t(grid_.height), 0);
}

void PlacedTileCollector::add(const InstanceBatch& batch) {
  for (std::size_t k = 0; k < batch.size(); ++k) {
    const std::int64_t i = std::int64_t(std::floor(double(batch.x[k]) / tile_size_)) - grid_.i0;
    const std::int64_t j = std::int64_t(std::floor(double(batch.y[k]) / tile_size_)) - grid_.j0;
    if (i >= 0 && j >= 0 && i < grid_.width && j < grid_.height) kept_[std::size_t(j * grid_.width + i)] = 1;
  }
}

PlacedTiles PlacedTileCollector::result() const {
  PlacedTiles placed = grid_;
  for (std::size_t c = 0; c < kept_.size(); ++c)
    if (kept_[c]) placed.cells.push_back(std::uint32_t(c));
  return placed;
}

PlacedTiles place_tiles(const SceneField& field) {
  PlacedTileCollector collector(field);
  field.place([&](const InstanceBatch& batch) { collector.add(batch); });
  return collector.result();
}

std::vector<std::uint16_t> placed_set_tiles(const SceneField& field, const PlacedTiles& placed) {
  const RowTiles rows(field.filled.set, tile_range(*field.placement.area, field.placement.tile_size), field.placement);
  std::vector<std::uint16_t> row(std::size_t(placed.width)), tiles;
  tiles.reserve(placed.cells.size());
  std::int64_t row_at = -1;  // the row in `row`
  for (const std::uint32_t cell : placed.cells) {
    const std::int64_t r = cell / std::uint32_t(placed.width);
    if (r != row_at) rows.row(int(r), row);
    row_at = r;
    tiles.push_back(row[cell % std::uint32_t(placed.width)]);
  }
  return tiles;
}

void write_folder_state(const FolderFiles& files, const std::string& scene_text, const Scene& scene,
                        const PlacedTiles& placed) {
  if (!scene.field) return;
  const Json tiles = filled_tileset_to_json(scene.field->filled);
  const std::string tiles_text = format_filled_tileset_json(tiles);
  write_file_atomically(files.tiles(), tiles_text);

  AtomicFile file(files.state());
  std::ostream& out = file.stream();
  put_binary_header(out, kMagic, FolderFiles::kFormatVersion);
  put_u64(out, fingerprint(scene_text));
  put_u64(out, fingerprint(tiles_text));
  put_i64(out, placed.i0);
  put_i64(out, placed.j0);
  put_i32(out, placed.width);
  put_i32(out, placed.height);
  put_u64(out, placed.cells.size());
  put_array<std::uint32_t>(out, placed.cells);
  const std::vector<std::uint16_t> set_tiles =
      placed.set_tiles.empty() ? placed_set_tiles(*scene.field, placed) : placed.set_tiles;
  if (set_tiles.size() != placed.cells.size())
    throw Error(files.state(), "", "the set's tiles are not one per placed tile (a bug: please report it)");
  put_array<std::uint16_t>(out, set_tiles);
  const GroundBake* bake = scene.ground_texture.get();
  put_u8(out, bake ? 1 : 0);
  if (bake) {
    for (const double v : {bake->extent.min_x, bake->extent.min_y, bake->extent.max_x, bake->extent.max_y})
      put_f64(out, v);
    put_i32(out, bake->image.width);
    put_i32(out, bake->image.height);
    put_array<std::uint8_t>(out, bake->image.pixels);
  }
  put_models(out, scene, files.state());
  file.commit();
}

FolderState read_folder_state(const FolderFiles& files, const std::string& scene_text) {
  const fs::path file = files.state(), tiles_file = files.tiles();
  const std::string missing = std::string("missing: the folder was written by an older wangscape; ") + kBuildAgain;
  std::error_code ec;
  if (!fs::exists(file, ec)) throw Error(file, "", missing);
  BinaryReader in(file, kMagic, "scene cache");
  const std::uint32_t version = in.version();
  if (version < FolderFiles::kOldestFormatVersion || version > FolderFiles::kFormatVersion)
    in.fail("version " + std::to_string(version) + ", this wangscape reads versions " +
            std::to_string(FolderFiles::kOldestFormatVersion) + " to " + std::to_string(FolderFiles::kFormatVersion) +
            "; " + kBuildAgain);
  if (in.u64("the scene file's fingerprint") != fingerprint(scene_text))
    throw Error(files.scene_file(), "", std::string("was changed after the build; ") + kBuildAgain);
  const std::uint64_t tiles_fingerprint = in.u64("the tile set's fingerprint");

  FolderState state;
  PlacedTiles& placed = state.placed;
  placed.i0 = in.i64("the grid's origin");
  placed.j0 = in.i64("the grid's origin");
  placed.width = in.i32("the grid's width");
  placed.height = in.i32("the grid's height");
  if (placed.width < 0 || placed.height < 0) in.fail("a tile grid of negative size");
  const auto count = in.u64("the placed tiles' count");
  const std::uint64_t cells = std::uint64_t(placed.width) * std::uint64_t(placed.height);
  if (count > cells) in.fail(std::to_string(count) + " placed tiles in a grid of " + std::to_string(cells) + " cells");
  placed.cells = in.array<std::uint32_t>(count, "the placed tiles");
  for (std::size_t k = 0; k < placed.cells.size(); ++k)
    if (placed.cells[k] >= cells || (k > 0 && placed.cells[k] <= placed.cells[k - 1]))
      in.fail("placed tile " + std::to_string(k) + " is out of the grid or out of order");
  if (version >= 2)  // version 1 kept no set's tiles: the view runs the tiling again
    placed.set_tiles = in.array<std::uint16_t>(count, "the set's tile of each placed tile");

  if (in.u8("the ground flag") != 0) {
    auto bake = std::make_shared<GroundBake>();
    bake->extent.min_x = in.f64("the ground's extent");
    bake->extent.min_y = in.f64("the ground's extent");
    bake->extent.max_x = in.f64("the ground's extent");
    bake->extent.max_y = in.f64("the ground's extent");
    const auto width = in.i32("the ground's width");
    const auto height = in.i32("the ground's height");
    // (Up to version 2 the pixels end the file.)
    const std::uint64_t bytes = width < 1 || height < 1 ? 0 : std::uint64_t(width) * std::uint64_t(height) * 3;
    if (bytes == 0 || bytes > in.left() || (version < 3 && bytes != in.left()))
      in.fail("a ground image of " + std::to_string(width) + " x " + std::to_string(height) + " pixels where " +
              std::to_string(in.left()) + " bytes are left");
    bake->image.width = width;
    bake->image.height = height;
    bake->image.pixels = in.array<std::uint8_t>(bytes, "the ground's pixels");
    state.prebuilt.ground_texture = std::move(bake);
  }
  if (version >= 3) state.prebuilt.models = read_models(in);  // before, the readers make them again
  in.expect_end("its last section");

  const std::string tiles_text = read_file(tiles_file, kMaxFolderTilesBytes, "tile set", missing);
  if (fingerprint(tiles_text) != tiles_fingerprint)
    throw Error(tiles_file, "", "does not match the folder's " + file.filename().string() + "; " + kBuildAgain);
  Json document;
  try {
    document = Json::parse(tiles_text);
  } catch (const Json::exception& e) {
    throw Error(tiles_file, "", "not JSON: " + json_error_text(e));
  }
  state.prebuilt.filled = filled_tileset_from_json(document, tiles_file.string());
  const std::size_t set_size = state.prebuilt.filled.tiles.size();
  for (std::size_t k = 0; k < placed.set_tiles.size(); ++k)
    if (placed.set_tiles[k] >= set_size)
      throw Error(file, "",
                  "placed tile " + std::to_string(k) + " is the set's tile " + std::to_string(placed.set_tiles[k]) +
                      ": expected one of the " + std::to_string(set_size) + " tiles of " +
                      tiles_file.filename().string() + "; " + kBuildAgain);
  return state;
}

}  // namespace wangscape
