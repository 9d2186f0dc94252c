// Where flowers may grow on a terrain (Shade 2002, section 5.1): tiles are instantiated only
// where the ground is low enough, and optionally not too steep and allowed by every mask (a
// painted image stretched over the terrain, a georeferenced raster, polygons, a lat/lon box). The predicates here are
// what placement calls per tile and per point.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "terrain/terrain.h"

namespace wangscape {

// Which side of a mask's polygons flowers grow on.
enum class PolygonSide { inside, outside };

// One mask: where flowers may grow, as a grid of pixels over the ground. Whatever the file, a
// mask is this one type, tested the same way by placement (TerrainFilter) and by species:
// - painted(): an image (PNG or anything GDAL reads) stretched over an ENU rectangle, north up
//   (top row = north edge, left column = west edge); a pixel allows flowers where it is light
//   (luminance >= 50%) and opaque (alpha >= 50%, when there is alpha);
// - raster(): a georeferenced raster in any CRS, warped by GDAL onto the DEM's grid (nearest
//   neighbour, exact transformation), refined so that its pixels are no larger than the file's;
//   a pixel allows flowers where its first band is non-zero (zero, no-data and off the raster:
//   none);
// - polygons(): the polygons of an OGR layer, reprojected by OGR into the DEM's CRS (buffered
//   first, in metres), burnt onto the DEM's grid by GDAL; pixels their boundary touches are
//   decided per point by an exact point-in-polygon test in the DEM's CRS;
// - lat_lon_box(): a WGS 84 latitude/longitude rectangle, on the DEM's grid the same way, its
//   boundary pixels decided per point by the point's latitude and longitude.
// The georeferenced kinds keep a pointer to the terrain: it must outlive the mask and not move.
// Thread-safe once built (const).
class GroundMask {
 public:
  // Throws Error naming the file if GDAL cannot read it.
  static GroundMask painted(const std::filesystem::path& image, const Extent& over);
  // Throws Error naming the file when it is missing, not a raster, has no georeference (a CRS
  // and a geotransform), or does not overlap the DEM.
  static GroundMask raster(const std::filesystem::path& file, const Terrain& terrain);
  // Throws Error naming the file when it is missing, not a vector file OGR reads, its first
  // layer holds no polygon (or something else than polygons), has no CRS, or `buffer_m` is not
  // finite.
  static GroundMask polygons(const std::filesystem::path& file, const Terrain& terrain, PolygonSide keep,
                             double buffer_m);
  // [min_lat, min_lon, max_lat, max_lon], WGS 84 degrees (checked by the caller).
  static GroundMask lat_lon_box(const std::array<double, 4>& box, const Terrain& terrain);

  const std::filesystem::path& file() const { return file_; }  // empty for a lat/lon box
  int width() const { return width_; }
  int height() const { return height_; }
  // The pixel under ENU (x, y) allows flowers (on a boundary pixel: the point itself is inside);
  // false outside the grid.
  bool allows(double x, double y) const;
  // Every pixel the rectangle touches allows flowers (false if it reaches outside, or touches a
  // boundary pixel).
  bool allows_all(const Extent& r) const;
  // Some pixel the rectangle touches may allow flowers.
  bool allows_any(const Extent& r) const;
  // Pixels that allow flowers, boundary pixels counted as half: for estimates.
  double allowed_count() const;

 private:
  enum Pixel : std::uint8_t { kRefused = 0, kAllowed = 1, kBoundary = 2 };
  // Pixel ranges the rectangle touches, clamped; false if it misses the grid.
  bool pixel_range(const Extent& r, int& x0, int& y0, int& x1, int& y1, bool& clamped) const;
  // Fractional pixel coordinates of ENU (x, y); false off the terrain's lattice.
  bool pixel_of(double x, double y, double& px, double& py) const;
  std::uint8_t at(int px, int py) const { return pixels_[std::size_t(py) * std::size_t(width_) + std::size_t(px)]; }

  std::filesystem::path file_;
  std::vector<std::uint8_t> pixels_;  // row-major, row 0 = north (painted) or the DEM's row 0
  int width_ = 0, height_ = 0;
  Extent area_;                       // painted: the ENU rectangle the image is stretched over
  const Terrain* terrain_ = nullptr;  // georeferenced: pixels on the DEM's grid, `refine_` a cell side
  int refine_ = 1;
  // Boundary pixels: whether the ENU point (as the instance stores it, floats) is inside.
  std::shared_ptr<const std::function<bool(double x, double y)>> exact_;
};

// An 8-bit RGB image read through GDAL (gray replicated, alpha dropped), top row first,
// 3 bytes per pixel: what a scene's user exemplar is read with (terrain/ is the scene's GDAL).
struct RgbRaster {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;
};
// Throws Error naming the file if it is missing or GDAL cannot read it.
RgbRaster read_rgb_raster(const std::filesystem::path& image);

struct TerrainFilterOptions {
  std::optional<double> max_height_m;               // orthometric meters; no flowers above
  std::optional<double> min_height_m;               // orthometric meters; no flowers below
  std::optional<double> max_slope_deg;              // degrees from horizontal
  std::optional<std::filesystem::path> mask_image;  // painted mask over the terrain's extent
  // Masks made beforehand (georeferenced rasters, polygons, a lat/lon box), all of which must allow.
  std::vector<GroundMask> masks;
};

// The ground tests for placement. Built once per terrain (a table over the DEM's cells),
// then thread-safe (const). Keeps a pointer to the terrain: the terrain must outlive the
// filter and not move.
//
// A tile passes when every DEM cell it touches has data at its four corners and a slope
// of at most max_slope at each corner (the bilinear slope is largest at a corner), and
// the ground over the tile is nowhere above max_height nor below min_height: exactly, with the
// bilinear surface's extremes over the tile's box in sample coordinates. The slope table converts
// DEM gradients to ENU with the Jacobian at the DEM center: exact for 7.5' quadrangles,
// within ~1% of the slope's tangent over a 1-degree DEM.
class TerrainFilter {
 public:
  TerrainFilter(const Terrain& terrain, TerrainFilterOptions options);

  // All of the tile's ground passes: every DEM cell the rectangle touches passes, and
  // every mask pixel it touches allows flowers. (Shade 2002: instantiate only these tiles.)
  bool tile_passes(const Extent& tile) const;
  // Some of the tile's ground may pass (a cheap superset, for fair edges, where each
  // point is then tested with point_passes).
  bool tile_may_pass(const Extent& tile) const;
  // The ground at ENU (x, y) has data, is low enough, flat enough and painted white.
  bool point_passes(double x, double y) const;
  // The same, for a point whose ground height z (meters) is already known.
  bool point_passes(double x, double y, double z) const;

  // Throws Error explaining why no ground can pass (a height threshold below every
  // height of the DEM, a slope limit below every slope, an all-black mask), so a scatter
  // reports that instead of writing an empty result.
  void check_satisfiable() const;

  // The share (0..1) of the DEM's cells whose ground passes (`partial`: may partly pass, the
  // tiles fair edges keep), times the share of the mask's pixels that allow flowers: an
  // estimate of what the masks keep, for counts before placement, not a test.
  double passing_share(bool partial) const;

  const TerrainFilterOptions& options() const { return options_; }
  // The painted mask (mask_image), or nullptr.
  const GroundMask* mask() const { return mask_image_ ? &masks_.front() : nullptr; }

 private:
  // A tile in DEM sample coordinates: the bounding box of its corners, and the cells
  // [c0, c1] x [r0, r1] it touches.
  struct SampleBox {
    double col_lo, col_hi, row_lo, row_hi;
    int c0, r0, c1, r1;
  };
  // False if a corner of the rectangle is off the lattice or the DEM (clamp false), or the
  // rectangle misses the DEM (clamp true: it is first cut to the terrain's extent).
  bool touched_cells(const Extent& tile, bool clamp, SampleBox& box) const;
  bool height_in_range(double z) const {
    return (!options_.max_height_m || z <= *options_.max_height_m) &&
           (!options_.min_height_m || z >= *options_.min_height_m);
  }
  bool masks_allow(double x, double y) const {
    for (const GroundMask& m : masks_)
      if (!m.allows(x, y)) return false;
    return true;
  }
  // The bilinear ground over the box has data and stays within [min_height, max_height] (exact).
  bool box_within(const SampleBox& box, double min_height, double max_height) const;

  const Terrain* terrain_;
  TerrainFilterOptions options_;
  std::vector<GroundMask> masks_;  // the painted one first, then options_.masks
  bool mask_image_ = false;
  int cells_x_ = 0, cells_y_ = 0;
  // Per DEM cell: all four corners have data, its slope is within the limit, all corners
  // are within the height limits, some of its ground (between its corners) may be.
  enum CellFlag : std::uint8_t { kData = 1, kFlat = 2, kInRange = 4, kSomeInRange = 8 };
  std::vector<std::uint8_t> cell_flags_;
  std::size_t passing_cells_ = 0, maybe_cells_ = 0;
  double min_cell_slope_deg_ = 0;
};

}  // namespace wangscape
