#include "generator/placement.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/number_text.h"

namespace wangscape {

PlacementTable::PlacementTable(const FilledTileSet& filled) {
  first.reserve(filled.tiles.size() + 1);
  first.push_back(0);
  for (const auto& points : filled.tiles) {
    max_points_per_tile = std::max(max_points_per_tile, points.size());
    for (const TilePoint& p : points) {
      x.push_back(p.x);
      y.push_back(p.y);
      yaw.push_back(p.yaw);
      scale.push_back(p.scale);
      variant.push_back(p.variant);
      species.push_back(p.species);
      rank.push_back(p.rank);
    }
    first.push_back(static_cast<std::uint32_t>(x.size()));
  }
  for (std::size_t c = 0; c < std::max<std::size_t>(filled.classes.size(), 1); ++c)
    class_variants.push_back(class_variant_range(filled, static_cast<int>(c)));
}

void resize_batch(InstanceBatch& batch, std::size_t n) {
  batch.x.resize(n);
  batch.y.resize(n);
  batch.z.resize(n);
  batch.yaw.resize(n);
  batch.scale.resize(n);
  batch.variant.resize(n);
  batch.tile.resize(n);
  batch.rank.resize(n);
}

TileRange tile_range(const Extent& area, double tile_size) {
  if (!(tile_size > 0) || !std::isfinite(tile_size))
    throw Error("placement: tile size " + significant_text(tile_size, 6) +
                " m; expected a finite number of meters > 0");
  // Checked as doubles first: a tiny tile or a huge area must not overflow the conversion.
  const double bounds[4] = {std::floor(area.min_x / tile_size), std::floor(area.min_y / tile_size),
                            std::ceil(area.max_x / tile_size), std::ceil(area.max_y / tile_size)};
  for (const double b : bounds)
    if (!(std::abs(b) <= static_cast<double>(kMaxTileCoordinate)))
      throw Error("placement: an area of " + significant_text(area.width(), 6) + " x " +
                  significant_text(area.height(), 6) + " m at tile size " + significant_text(tile_size, 6) +
                  " m reaches beyond tile coordinate +-2^60, the largest a tiling addresses");
  TileRange r;
  r.i0 = static_cast<std::int64_t>(bounds[0]);
  r.j0 = static_cast<std::int64_t>(bounds[1]);
  r.i1 = static_cast<std::int64_t>(bounds[2]);
  r.j1 = static_cast<std::int64_t>(bounds[3]);
  constexpr std::int64_t kMaxSide = 1 << 30;
  if (r.i1 - r.i0 > kMaxSide || r.j1 - r.j0 > kMaxSide)
    throw Error("placement: area of " + std::to_string(area.width()) + " x " + std::to_string(area.height()) +
                " m needs more than 2^30 tiles of " + std::to_string(tile_size) + " m per side");
  return r;
}

TileRange clip_range(const TileRange& part, const TileRange& whole) {
  TileRange r{std::max(part.i0, whole.i0), std::max(part.j0, whole.j0), std::min(part.i1, whole.i1),
              std::min(part.j1, whole.j1)};
  if (r.i1 < r.i0) r.i1 = r.i0;
  if (r.j1 < r.j0) r.j1 = r.j0;
  return r;
}

RowTiles::RowTiles(const TileSet& set, const TileRange& range, const PlacementOptions& options)
    : RowTiles(set, range, options, range) {}

RowTiles::RowTiles(const TileSet& set, const TileRange& range, const PlacementOptions& options, const TileRange& needed)
    : range_(range) {
  const bool hashed = options.algorithm == TilingAlgorithm::hash;
  if (hashed && !options.forbid_identical_neighbours) {
    hashed_.emplace(set, options.seed);
    return;
  }
  // A hashed tiling is the same wherever its window starts: only the part asked for.
  const TileRange part = hashed ? clip_range(needed, range) : range;
  TilingOptions tiling_options;
  tiling_options.algorithm = options.algorithm;
  tiling_options.seed = options.seed;
  tiling_options.forbid_identical_neighbours = options.forbid_identical_neighbours;
  tiling_options.origin_i = part.i0;
  tiling_options.origin_j = part.j0;
  tiling_.emplace(make_tiling(set, part.width(), part.height(), tiling_options));
}

void RowTiles::row(int r, std::span<std::uint16_t> out, int c) const {
  if (hashed_) {
    hashed_->fill_row(range_.i0 + c, range_.j0 + r, out);
    return;
  }
  const std::int64_t i = range_.i0 + c - tiling_->origin_i, j = range_.j0 + r - tiling_->origin_j;
  const auto* start = tiling_->tiles.data() + static_cast<std::size_t>(j) * static_cast<std::size_t>(tiling_->width) +
                      static_cast<std::size_t>(i);
  std::copy(start, start + out.size(), out.begin());
}

}  // namespace wangscape
