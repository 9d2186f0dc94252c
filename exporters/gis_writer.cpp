#include "exporters/gis_writer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace wangscape {

namespace {

// The file's CRS: the DEM's, or WGS 84 longitude and latitude.
GisCrs gis_crs(const Terrain& terrain, GisCrsChoice choice) {
  if (choice == GisCrsChoice::wgs84) return GisCrs{"", true};
  return GisCrs{terrain.dem().crs_wkt, terrain.dem().geographic};
}

const Terrain& terrain_of(const Scene& scene) {
  const Terrain* terrain = scene.field ? scene.field->ground.terrain() : nullptr;
  if (terrain == nullptr)
    throw Error("scene '" + scene.name +
                "': [exports] gis needs a DEM ([terrain] dem): a flat ground has no coordinate reference system");
  return *terrain;
}

// A model's name without its variant number: "sunflower_3" -> "sunflower".
std::string model_kind(const std::string& name) {
  const auto underscore = name.find_last_of('_');
  if (underscore == std::string::npos || underscore + 1 == name.size()) return name.empty() ? "plant" : name;
  for (std::size_t k = underscore + 1; k < name.size(); ++k)
    if (name[k] < '0' || name[k] > '9') return name;
  return name.substr(0, underscore);
}

// The DEM pixel (column, row) whose centre is nearest to ENU (x, y); false off the georeference.
bool pixel_of(const Terrain& terrain, double x, double y, long long& c, long long& r) {
  double col = 0, row = 0;
  if (!terrain.map_to_sample(x, y, col, row)) {
    std::array<double, 1> xs{x}, ys{y};
    terrain.enu_to_samples(xs, ys);
    col = xs[0];
    row = ys[0];
    if (!std::isfinite(col) || !std::isfinite(row)) return false;
  }
  c = static_cast<long long>(std::floor(col + 0.5));
  r = static_cast<long long>(std::floor(row + 0.5));
  return true;
}

}  // namespace

PlantNames plant_names(const Scene& scene) {
  PlantNames names;
  const SceneField* field = scene.field.get();
  if (field && field->species) {
    names.species = field->species->names();
  } else {
    names.species = {model_kind(scene.models.empty() ? std::string() : scene.models.front().name)};
  }
  const std::size_t proxy_offset = field ? field->proxy_offset : 0;
  for (std::size_t v = 0; v < scene.models.size(); ++v) {
    const std::size_t model = proxy_offset && v >= proxy_offset ? v - proxy_offset : v;
    const auto species = field ? field->species_of_model(v) : std::nullopt;
    names.species_of_variant.push_back(static_cast<std::uint16_t>(species.value_or(0)));
    names.written_variant.push_back(static_cast<std::uint16_t>(model));
  }
  return names;
}

PlantNames plant_names(const FilledTileSet& filled) {
  PlantNames names;
  const std::size_t classes = std::max<std::size_t>(filled.classes.size(), 1);
  for (std::size_t c = 0; c < classes; ++c) names.species.push_back(std::to_string(c));
  for (int v = 0; v < filled.variants; ++v) {
    names.species_of_variant.push_back(static_cast<std::uint16_t>(class_of_variant(filled, v).value_or(0)));
    names.written_variant.push_back(static_cast<std::uint16_t>(v));
  }
  return names;
}

// ---------------------------------------------------------------------------------------
// PlantPointWriter

PlantPointWriter::PlantPointWriter(const Terrain& terrain, const std::filesystem::path& path, GisVectorFormat format,
                                   GisCrsChoice crs, PlantNames names)
    : terrain_(terrain),
      path_(path),
      crs_(crs),
      names_(std::move(names)),
      file_(path, format, gis_crs(terrain, crs), names_.species) {}

void PlantPointWriter::write(const InstanceBatch& b) {
  const std::size_t n = b.size();
  x_.resize(n);
  y_.resize(n);
  species_.resize(n);
  variant_.resize(n);
  std::size_t exact = 0;  // points off the lattice (none on a DEM's own ground): converted exactly below
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint16_t v = b.variant[k];
    if (v >= names_.species_of_variant.size())
      throw Error(path_, "",
                  "a plant of variant " + std::to_string(v) + " but only " +
                      std::to_string(names_.species_of_variant.size()) + " variants are named");
    species_[k] = names_.species_of_variant[v];
    variant_[k] = names_.written_variant[v];
    if (crs_ == GisCrsChoice::wgs84) {
      const LatLon p = terrain_.frame().to_lat_lon(b.x[k], b.y[k]);
      x_[k] = p.lon;
      y_[k] = p.lat;
      continue;
    }
    double col = 0, row = 0;
    if (terrain_.map_to_sample(b.x[k], b.y[k], col, row)) {
      const auto crs = terrain_.dem().crs_of(col, row);
      x_[k] = crs[0];
      y_[k] = crs[1];
    } else {
      x_[k] = std::numeric_limits<double>::quiet_NaN();
      ++exact;
    }
  }
  if (exact != 0) {
    for (std::size_t k = 0; k < n; ++k) {
      if (!std::isnan(x_[k])) continue;
      std::array<double, 1> col{b.x[k]}, row{b.y[k]};
      terrain_.enu_to_samples(col, row);
      if (!std::isfinite(col[0]) || !std::isfinite(row[0]))
        throw Error(path_, "",
                    "a plant at ENU (" + std::to_string(b.x[k]) + ", " + std::to_string(b.y[k]) +
                        ") m has no place in the DEM's coordinate reference system");
      const auto crs = terrain_.dem().crs_of(col[0], row[0]);
      x_[k] = crs[0];
      y_[k] = crs[1];
    }
  }
  file_.append(PlantColumns{x_, y_, species_, variant_, b.scale, b.yaw, b.z, b.rank});
}

void PlantPointWriter::commit() { file_.commit(); }

// ---------------------------------------------------------------------------------------
// PlantCover

PlantCover::PlantCover(const Terrain& terrain, const Extent& area) : terrain_(terrain) {
  const DemRaster& dem = terrain.dem();
  // The area's outline in DEM samples: its bounding box, a cell more on each side.
  constexpr int kSteps = 32;
  std::vector<double> cols, rows;
  for (int k = 0; k <= kSteps; ++k) {
    const double t = double(k) / kSteps;
    const double x = area.min_x + t * area.width(), y = area.min_y + t * area.height();
    for (const auto& [px, py] :
         {std::pair{x, area.min_y}, std::pair{x, area.max_y}, std::pair{area.min_x, y}, std::pair{area.max_x, y}}) {
      cols.push_back(px);
      rows.push_back(py);
    }
  }
  terrain.enu_to_samples(cols, rows);
  double lo_c = std::numeric_limits<double>::infinity(), hi_c = -lo_c, lo_r = lo_c, hi_r = -lo_c;
  for (std::size_t k = 0; k < cols.size(); ++k) {
    if (!std::isfinite(cols[k]) || !std::isfinite(rows[k])) continue;
    lo_c = std::min(lo_c, cols[k]);
    hi_c = std::max(hi_c, cols[k]);
    lo_r = std::min(lo_r, rows[k]);
    hi_r = std::max(hi_r, rows[k]);
  }
  if (!(lo_c <= hi_c && lo_r <= hi_r)) {  // no point of the outline transforms: the whole DEM
    lo_c = lo_r = 0;
    hi_c = dem.width - 1;
    hi_r = dem.height - 1;
  }
  const auto clamp_to = [](double v, int n) { return static_cast<int>(std::clamp(v, 0.0, double(n - 1))); };
  c0_ = clamp_to(std::floor(lo_c + 0.5) - 1, dem.width);
  r0_ = clamp_to(std::floor(lo_r + 0.5) - 1, dem.height);
  width_ = clamp_to(std::floor(hi_c + 0.5) + 1, dem.width) - c0_ + 1;
  height_ = clamp_to(std::floor(hi_r + 0.5) + 1, dem.height) - r0_ + 1;
  counts_.assign(std::size_t(width_) * std::size_t(height_), 0);
}

void PlantCover::add(const InstanceBatch& b) {
  for (std::size_t k = 0; k < b.size(); ++k) {
    long long c = 0, r = 0;
    if (!pixel_of(terrain_, b.x[k], b.y[k], c, r) || c < c0_ || r < r0_ || c >= c0_ + width_ || r >= r0_ + height_)
      throw Error("cover: a plant at ENU (" + std::to_string(b.x[k]) + ", " + std::to_string(b.y[k]) +
                  ") m lies outside the field's DEM cells (columns " + std::to_string(c0_) + " to " +
                  std::to_string(c0_ + width_ - 1) + ", rows " + std::to_string(r0_) + " to " +
                  std::to_string(r0_ + height_ - 1) + ")");
    ++counts_[std::size_t(r - r0_) * std::size_t(width_) + std::size_t(c - c0_)];
  }
  count_ += b.size();
}

GisGrid PlantCover::grid() const {
  const DemRaster& dem = terrain_.dem();
  // The bounding box of the cells holding plants, in the counted window.
  int lo_c = width_, hi_c = -1, lo_r = height_, hi_r = -1;
  for (int r = 0; r < height_; ++r)
    for (int c = 0; c < width_; ++c)
      if (counts_[std::size_t(r) * std::size_t(width_) + std::size_t(c)] != 0) {
        lo_c = std::min(lo_c, c);
        hi_c = std::max(hi_c, c);
        lo_r = std::min(lo_r, r);
        hi_r = std::max(hi_r, r);
      }
  if (hi_c < 0) lo_c = hi_c = lo_r = hi_r = 0;  // no plant: one empty cell
  GisGrid grid;
  grid.crs = GisCrs{dem.crs_wkt, dem.geographic};
  grid.width = hi_c - lo_c + 1;
  grid.height = hi_r - lo_r + 1;
  const auto& t = dem.transform;
  const double c = c0_ + lo_c, r = r0_ + lo_r;  // the DEM pixel of the grid's first one
  grid.transform = {t[0] + c * t[1] + r * t[2], t[1], t[2], t[3] + c * t[4] + r * t[5], t[4], t[5]};
  grid.values.resize(std::size_t(grid.width) * std::size_t(grid.height));
  for (int gr = 0; gr < grid.height; ++gr) {
    const double area = dem_cell_area_m2(dem, r0_ + lo_r + gr);
    for (int gc = 0; gc < grid.width; ++gc) {
      const std::uint32_t n = counts_[std::size_t(lo_r + gr) * std::size_t(width_) + std::size_t(lo_c + gc)];
      grid.values[std::size_t(gr) * std::size_t(grid.width) + std::size_t(gc)] = static_cast<float>(n / area);
    }
  }
  grid.description = "plants per square metre";
  return grid;
}

// ---------------------------------------------------------------------------------------
// GisWriter

GisWriter::GisWriter(const Scene& scene, const std::filesystem::path& plants, const std::filesystem::path& cover,
                     GisCrsChoice crs)
    : cover_path_(cover) {
  const Terrain& terrain = terrain_of(scene);
  points_ = std::make_unique<PlantPointWriter>(terrain, plants, GisVectorFormat::geopackage, crs, plant_names(scene));
  // Plants stand in the tiles that meet the field's area: a tile more on each side.
  Extent area = scene.field_area;
  const double tile = scene.field->placement.tile_size;
  area = {area.min_x - tile, area.min_y - tile, area.max_x + tile, area.max_y + tile};
  cover_ = std::make_unique<PlantCover>(terrain, area);
}

void GisWriter::append(const InstanceBatch& batch) {
  points_->write(batch);
  cover_->add(batch);
}

void GisWriter::finish(const StreamTotals&) {
  points_->commit();
  write_geotiff(cover_path_, cover_->grid());
}

}  // namespace wangscape
