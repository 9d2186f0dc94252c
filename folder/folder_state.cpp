#include "folder/folder_state.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json_text.h"
#include "core/text_file.h"
#include "generator/placement.h"
#include "scene/filled_tileset_file.h"
#include "scene/ground_look.h"

namespace wangscape {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'W', 'S', 'C', 'A', 'C', 'H', 'E', '\n'};

// FNV-1a, 64 bits: a fingerprint of the scene file, not a defence against tampering.
std::uint64_t fingerprint(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

class Writer {
 public:
  template <class T>
  void put(const T& value) {
    const auto* bytes = reinterpret_cast<const char*>(&value);
    out_.append(bytes, sizeof value);
  }
  void put_bytes(const void* data, std::size_t size) { out_.append(static_cast<const char*>(data), size); }
  const std::string& text() const { return out_; }

 private:
  std::string out_;
};

// Reads the file's fields in order; every read is checked against the bytes left.
class Reader {
 public:
  Reader(std::string bytes, fs::path file) : bytes_(std::move(bytes)), file_(std::move(file)) {}
  template <class T>
  T get(const char* what) {
    T value;
    std::memcpy(&value, take(sizeof value, what), sizeof value);
    return value;
  }
  const char* take(std::size_t size, const char* what) {
    if (size > bytes_.size() - at_)
      throw Error(file_, "byte " + std::to_string(at_), std::string("truncated: ") + what + " goes past the end");
    const char* p = bytes_.data() + at_;
    at_ += size;
    return p;
  }
  std::size_t left() const { return bytes_.size() - at_; }
  [[noreturn]] void fail(const std::string& what) const { throw Error(file_, "byte " + std::to_string(at_), what); }

 private:
  std::string bytes_;
  fs::path file_;
  std::size_t at_ = 0;
};

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

  Writer w;
  w.put_bytes(kMagic, sizeof kMagic);
  w.put(FolderFiles::kFormatVersion);
  w.put(fingerprint(scene_text));
  w.put(fingerprint(tiles_text));
  w.put(placed.i0);
  w.put(placed.j0);
  w.put(placed.width);
  w.put(placed.height);
  w.put(std::uint64_t(placed.cells.size()));
  w.put_bytes(placed.cells.data(), placed.cells.size() * sizeof(std::uint32_t));
  const std::vector<std::uint16_t> set_tiles =
      placed.set_tiles.empty() ? placed_set_tiles(*scene.field, placed) : placed.set_tiles;
  if (set_tiles.size() != placed.cells.size())
    throw Error(files.state(), "", "the set's tiles are not one per placed tile (a bug: please report it)");
  w.put_bytes(set_tiles.data(), set_tiles.size() * sizeof(std::uint16_t));
  const GroundBake* bake = scene.ground_texture.get();
  w.put(std::uint8_t(bake ? 1 : 0));
  if (bake) {
    for (const double v : {bake->extent.min_x, bake->extent.min_y, bake->extent.max_x, bake->extent.max_y}) w.put(v);
    w.put(std::int32_t(bake->image.width));
    w.put(std::int32_t(bake->image.height));
    w.put_bytes(bake->image.pixels.data(), bake->image.pixels.size());
  }
  write_file_atomically(files.state(), w.text());
}

FolderState read_folder_state(const FolderFiles& files, const std::string& scene_text) {
  const fs::path file = files.state(), tiles_file = files.tiles();
  const std::string missing = std::string("missing: the folder was written by an older wangscape; ") + kBuildAgain;
  Reader r(read_file(file, kMaxFolderStateBytes, "scene cache", missing), file);
  if (std::memcmp(r.take(sizeof kMagic, "the magic"), kMagic, sizeof kMagic) != 0)
    r.fail("bad magic: not a Wangscape scene cache");
  const auto version = r.get<std::uint32_t>("the version");
  if (version < FolderFiles::kOldestFormatVersion || version > FolderFiles::kFormatVersion)
    r.fail("version " + std::to_string(version) + ", this wangscape reads versions " +
           std::to_string(FolderFiles::kOldestFormatVersion) + " to " + std::to_string(FolderFiles::kFormatVersion) +
           "; " + kBuildAgain);
  if (r.get<std::uint64_t>("the scene file's fingerprint") != fingerprint(scene_text))
    throw Error(files.scene_file(), "", std::string("was changed after the build; ") + kBuildAgain);
  const std::uint64_t tiles_fingerprint = r.get<std::uint64_t>("the tile set's fingerprint");

  FolderState state;
  PlacedTiles& placed = state.placed;
  placed.i0 = r.get<std::int64_t>("the grid's origin");
  placed.j0 = r.get<std::int64_t>("the grid's origin");
  placed.width = r.get<std::int32_t>("the grid's width");
  placed.height = r.get<std::int32_t>("the grid's height");
  if (placed.width < 0 || placed.height < 0) r.fail("a tile grid of negative size");
  const auto count = r.get<std::uint64_t>("the placed tiles' count");
  const std::uint64_t cells = std::uint64_t(placed.width) * std::uint64_t(placed.height);
  if (count > cells) r.fail(std::to_string(count) + " placed tiles in a grid of " + std::to_string(cells) + " cells");
  if (count > r.left() / sizeof(std::uint32_t)) r.fail("truncated: the placed tiles go past the end");
  placed.cells.resize(count);
  std::memcpy(placed.cells.data(), r.take(count * sizeof(std::uint32_t), "the placed tiles"),
              count * sizeof(std::uint32_t));
  for (std::size_t k = 0; k < placed.cells.size(); ++k)
    if (placed.cells[k] >= cells || (k > 0 && placed.cells[k] <= placed.cells[k - 1]))
      r.fail("placed tile " + std::to_string(k) + " is out of the grid or out of order");
  if (version >= 2) {  // version 1 kept no set's tiles: the view runs the tiling again
    placed.set_tiles.resize(count);
    std::memcpy(placed.set_tiles.data(), r.take(count * sizeof(std::uint16_t), "the set's tile of each placed tile"),
                count * sizeof(std::uint16_t));
  }

  if (r.get<std::uint8_t>("the ground flag") != 0) {
    auto bake = std::make_shared<GroundBake>();
    bake->extent.min_x = r.get<double>("the ground's extent");
    bake->extent.min_y = r.get<double>("the ground's extent");
    bake->extent.max_x = r.get<double>("the ground's extent");
    bake->extent.max_y = r.get<double>("the ground's extent");
    const auto width = r.get<std::int32_t>("the ground's width");
    const auto height = r.get<std::int32_t>("the ground's height");
    if (width < 1 || height < 1 || std::uint64_t(width) * std::uint64_t(height) * 3 != r.left())
      r.fail("a ground image of " + std::to_string(width) + " x " + std::to_string(height) + " pixels where " +
             std::to_string(r.left()) + " bytes are left");
    bake->image.width = width;
    bake->image.height = height;
    const std::size_t bytes = r.left();
    const char* pixels = r.take(bytes, "the ground's pixels");
    bake->image.pixels.assign(pixels, pixels + bytes);
    state.prebuilt.ground_texture = std::move(bake);
  }
  if (r.left() != 0) r.fail(std::to_string(r.left()) + " bytes after the last section");

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
