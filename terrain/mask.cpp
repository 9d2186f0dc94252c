#include "terrain/mask.h"

#include <gdal_priv.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <memory>
#include <numbers>

#include "core/memory_budget.h"
#include "core/number_text.h"
#include "terrain/gdal_support.h"

namespace wangscape {

namespace {

using gdal_support::DatasetPtr;

// Reads band `index` (1-based) as floats scaled to 0..1 by the band type's range.
std::vector<float> read_unit_band(GDALDataset& dataset, int index, const std::string& path) {
  GDALRasterBand* band = dataset.GetRasterBand(index);
  const int w = dataset.GetRasterXSize(), h = dataset.GetRasterYSize();
  std::vector<float> values(std::size_t(w) * std::size_t(h));
  if (band->RasterIO(GF_Read, 0, 0, w, h, values.data(), w, h, GDT_Float32, 0, 0, nullptr) != CE_None)
    throw Error("cannot read the pixels of image '" + path + "'");
  const GDALDataType type = band->GetRasterDataType();
  const float full = type == GDT_Byte ? 255.0f : type == GDT_UInt16 ? 65535.0f : 1.0f;
  for (float& v : values) v /= full;
  return values;
}

// Opens an image file through GDAL; `what` names it in errors ("mask image").
DatasetPtr open_image(const std::filesystem::path& image, const std::string& what) {
  gdal_support::ensure_registered();
  gdal_support::ErrorCapture capture;
  const std::string path = image.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(image, ec)) throw Error(what + " '" + path + "' does not exist");
  DatasetPtr dataset(
      GDALDataset::FromHandle(GDALOpenEx(image.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!dataset || dataset->GetRasterCount() < 1)
    throw Error("cannot read " + what + " '" + path + "': not an image GDAL recognizes (expected PNG)" +
                capture.suffix());
  return dataset;
}

// Refuses an image whose reader would hold more than the memory limit (`bytes_per_pixel` at
// its peak).
void check_image_memory(const std::filesystem::path& image, const std::string& what, GDALDataset& dataset,
                        double bytes_per_pixel) {
  const int width = dataset.GetRasterXSize(), height = dataset.GetRasterYSize();
  check_memory_estimate(image,
                        "the " + what + " of " + std::to_string(width) + " x " + std::to_string(height) + " pixels",
                        bytes_per_pixel * width * height);
}

}  // namespace

RgbRaster read_rgb_raster(const std::filesystem::path& image) {
  const std::string path = image.string();
  const auto dataset = open_image(image, "image");
  check_image_memory(image, "image", *dataset, 3 + 4);  // RGB bytes and one float band
  RgbRaster raster;
  raster.width = dataset->GetRasterXSize();
  raster.height = dataset->GetRasterYSize();
  const int bands = dataset->GetRasterCount();
  raster.pixels.resize(std::size_t(raster.width) * std::size_t(raster.height) * 3);
  for (int c = 0; c < 3; ++c) {
    const auto values = read_unit_band(*dataset, bands >= 3 ? c + 1 : 1, path);
    for (std::size_t k = 0; k < values.size(); ++k)
      raster.pixels[k * 3 + std::size_t(c)] =
          static_cast<std::uint8_t>(std::lround(std::clamp(values[k], 0.0f, 1.0f) * 255.0f));
  }
  return raster;
}

// ---------------------------------------------------------------------------------------
// GroundMask

GroundMask GroundMask::painted(const std::filesystem::path& image, const Extent& over) {
  const std::string path = image.string();
  const auto dataset = open_image(image, "mask image");

  GroundMask mask;
  mask.file_ = image;
  mask.width_ = dataset->GetRasterXSize();
  mask.height_ = dataset->GetRasterYSize();
  mask.area_ = over;
  const int bands = dataset->GetRasterCount();
  // Gray, gray + alpha, RGB, RGB + alpha.
  const bool color = bands >= 3;
  const int alpha_band = bands == 2 ? 2 : bands >= 4 ? 4 : 0;
  // Luminance (with two more color bands) and alpha as floats at the peak, then one byte.
  check_image_memory(image, "mask image", *dataset, 4.0 * ((color ? 3 : 1) + (alpha_band > 0 ? 1 : 0)) + 1);
  std::vector<float> luminance = read_unit_band(*dataset, 1, path);
  if (color) {
    const auto g = read_unit_band(*dataset, 2, path), b = read_unit_band(*dataset, 3, path);
    for (std::size_t k = 0; k < luminance.size(); ++k)
      luminance[k] = 0.2126f * luminance[k] + 0.7152f * g[k] + 0.0722f * b[k];
  }
  std::vector<float> alpha;
  if (alpha_band > 0) alpha = read_unit_band(*dataset, alpha_band, path);
  mask.pixels_.resize(luminance.size());
  for (std::size_t k = 0; k < luminance.size(); ++k)
    mask.pixels_[k] = luminance[k] >= 0.5f && (alpha.empty() || alpha[k] >= 0.5f) ? kAllowed : kRefused;
  return mask;
}

bool GroundMask::pixel_of(double x, double y, double& px, double& py) const {
  if (terrain_ == nullptr) {
    px = (x - area_.min_x) / area_.width() * width_;
    py = (area_.max_y - y) / area_.height() * height_;
    return true;
  }
  // Sample (col, row) stands at the centre of DEM pixel (col, row).
  double col = 0, row = 0;
  if (!terrain_->map_to_sample(x, y, col, row)) return false;
  px = (col + 0.5) * refine_;
  py = (row + 0.5) * refine_;
  return true;
}

bool GroundMask::allows(double x, double y) const {
  if (terrain_ == nullptr && !area_.contains(x, y)) return false;
  double fx = 0, fy = 0;
  if (!pixel_of(x, y, fx, fy) || !(fx >= 0 && fy >= 0)) return false;
  const int px = std::min(int(fx), width_ - 1), py = std::min(int(fy), height_ - 1);
  if (terrain_ != nullptr && (fx > width_ || fy > height_)) return false;
  const std::uint8_t pixel = at(px, py);
  if (pixel != kBoundary) return pixel == kAllowed;
  // Tested where the instance will stand: its coordinates are stored as floats, and a GIS reads
  // those, so a point a hair inside must not be written a hair outside.
  return (*exact_)(double(float(x)), double(float(y)));
}

bool GroundMask::pixel_range(const Extent& r, int& x0, int& y0, int& x1, int& y1, bool& clamped) const {
  double fx0 = 0, fx1 = 0, fy0 = 0, fy1 = 0;
  if (terrain_ == nullptr) {
    fx0 = (r.min_x - area_.min_x) / area_.width() * width_;
    fx1 = (r.max_x - area_.min_x) / area_.width() * width_;
    fy0 = (area_.max_y - r.max_y) / area_.height() * height_;
    fy1 = (area_.max_y - r.min_y) / area_.height() * height_;
  } else {
    // The box of the rectangle's corners on the grid (its image is a slightly bent quadrilateral
    // inside it), cut to the terrain's extent first; a corner off the lattice counts as clamped.
    const Extent e = terrain_->extent();
    const Extent cut = r.intersected(e);
    if (cut.empty()) return false;
    clamped = !(cut.min_x == r.min_x && cut.min_y == r.min_y && cut.max_x == r.max_x && cut.max_y == r.max_y);
    fx0 = fy0 = std::numeric_limits<double>::infinity();
    fx1 = fy1 = -fx0;
    for (double x : {cut.min_x, cut.max_x})
      for (double y : {cut.min_y, cut.max_y}) {
        double px = 0, py = 0;
        if (!pixel_of(x, y, px, py)) return false;
        fx0 = std::min(fx0, px), fx1 = std::max(fx1, px);
        fy0 = std::min(fy0, py), fy1 = std::max(fy1, py);
      }
    constexpr double kPad = 1e-6;
    fx0 -= kPad, fy0 -= kPad, fx1 += kPad, fy1 += kPad;
  }
  if (fx1 < 0 || fy1 < 0 || fx0 > width_ || fy0 > height_) return false;
  clamped = clamped || fx0 < 0 || fy0 < 0 || fx1 > width_ || fy1 > height_;
  x0 = std::clamp(int(std::floor(fx0)), 0, width_ - 1);
  x1 = std::clamp(int(std::floor(fx1)), 0, width_ - 1);
  y0 = std::clamp(int(std::floor(fy0)), 0, height_ - 1);
  y1 = std::clamp(int(std::floor(fy1)), 0, height_ - 1);
  return true;
}

bool GroundMask::allows_all(const Extent& r) const {
  int x0, y0, x1, y1;
  bool clamped = false;
  if (!pixel_range(r, x0, y0, x1, y1, clamped) || clamped) return false;
  for (int py = y0; py <= y1; ++py)
    for (int px = x0; px <= x1; ++px)
      if (at(px, py) != kAllowed) return false;
  return true;
}

bool GroundMask::allows_any(const Extent& r) const {
  int x0, y0, x1, y1;
  bool clamped = false;
  if (!pixel_range(r, x0, y0, x1, y1, clamped)) return false;
  for (int py = y0; py <= y1; ++py)
    for (int px = x0; px <= x1; ++px)
      if (at(px, py) != kRefused) return true;
  return false;
}

double GroundMask::allowed_count() const {
  double count = 0;
  for (const std::uint8_t p : pixels_) count += p == kAllowed ? 1.0 : p == kBoundary ? 0.5 : 0.0;
  return count;
}

// ---------------------------------------------------------------------------------------
// TerrainFilter

TerrainFilter::TerrainFilter(const Terrain& terrain, TerrainFilterOptions options)
    : terrain_(&terrain), options_(std::move(options)) {
  if (options_.max_slope_deg && !(*options_.max_slope_deg >= 0 && *options_.max_slope_deg <= 90))
    throw Error("maximum slope " + significant_text(*options_.max_slope_deg, 6) +
                " is not an angle in [0, 90] degrees");
  if (options_.max_height_m && !std::isfinite(*options_.max_height_m))
    throw Error("maximum height is not a finite number of meters");
  if (options_.min_height_m && !std::isfinite(*options_.min_height_m))
    throw Error("minimum height is not a finite number of meters");
  if (options_.min_height_m && options_.max_height_m && *options_.min_height_m > *options_.max_height_m)
    throw Error("minimum height " + significant_text(*options_.min_height_m, 6) + " m is above the maximum height " +
                significant_text(*options_.max_height_m, 6) + " m");
  if (options_.mask_image) {
    masks_.push_back(GroundMask::painted(*options_.mask_image, terrain.extent()));
    mask_image_ = true;
  }
  // Moved, not copied: a mask's grid may be large.
  for (GroundMask& mask : options_.masks) masks_.push_back(std::move(mask));
  options_.masks.clear();

  const DemRaster& dem = terrain.dem();
  cells_x_ = dem.width - 1;
  cells_y_ = dem.height - 1;

  // d(col, row)/d(x, y) at the DEM center, from the exact sample -> ENU mapping.
  const double c = std::floor((dem.width - 1) / 2.0), r = std::floor((dem.height - 1) / 2.0);
  std::array<double, 3> xs{c, c + 1, c}, ys{r, r, r + 1};
  terrain.samples_to_enu(xs, ys);
  const double x_col = xs[1] - xs[0], y_col = ys[1] - ys[0], x_row = xs[2] - xs[0], y_row = ys[2] - ys[0];
  const double det = x_col * y_row - x_row * y_col;
  const double col_x = y_row / det, col_y = -x_row / det, row_x = -y_col / det, row_y = x_col / det;

  const double max_height = options_.max_height_m.value_or(std::numeric_limits<double>::infinity());
  const double min_height = options_.min_height_m.value_or(-std::numeric_limits<double>::infinity());
  const double max_tan2 = options_.max_slope_deg
                              ? std::pow(std::tan(*options_.max_slope_deg * std::numbers::pi / 180), 2)
                              : std::numeric_limits<double>::infinity();
  double min_tan2 = std::numeric_limits<double>::infinity();
  cell_flags_.assign(std::size_t(cells_x_) * std::size_t(cells_y_), 0);
  for (int row = 0; row < cells_y_; ++row)
    for (int col = 0; col < cells_x_; ++col) {
      const float* p = &dem.heights[dem.index(col, row)];
      const float* q = p + dem.width;
      const float corners[4] = {p[0], p[1], q[0], q[1]};
      bool all_data = true;
      double highest = -std::numeric_limits<double>::infinity(), lowest = -highest;
      for (float h : corners) {
        if (std::isnan(h)) {
          all_data = false;
          continue;
        }
        highest = std::max(highest, double(h));
        lowest = std::min(lowest, double(h));
      }
      // The bilinear ground of a cell takes every height between its lowest and highest corner.
      const bool some_in_range = lowest <= max_height && highest >= min_height;
      std::uint8_t& flags = cell_flags_[std::size_t(row) * std::size_t(cells_x_) + std::size_t(col)];
      if (some_in_range) {
        flags |= kSomeInRange;
        ++maybe_cells_;
      }
      if (!all_data) continue;
      flags |= kData;
      if (highest <= max_height && lowest >= min_height) flags |= kInRange;
      // The gradient at each corner, from the cell's edges that meet there.
      const double along_top = p[1] - p[0], along_bottom = q[1] - q[0];
      const double down_left = q[0] - p[0], down_right = q[1] - p[1];
      const double gradients[4][2] = {
          {along_top, down_left}, {along_top, down_right}, {along_bottom, down_left}, {along_bottom, down_right}};
      double steepest = 0;
      for (const auto& g : gradients) {
        const double dz_dx = g[0] * col_x + g[1] * row_x, dz_dy = g[0] * col_y + g[1] * row_y;
        steepest = std::max(steepest, dz_dx * dz_dx + dz_dy * dz_dy);
      }
      if (some_in_range) min_tan2 = std::min(min_tan2, steepest);
      if (steepest > max_tan2) continue;
      flags |= kFlat;
      if (flags & kInRange) ++passing_cells_;
    }
  min_cell_slope_deg_ = std::atan(std::sqrt(min_tan2)) * 180 / std::numbers::pi;
}

bool TerrainFilter::touched_cells(const Extent& tile, bool clamp, SampleBox& box) const {
  Extent rect = tile;
  if (clamp) {
    const Extent e = terrain_->extent();
    rect = {std::max(rect.min_x, e.min_x), std::max(rect.min_y, e.min_y), std::min(rect.max_x, e.max_x),
            std::min(rect.max_y, e.max_y)};
    if (!(rect.min_x <= rect.max_x && rect.min_y <= rect.max_y)) return false;
  }
  box.col_lo = box.row_lo = std::numeric_limits<double>::infinity();
  box.col_hi = box.row_hi = -box.col_lo;
  const double xs[2] = {rect.min_x, rect.max_x}, ys[2] = {rect.min_y, rect.max_y};
  for (double x : xs)
    for (double y : ys) {
      double col, row;
      if (!terrain_->map_to_sample(x, y, col, row)) return false;
      box.col_lo = std::min(box.col_lo, col);
      box.col_hi = std::max(box.col_hi, col);
      box.row_lo = std::min(box.row_lo, row);
      box.row_hi = std::max(box.row_hi, row);
    }
  if (!clamp && (box.col_lo < 0 || box.row_lo < 0 || box.col_hi > cells_x_ || box.row_hi > cells_y_)) return false;
  if (box.col_hi < 0 || box.row_hi < 0 || box.col_lo > cells_x_ || box.row_lo > cells_y_) return false;
  box.c0 = std::clamp(int(std::floor(box.col_lo)), 0, cells_x_ - 1);
  box.c1 = std::clamp(int(std::floor(box.col_hi)), 0, cells_x_ - 1);
  box.r0 = std::clamp(int(std::floor(box.row_lo)), 0, cells_y_ - 1);
  box.r1 = std::clamp(int(std::floor(box.row_hi)), 0, cells_y_ - 1);
  return true;
}

bool TerrainFilter::box_within(const SampleBox& box, double min_height, double max_height) const {
  // Along any row or column line the bilinear surface is linear between grid lines, so its
  // extremes over an axis-aligned box is reached where the box's edges or corners meet the
  // grid lines (or at grid nodes inside). The box is padded by a hair: the tile's image
  // in sample coordinates is a slightly bent quadrilateral inside it.
  constexpr double kPad = 1e-6;
  const double max_col = cells_x_, max_row = cells_y_;
  const double col_lo = std::max(0.0, box.col_lo - kPad), col_hi = std::min(max_col, box.col_hi + kPad);
  const double row_lo = std::max(0.0, box.row_lo - kPad), row_hi = std::min(max_row, box.row_hi + kPad);
  auto lines = [](double lo, double hi, std::vector<double>& out) {
    out.clear();
    out.push_back(lo);
    for (double k = std::floor(lo) + 1; k < hi; ++k) out.push_back(k);
    out.push_back(hi);
  };
  thread_local std::vector<double> cols, rows;
  lines(col_lo, col_hi, cols);
  lines(row_lo, row_hi, rows);
  for (double row : rows)
    for (double col : cols) {
      const auto h = terrain_->height_at_sample(col, row);
      if (!h || *h > max_height || *h < min_height) return false;
    }
  return true;
}

bool TerrainFilter::tile_passes(const Extent& tile) const {
  SampleBox box;
  if (!touched_cells(tile, false, box)) return false;
  bool all_in_range = true;
  for (int row = box.r0; row <= box.r1; ++row)
    for (int col = box.c0; col <= box.c1; ++col) {
      const std::uint8_t flags = cell_flags_[std::size_t(row) * std::size_t(cells_x_) + std::size_t(col)];
      if ((flags & (kData | kFlat)) != (kData | kFlat)) return false;
      all_in_range = all_in_range && (flags & kInRange);
    }
  // Cells whose corners are all within the limits need nothing more; otherwise the tile's own
  // ground decides.
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (!all_in_range &&
      !box_within(box, options_.min_height_m.value_or(-kInfinity), options_.max_height_m.value_or(kInfinity)))
    return false;
  return std::all_of(masks_.begin(), masks_.end(), [&](const GroundMask& m) { return m.allows_all(tile); });
}

bool TerrainFilter::tile_may_pass(const Extent& tile) const {
  SampleBox box;
  if (!touched_cells(tile, true, box)) return false;
  bool some = false;
  for (int row = box.r0; row <= box.r1 && !some; ++row)
    for (int col = box.c0; col <= box.c1 && !some; ++col)
      some = (cell_flags_[std::size_t(row) * std::size_t(cells_x_) + std::size_t(col)] & kSomeInRange) != 0;
  return some && std::all_of(masks_.begin(), masks_.end(), [&](const GroundMask& m) { return m.allows_any(tile); });
}

bool TerrainFilter::point_passes(double x, double y) const {
  if (!options_.max_slope_deg) {  // the common case needs no gradient
    const auto h = terrain_->height(x, y);
    if (!h || !height_in_range(*h)) return false;
  } else {
    const auto s = terrain_->sample(x, y);
    if (!s || !height_in_range(s->height)) return false;
    if (s->slope_degrees() > *options_.max_slope_deg) return false;
  }
  return masks_allow(x, y);
}

bool TerrainFilter::point_passes(double x, double y, double z) const {
  if (!height_in_range(z)) return false;
  if (options_.max_slope_deg) {
    const auto slope = terrain_->slope_degrees(x, y);
    if (!slope || *slope > *options_.max_slope_deg) return false;
  }
  return masks_allow(x, y);
}

double TerrainFilter::passing_share(bool partial) const {
  const double cells = double(cells_x_) * double(cells_y_);
  if (!(cells > 0)) return 0;
  double share = double(partial ? maybe_cells_ : passing_cells_) / cells;
  for (const GroundMask& m : masks_) share *= m.allowed_count() / (double(m.width()) * double(m.height()));
  return share;
}

void TerrainFilter::check_satisfiable() const {
  const DemRaster& dem = terrain_->dem();
  std::string range(1, '(');  // appended piecewise: GCC 12 warns falsely on "(" + ...
  range += significant_text(dem.min_height, 6);
  range += " .. ";
  range += significant_text(dem.max_height, 6);
  range += " m)";
  if (options_.max_height_m && *options_.max_height_m < dem.min_height)
    throw Error("maximum height " + significant_text(*options_.max_height_m, 6) + " m is below every height of DEM '" +
                dem.path.string() + "' " + range + ": no tile would be instantiated");
  if (options_.min_height_m && *options_.min_height_m > dem.max_height)
    throw Error("minimum height " + significant_text(*options_.min_height_m, 6) + " m is above every height of DEM '" +
                dem.path.string() + "' " + range + ": no tile would be instantiated");
  for (const GroundMask& m : masks_) {
    if (m.allowed_count() > 0) continue;
    if (&m == mask())
      throw Error("mask image '" + m.file().string() +
                  "' allows flowers nowhere (no pixel is white): no tile would be instantiated");
    if (m.file().empty())
      throw Error("the latitude/longitude area misses DEM '" + dem.path.string() + "': no tile would be instantiated");
    throw Error(m.file(), "",
                "allows flowers nowhere over DEM '" + dem.path.string() + "': no tile would be instantiated");
  }
  if (maybe_cells_ == 0) throw Error("no ground of DEM '" + dem.path.string() + "' passes the height test " + range);
  if (options_.max_slope_deg && passing_cells_ == 0 && *options_.max_slope_deg < min_cell_slope_deg_)
    throw Error("maximum slope " + significant_text(*options_.max_slope_deg, 6) +
                " deg is below the slope of every cell of DEM '" + dem.path.string() + "' (the flattest cell reaches " +
                significant_text(min_cell_slope_deg_, 6) + " deg): no tile would be instantiated");
}

}  // namespace wangscape
