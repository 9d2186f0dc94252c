#include "terrain/terrain.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "core/memory_budget.h"
#include "core/number_text.h"

namespace wangscape {

namespace {

// Lattice nodes are this many DEM samples apart: the ENU -> sample mapping bends by about
// (step^2 / Earth radius) over a lattice cell, far below a millimeter at this size.
constexpr double kLatticeStepInSamples = 8.0;
// A regular DEM needs 1/64; a strip one or two cells wide 1/4. Found by the DEM fuzzer: 2 x 280,487
// cells bent over 4,116 km by the frame took 2.2 million nodes (6 s) at the earlier 4 per cell.
constexpr double kMaxLatticeNodesPerCell = 0.5;

// The ENU frame and the sample lattice need one continuous longitude range within +-180
// degrees: a geographic DEM past 180 (across the antimeridian, or in 0..360 longitudes) is
// refused with what to do, instead of failing later on an origin "out of range".
void check_longitudes(const DemRaster& dem) {
  if (!dem.geographic) return;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const double col : {-0.5, dem.width - 0.5})  // pixel edges, as GDAL's corners
    for (const double row : {-0.5, dem.height - 0.5}) {
      const double lon = dem.crs_of(col, row)[0];
      lo = std::min(lo, lon);
      hi = std::max(hi, lon);
    }
  if (lo >= -180.0 && hi <= 180.0) return;
  const bool crosses = (lo < -180.0 && hi > -180.0) || (lo < 180.0 && hi > 180.0);
  throw Error(dem.path, "",
              "the DEM spans longitudes " + fixed_text(lo, 4) + " to " + fixed_text(hi, 4) + ", " +
                  (crosses ? "across the antimeridian (180 degrees)" : "beyond +-180 degrees (0..360 longitudes)") +
                  "; Wangscape needs geographic longitudes within -180..180: reproject the DEM to a projected CRS, "
                  "e.g. UTM zone 60 (gdalwarp -t_srs EPSG:32660, or EPSG:32760 south of the equator), or cut it at "
                  "180 degrees");
}

const DemRaster& checked(const DemRaster& dem) {
  if (dem.width < 2 || dem.height < 2)
    throw Error("DEM '" + dem.path.string() + "' has " + std::to_string(dem.width) + " x " +
                std::to_string(dem.height) + " samples; at least 2 x 2 are needed to interpolate heights");
  check_longitudes(dem);
  return dem;
}

LatLon default_origin(const DemRaster& dem, const CrsToWgs84& crs, const TerrainOptions& options) {
  if (options.origin) return *options.origin;
  auto center = dem.crs_of((dem.width - 1) / 2.0, (dem.height - 1) / 2.0);
  crs.to_wgs84(std::span(&center[0], 1), std::span(&center[1], 1));
  // EnuFrame refuses such an origin too, but without the file: here the DEM is at fault.
  if (!(std::abs(center[1]) <= 90) || !(std::abs(center[0]) <= 180))
    throw Error(dem.path, "",
                "its center lies at latitude " + fixed_text(center[1], 6) + ", longitude " + fixed_text(center[0], 6) +
                    " (WGS 84 degrees); expected latitude in [-90, 90] and longitude in [-180, 180]: check the DEM's "
                    "georeference (its corner coordinates and CRS)");
  return {center[1], center[0]};
}

std::string vertical_datum_of(const DemRaster& dem) {
  if (dem.driver == "SRTMHGT") return "EGM96 geoid (SRTM); heights as stored, not converted";
  if (dem.driver == "USGSDEM")
    return "mean sea level as the USGS DEM header states (usually NGVD 1929); heights as stored, not converted";
  return "orthometric, as stored in the file; not converted";
}

}  // namespace

std::array<double, 3> GroundSample::normal() const {
  const double inverse_length = 1.0 / std::sqrt(dz_dx * dz_dx + dz_dy * dz_dy + 1.0);
  return {-dz_dx * inverse_length, -dz_dy * inverse_length, inverse_length};
}

double GroundSample::slope_degrees() const {
  return std::atan(std::sqrt(dz_dx * dz_dx + dz_dy * dz_dy)) * (180.0 / std::numbers::pi);
}

Terrain Terrain::load(const std::filesystem::path& path, const TerrainOptions& options) {
  return Terrain(read_dem(path), options);
}

Terrain::Terrain(DemRaster dem, const TerrainOptions& options)
    : dem_(std::move(dem)),
      crs_(checked(dem_)),
      frame_(default_origin(dem_, crs_, options)),
      max_col_(dem_.width - 1),
      max_row_(dem_.height - 1) {
  // Spacing: the ENU length of one sample step at the DEM center.
  const double c = (dem_.width - 1) / 2.0, r = (dem_.height - 1) / 2.0;
  std::array<double, 3> cols{c, c + 1, c}, rows{r, r, r + 1};
  samples_to_enu(cols, rows);
  spacing_m_ = {std::hypot(cols[1] - cols[0], rows[1] - rows[0]), std::hypot(cols[2] - cols[0], rows[2] - rows[0])};

  build_extent();
  build_lattice();
}

TerrainGeoreference Terrain::georeference() const {
  TerrainGeoreference g;
  const LatLon origin = frame_.origin();
  g.crs_wkt = dem_.crs_wkt;
  g.crs_name = dem_.crs_name;
  g.horizontal_datum = crs_.datum();
  g.origin_lat_deg = origin.lat;
  g.origin_lon_deg = origin.lon;
  g.vertical_datum = vertical_datum_of(dem_);
  g.utm_zone = frame_.utm_zone();
  g.utm_north = frame_.utm_north();
  g.convergence_deg = frame_.convergence_deg();
  g.utm_scale = frame_.utm_scale();
  g.datum_note = crs_.note();
  g.datum_accuracy_m = crs_.accuracy_m();
  return g;
}

void Terrain::build_extent() {
  // The ENU bounding box of the samples with data is reached on the boundary of the data:
  // the first and last valid sample of every row and of every column.
  std::vector<double> cols, rows;
  auto add = [&](int col, int row) {
    cols.push_back(col);
    rows.push_back(row);
  };
  for (int row = 0; row < dem_.height; ++row) {
    int first = -1, last = -1;
    for (int col = 0; col < dem_.width; ++col)
      if (!std::isnan(dem_.heights[dem_.index(col, row)])) {
        if (first < 0) first = col;
        last = col;
      }
    if (first >= 0) {
      add(first, row);
      add(last, row);
    }
  }
  for (int col = 0; col < dem_.width; ++col) {
    int first = -1, last = -1;
    for (int row = 0; row < dem_.height; ++row)
      if (!std::isnan(dem_.heights[dem_.index(col, row)])) {
        if (first < 0) first = row;
        last = row;
      }
    if (first >= 0) {
      add(col, first);
      add(col, last);
    }
  }
  samples_to_enu(cols, rows);
  const double inf = std::numeric_limits<double>::infinity();
  extent_ = {inf, inf, -inf, -inf};
  for (std::size_t k = 0; k < cols.size(); ++k) {
    extent_.min_x = std::min(extent_.min_x, cols[k]);
    extent_.max_x = std::max(extent_.max_x, cols[k]);
    extent_.min_y = std::min(extent_.min_y, rows[k]);
    extent_.max_y = std::max(extent_.max_y, rows[k]);
  }
}

void Terrain::build_lattice() {
  const double step = kLatticeStepInSamples * std::min(spacing_m_[0], spacing_m_[1]);
  const double nx = std::max(2.0, std::ceil(extent_.width() / step) + 1),
               ny = std::max(2.0, std::ceil(extent_.height() / step) + 1);
  // A regular DEM needs about one lattice node per 64 cells. A grid whose cells spread far wider
  // in the scene's frame (a strip thousands of kilometers long, bent by the frame) would need
  // work out of proportion to its data: refused before the conversions (docs/limits.md).
  const double max_nodes = kMaxLatticeNodesPerCell * double(dem_.cell_count()) + 65536.0;
  const auto km = [](double m) {
    return std::isfinite(m) ? std::to_string(static_cast<long long>(std::min(m, 1e15) / 1000)) : std::string("?");
  };
  if (!(nx * ny <= max_nodes))
    throw Error("DEM '" + dem_.path.string() + "': its heights span " + km(extent_.width()) + " x " +
                km(extent_.height()) + " km in the scene's frame, more than its " + std::to_string(dem_.cell_count()) +
                " cells cover (at most one georeference node per " + std::to_string(int(1 / kMaxLatticeNodesPerCell)) +
                " cells); a grid this long or bent does not fit one local frame");
  // Per node: its ENU position while converting (2 doubles) and the sample it maps to (2 doubles).
  check_memory_estimate(dem_.path,
                        "its georeference lattice of " + std::to_string(static_cast<long long>(nx)) + " x " +
                            std::to_string(static_cast<long long>(ny)) + " nodes",
                        32.0 * nx * ny);
  lattice_nx_ = int(nx);
  lattice_ny_ = int(ny);
  lattice_x0_ = extent_.min_x;
  lattice_y0_ = extent_.min_y;
  inverse_lattice_step_ = 1.0 / step;
  // The lattice may reach a little past the extent; queries stop at the extent's edge.
  lattice_max_fx_ = std::min(double(lattice_nx_ - 1), extent_.width() * inverse_lattice_step_);
  lattice_max_fy_ = std::min(double(lattice_ny_ - 1), extent_.height() * inverse_lattice_step_);

  const std::size_t count = std::size_t(lattice_nx_) * std::size_t(lattice_ny_);
  std::vector<double> xs(count), ys(count);
  for (int j = 0; j < lattice_ny_; ++j)
    for (int i = 0; i < lattice_nx_; ++i) {
      xs[std::size_t(j) * lattice_nx_ + i] = lattice_x0_ + i * step;
      ys[std::size_t(j) * lattice_nx_ + i] = lattice_y0_ + j * step;
    }
  enu_to_samples(xs, ys);
  lattice_.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    if (!std::isfinite(xs[k]) || !std::isfinite(ys[k]))
      throw Error("DEM '" + dem_.path.string() + "': part of its area does not transform between its CRS and WGS 84");
    lattice_[k] = {xs[k], ys[k]};
  }
}

std::optional<GroundSample> Terrain::sample(double x, double y) const {
  LatticeHit lattice;
  if (!locate_in_lattice(x, y, lattice)) return std::nullopt;
  const double col = lattice.interpolate(&LatticeNode::col);
  const double row = lattice.interpolate(&LatticeNode::row);
  CellHit cell;
  if (!locate_in_dem(col, row, cell)) return std::nullopt;
  const float *p = cell.p, *q = cell.q;
  const double top = p[0] + cell.tc * (p[1] - p[0]), bottom = q[0] + cell.tc * (q[1] - q[0]);
  const double h = top + cell.tr * (bottom - top);
  if (std::isnan(h)) return std::nullopt;

  // Chain rule: d(height)/d(sample coords) from the DEM cell, d(sample coords)/d(ENU)
  // from the lattice cell.
  const double dh_dcol = (1 - cell.tr) * (p[1] - p[0]) + cell.tr * (q[1] - q[0]);
  const double dh_drow = (1 - cell.tc) * (q[0] - p[0]) + cell.tc * (q[1] - p[1]);
  const LatticeNode *a = lattice.a, *b = lattice.b;
  const double tx = lattice.tx, ty = lattice.ty, k = inverse_lattice_step_;
  const double dcol_dx = ((1 - ty) * (a[1].col - a[0].col) + ty * (b[1].col - b[0].col)) * k;
  const double drow_dx = ((1 - ty) * (a[1].row - a[0].row) + ty * (b[1].row - b[0].row)) * k;
  const double dcol_dy = ((1 - tx) * (b[0].col - a[0].col) + tx * (b[1].col - a[1].col)) * k;
  const double drow_dy = ((1 - tx) * (b[0].row - a[0].row) + tx * (b[1].row - a[1].row)) * k;
  GroundSample s;
  s.height = h;
  s.dz_dx = dh_dcol * dcol_dx + dh_drow * drow_dx;
  s.dz_dy = dh_dcol * dcol_dy + dh_drow * drow_dy;
  return s;
}

std::optional<std::array<double, 3>> Terrain::normal(double x, double y) const {
  const auto s = sample(x, y);
  if (!s) return std::nullopt;
  return s->normal();
}

std::optional<double> Terrain::slope_degrees(double x, double y) const {
  const auto s = sample(x, y);
  if (!s) return std::nullopt;
  return s->slope_degrees();
}

void Terrain::samples_to_enu(std::span<double> col_to_x, std::span<double> row_to_y) const {
  for (std::size_t k = 0; k < col_to_x.size(); ++k) {
    const auto p = dem_.crs_of(col_to_x[k], row_to_y[k]);
    col_to_x[k] = p[0];
    row_to_y[k] = p[1];
  }
  crs_.to_wgs84(col_to_x, row_to_y);
  for (std::size_t k = 0; k < col_to_x.size(); ++k) {
    const auto p = frame_.to_enu({row_to_y[k], col_to_x[k]});
    col_to_x[k] = p[0];
    row_to_y[k] = p[1];
  }
}

void Terrain::enu_to_samples(std::span<double> x_to_col, std::span<double> y_to_row) const {
  for (std::size_t k = 0; k < x_to_col.size(); ++k) {
    const LatLon p = frame_.to_lat_lon(x_to_col[k], y_to_row[k]);
    x_to_col[k] = p.lon;
    y_to_row[k] = p.lat;
  }
  crs_.from_wgs84(x_to_col, y_to_row);
  for (std::size_t k = 0; k < x_to_col.size(); ++k) {
    if (std::isnan(x_to_col[k])) continue;
    const auto s = dem_.sample_of(x_to_col[k], y_to_row[k]);
    x_to_col[k] = s[0];
    y_to_row[k] = s[1];
  }
}

}  // namespace wangscape
