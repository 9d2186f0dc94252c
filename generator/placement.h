// Placement: lays a tiling of a filled tile set over a Ground and streams the instances.
// Tile (i, j) covers [i s, (i+1) s) x [j s, (j+1) s) in ENU meters (s = tile size), so with a
// hashed tiling the same tile covers the same ground in every run and every window. Instances
// are produced in batches of whole tile rows (south to north), filled in parallel and handed
// to the sink serially, in order: the same bytes on any thread count, never one giant vector.
#pragma once

#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "generator/ground_concept.h"
#include "generator/instances.h"
#include "generator/poisson_tiles.h"
#include "generator/tiling.h"

namespace wangscape {

struct PlacementOptions {
  double tile_size = 4.0;  // meters
  TilingAlgorithm algorithm = TilingAlgorithm::scanline;
  std::uint64_t seed = 1;
  bool forbid_identical_neighbours = false;
  std::optional<Extent> area;  // what to cover; the ground's extent when unset
  // Only the tiles meeting `window` are laid; the tiling stays that of `area`, so a window holds
  // exactly the tiles (and flowers) the whole area has there. Unset: the whole area.
  std::optional<Extent> window;
  // Interior variation: when set, each instance's variant, yaw and scale come from
  // world_point_attributes (its world tile and index) instead of from the tile's point.
  struct WorldAttributes {
    std::uint64_t seed = 1;
    int variants = 1;
    double min_scale = 1, max_scale = 1;
  };
  std::optional<WorldAttributes> world_attributes;
  std::size_t batch_points = 1u << 16;  // rows are grouped until a batch holds about this many points
};

// One tile of the tiling, as the tile filter sees it.
struct TileCell {
  std::int64_t i = 0, j = 0;  // tile coordinates
  std::uint32_t tile = 0;     // index into the set's tiles
  Extent bounds;              // [i s, (i+1) s) x [j s, (j+1) s), meters
};

// Default filters: keep every tile, keep every point that has ground.
struct KeepAllTiles {
  bool operator()(const TileCell&) const { return true; }
};
struct KeepAllPoints {
  bool operator()(double, double, double) const { return true; }
};

struct PlacementStats {
  std::uint64_t tiles = 0;       // tiles of the tiling over the area (the window, when set)
  std::uint64_t tiles_kept = 0;  // tiles the tile filter kept
  std::uint64_t points = 0;      // instances handed to the sink
  std::uint64_t batches = 0;
};

// The filled set flattened for placement: per tile, a range of points in SoA arrays.
struct PlacementTable {
  std::vector<std::uint32_t> first;  // tile t's points are [first[t], first[t+1])
  std::vector<float> x, y, yaw, scale;
  std::vector<std::uint16_t> variant;
  std::vector<std::uint8_t> species;  // the point's class
  std::vector<float> rank;            // progressive order in [0, 1) (TilePoint::rank)
  // Per class: first variant and count (interior variation draws inside the point's class).
  std::vector<std::pair<int, int>> class_variants;
  std::size_t max_points_per_tile = 0;
  explicit PlacementTable(const FilledTileSet& filled);
};

// The tile range covering `area` with tiles of side `tile_size`: [i0, i1) x [j0, j1).
struct TileRange {
  std::int64_t i0 = 0, j0 = 0, i1 = 0, j1 = 0;
  int width() const { return static_cast<int>(i1 - i0); }
  int height() const { return static_cast<int>(j1 - j0); }
};
TileRange tile_range(const Extent& area, double tile_size);
// The tiles of `part` that lie in `whole` (empty when they do not meet).
TileRange clip_range(const TileRange& part, const TileRange& whole);

// Tiles of the area row by row (local row r = tile row j0 + r): computed up front for scanline
// and bottom-left tilings (2 bytes per tile), per row on demand for hashed ones, and up front for
// the part of `range` in `needed` for hashed ones without identical neighbours (their repair looks
// 16 tiles around each window: once for the window, not per row). Rows outside `needed` are then
// not available.
class RowTiles {
 public:
  RowTiles(const TileSet& set, const TileRange& range, const PlacementOptions& options);
  RowTiles(const TileSet& set, const TileRange& range, const PlacementOptions& options, const TileRange& needed);
  // Tiles of local row r from local column c into out (at most range.width() - c).
  void row(int r, std::span<std::uint16_t> out, int c = 0) const;

 private:
  TileRange range_;
  std::optional<Tiling> tiling_;
  std::optional<HashedTiling> hashed_;
};

// Sets every array of `batch` to n entries.
void resize_batch(InstanceBatch& batch, std::size_t n);

// Lays the tiling over `ground` and calls sink(const InstanceBatch&) once per batch.
//  tile_filter(const TileCell&) -> bool: a tile is instantiated only if it holds;
//  point_filter(x, y, z) -> bool (meters), or point_filter(x, y, z, species, rank) -> bool (the
//  point's class and progressive rank, for per-class rules and density): an instance is kept
//  only if it holds.
// Every instance gets z = ground.height(x, y); points where the ground has no height are dropped.
// The filters and the ground are called from several threads at once.
template <Ground G, class Sink, class TileFilter = KeepAllTiles, class PointFilter = KeepAllPoints>
PlacementStats place_instances(const FilledTileSet& filled, const G& ground, const PlacementOptions& options,
                               Sink&& sink, TileFilter tile_filter = {}, PointFilter point_filter = {}) {
  if (!(options.tile_size > 0))
    throw Error("placement: tile size " + std::to_string(options.tile_size) + " m; expected > 0");
  const Extent area = options.area ? *options.area : Extent(ground.extent());
  const TileRange whole = tile_range(area, options.tile_size);
  const TileRange range = options.window ? clip_range(tile_range(*options.window, options.tile_size), whole) : whole;
  PlacementStats stats;
  if (range.width() <= 0 || range.height() <= 0) return stats;
  const PlacementTable table(filled);
  const RowTiles rows(filled.set, whole, options, range);
  const double s = options.tile_size;
  const auto* world = options.world_attributes ? &*options.world_attributes : nullptr;

  // Rows per batch, from the mean points per tile.
  const double mean_points = static_cast<double>(table.x.size()) / std::max<std::size_t>(filled.tiles.size(), 1);
  const double row_points = std::max(1.0, mean_points * range.width());
  const int rows_per_batch =
      std::clamp(static_cast<int>(static_cast<double>(options.batch_points) / row_points), 1, range.height());
  const int batch_count = (range.height() + rows_per_batch - 1) / rows_per_batch;
  const std::size_t rows_per_batch_capacity =
      static_cast<std::size_t>(rows_per_batch) * static_cast<std::size_t>(range.width()) * table.max_points_per_tile;
  const int tokens = std::max(2, 2 * tbb::this_task_arena::max_concurrency());

  struct BatchSlot {
    InstanceBatch batch;
    std::vector<std::uint16_t> row_tiles;
    std::uint64_t kept = 0;
  };
  std::vector<BatchSlot> slots(static_cast<std::size_t>(tokens));
  int next_batch = 0;
  tbb::parallel_pipeline(
      static_cast<std::size_t>(tokens),
      tbb::make_filter<void, int>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& fc) -> int {
        if (next_batch >= batch_count) {
          fc.stop();
          return 0;
        }
        return next_batch++;
      }) & tbb::make_filter<int, int>(tbb::filter_mode::parallel, [&](int b) -> int {
        // At most `tokens` batches are alive and they leave in order, so batch b can
        // reuse the slot of batch b - tokens.
        BatchSlot& slot = slots[static_cast<std::size_t>(b % tokens)];
        InstanceBatch& out = slot.batch;
        slot.kept = 0;
        slot.row_tiles.resize(static_cast<std::size_t>(range.width()));
        const int r_begin = b * rows_per_batch, r_end = std::min(range.height(), (b + 1) * rows_per_batch);
        // Sized for the most points these rows can hold and written through pointers (no
        // per-point capacity checks), then cut to the real count.
        resize_batch(out, rows_per_batch_capacity);
        float *ox = out.x.data(), *oy = out.y.data(), *oz = out.z.data(), *oyaw = out.yaw.data(),
              *oscale = out.scale.data();
        std::uint16_t* ovariant = out.variant.data();
        std::uint32_t* otile = out.tile.data();
        float* orank = out.rank.data();
        std::size_t n = 0;
        for (int r = r_begin; r < r_end; ++r) {
          rows.row(static_cast<int>(range.j0 - whole.j0) + r, slot.row_tiles, static_cast<int>(range.i0 - whole.i0));
          const std::int64_t j = range.j0 + r;
          for (int c = 0; c < range.width(); ++c) {
            const std::int64_t i = range.i0 + c;
            const std::uint32_t t = slot.row_tiles[static_cast<std::size_t>(c)];
            const double x0 = static_cast<double>(i) * s, y0 = static_cast<double>(j) * s;
            if (!tile_filter(TileCell{i, j, t, Extent{x0, y0, x0 + s, y0 + s}})) continue;
            ++slot.kept;
            for (std::uint32_t k = table.first[t]; k < table.first[t + 1]; ++k) {
              const double x = x0 + table.x[k] * s, y = y0 + table.y[k] * s;
              const std::optional<double> z = ground.height(x, y);
              if (!z) continue;
              if constexpr (std::is_invocable_r_v<bool, PointFilter&, double, double, double, std::uint8_t, float>) {
                if (!point_filter(x, y, *z, table.species[k], table.rank[k])) continue;
              } else {
                if (!point_filter(x, y, *z)) continue;
              }
              ox[n] = static_cast<float>(x);
              oy[n] = static_cast<float>(y);
              oz[n] = static_cast<float>(*z);
              if (world) {
                // One class: the options' variant count (as before classes); several: the
                // point's class range.
                const bool by_class = table.class_variants.size() > 1;
                const auto [first_variant, variant_count] =
                    by_class ? table.class_variants[table.species[k]] : std::pair{0, world->variants};
                const PointAttributes a = world_point_attributes(world->seed, i, j, k - table.first[t], variant_count,
                                                                 world->min_scale, world->max_scale);
                oyaw[n] = a.yaw;
                oscale[n] = a.scale;
                ovariant[n] = static_cast<std::uint16_t>(first_variant + a.variant);
              } else {
                oyaw[n] = table.yaw[k];
                oscale[n] = table.scale[k];
                ovariant[n] = table.variant[k];
              }
              otile[n] = t;
              orank[n] = table.rank[k];
              ++n;
            }
          }
        }
        resize_batch(out, n);
        return b;
      }) & tbb::make_filter<int, void>(tbb::filter_mode::serial_in_order, [&](int b) {
        const BatchSlot& slot = slots[static_cast<std::size_t>(b % tokens)];
        stats.tiles_kept += slot.kept;
        if (slot.batch.empty()) return;
        stats.points += slot.batch.size();
        ++stats.batches;
        sink(static_cast<const InstanceBatch&>(slot.batch));
      }));
  stats.tiles = static_cast<std::uint64_t>(range.width()) * static_cast<std::uint64_t>(range.height());
  return stats;
}

}  // namespace wangscape
