#include "cli/scene_ground.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <variant>

#include "terrain/terrain.h"

namespace wangscape::cli {

struct SceneGround::Impl {
  std::optional<Terrain> terrain;  // empty: flat ground
  FlatGround flat;
  Extent area;                    // after the crop
  std::optional<EnuFrame> frame;  // flat ground: around the configured origin
  std::string description;
};

namespace {
Extent intersect(Extent a, const std::optional<std::array<double, 4>>& crop) {
  if (!crop) return a;
  return {std::max(a.min_x, (*crop)[0]), std::max(a.min_y, (*crop)[1]), std::min(a.max_x, (*crop)[2]),
          std::min(a.max_y, (*crop)[3])};
}

std::string number(double value) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(10);
  out << value;
  return out.str();
}
}  // namespace

SceneGround SceneGround::load(const TerrainConfig& config) {
  auto impl = std::make_shared<Impl>();
  if (!config.dem.empty()) {
    TerrainOptions options;
    if (config.origin_latitude) options.origin = LatLon{*config.origin_latitude, *config.origin_longitude};
    impl->terrain.emplace(Terrain::load(config.dem, options));
    const auto r = impl->terrain->extent();
    impl->area = intersect({r.min_x, r.min_y, r.max_x, r.max_y}, config.crop);
    const auto& dem = impl->terrain->dem();
    const auto spacing = impl->terrain->spacing_m();
    std::ostringstream d;
    d << config.dem.filename().string() << " (" << dem.width << " x " << dem.height << " samples, "
      << std::lround(spacing[0]) << " m)";
    impl->description = d.str();
  } else {
    const double half = config.flat_size / 2;
    impl->flat = FlatGround{{-half, -half, half, half}, 0.0};
    impl->area = intersect(impl->flat.area, config.crop);
    impl->flat.area = impl->area;
    impl->frame.emplace(LatLon{config.origin_latitude.value_or(0.0), config.origin_longitude.value_or(0.0)});
    impl->description = "flat ground " + number(impl->area.width()) + " x " + number(impl->area.height()) + " m";
  }
  if (!(impl->area.width() > 0 && impl->area.height() > 0))
    throw SceneConfigError("terrain.crop [" + number((*config.crop)[0]) + ", " + number((*config.crop)[1]) + ", " +
                           number((*config.crop)[2]) + ", " + number((*config.crop)[3]) +
                           "] does not overlap the ground (" + impl->description + ")");
  SceneGround ground;
  ground.impl_ = std::move(impl);
  return ground;
}

Extent SceneGround::extent() const { return impl_->area; }

std::optional<double> SceneGround::height(double x, double y) const {
  if (!impl_->area.contains(x, y)) return std::nullopt;
  return impl_->terrain ? impl_->terrain->height(x, y) : impl_->flat.height(x, y);
}

std::optional<double> SceneGround::slope_degrees(double x, double y) const {
  if (!impl_->area.contains(x, y)) return std::nullopt;
  return impl_->terrain ? impl_->terrain->slope_degrees(x, y) : impl_->flat.slope_degrees(x, y);
}

std::array<double, 2> SceneGround::to_enu(double latitude, double longitude) const {
  const auto& frame = impl_->terrain ? impl_->terrain->frame() : *impl_->frame;
  return frame.to_enu({latitude, longitude});
}

std::array<double, 2> SceneGround::origin() const {
  const auto& frame = impl_->terrain ? impl_->terrain->frame() : *impl_->frame;
  return {frame.origin().lat, frame.origin().lon};
}

Mesh SceneGround::mesh(int max_vertices_per_side) const {
  const Extent area = impl_->area;
  double step = 10.0;
  if (impl_->terrain) {
    const auto spacing = impl_->terrain->spacing_m();
    step = std::min(spacing[0], spacing[1]);
  } else {
    step = std::max(area.width(), area.height()) / 16.0;
  }
  step = std::max(step, std::max(area.width(), area.height()) / double(max_vertices_per_side - 1));
  const int nx = std::max(2, int(std::ceil(area.width() / step)) + 1);
  const int ny = std::max(2, int(std::ceil(area.height() / step)) + 1);
  const double dx = area.width() / (nx - 1), dy = area.height() / (ny - 1);

  Mesh mesh;
  mesh.name = "terrain";
  mesh.materials = {{"ground", {0.2f, 0.18f, 0.12f}, 0.9f, 0.0f}};
  constexpr std::uint32_t kNone = ~0u;
  std::vector<std::uint32_t> index(std::size_t(nx) * std::size_t(ny), kNone);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      // Pull the border a hair inwards so edge samples fall inside the DEM.
      const double x = std::clamp(area.min_x + i * dx, area.min_x + 1e-6, area.max_x - 1e-6);
      const double y = std::clamp(area.min_y + j * dy, area.min_y + 1e-6, area.max_y - 1e-6);
      const auto h = height(x, y);
      if (!h) continue;
      // Normal from central differences of the heights (smooth across cells).
      const auto hx0 = height(x - dx, y), hx1 = height(x + dx, y), hy0 = height(x, y - dy), hy1 = height(x, y + dy);
      const double gx = (hx1 && hx0) ? (*hx1 - *hx0) / (2 * dx) : hx1 ? (*hx1 - *h) / dx : hx0 ? (*h - *hx0) / dx : 0;
      const double gy = (hy1 && hy0) ? (*hy1 - *hy0) / (2 * dy) : hy1 ? (*hy1 - *h) / dy : hy0 ? (*h - *hy0) / dy : 0;
      const double len = std::sqrt(gx * gx + gy * gy + 1);
      index[std::size_t(j) * std::size_t(nx) + std::size_t(i)] = std::uint32_t(mesh.positions.size());
      mesh.positions.push_back({float(x), float(y), float(*h)});
      mesh.normals.push_back({float(-gx / len), float(-gy / len), float(1 / len)});
    }
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const auto at = [&](int a, int b) { return index[std::size_t(b) * std::size_t(nx) + std::size_t(a)]; };
      const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i, j + 1), d = at(i + 1, j + 1);
      // Counter-clockwise seen from above (+z).
      if (a != kNone && b != kNone && d != kNone) mesh.triangles.push_back({a, b, d});
      if (a != kNone && d != kNone && c != kNone) mesh.triangles.push_back({a, d, c});
    }
  mesh.triangle_material.assign(mesh.triangles.size(), 0);
  return mesh;
}

std::vector<std::pair<std::string, std::string>> SceneGround::georeference() const {
  std::vector<std::pair<std::string, std::string>> out;
  if (impl_->terrain) {
    for (const auto& field : georeference_fields(impl_->terrain->georeference())) {
      std::string value = std::visit(
          [](const auto& v) -> std::string {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, std::string>) {
              return v;
            } else if constexpr (std::is_same_v<T, bool>) {
              return v ? "true" : "false";
            } else {
              return number(double(v));
            }
          },
          field.value);
      out.emplace_back(field.key, std::move(value));
    }
    out.emplace_back("dem", impl_->terrain->dem().path.filename().string());
  } else {
    out.emplace_back("frame", "flat ground, local east-north-up");
    out.emplace_back("origin_latitude", number(impl_->frame->origin().lat));
    out.emplace_back("origin_longitude", number(impl_->frame->origin().lon));
    out.emplace_back("units", "metre");
  }
  const auto& a = impl_->area;
  out.emplace_back("extent_enu_m",
                   number(a.min_x) + " " + number(a.min_y) + " " + number(a.max_x) + " " + number(a.max_y));
  return out;
}

std::string SceneGround::description() const { return impl_->description; }

}  // namespace wangscape::cli
