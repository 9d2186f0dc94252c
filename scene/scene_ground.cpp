#include "scene/scene_ground.h"

#include <map>
#include <tuple>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <variant>

#include "scene/shading_light.h"
#include "terrain/mask.h"
#include "terrain/terrain.h"
#include "terrain/terrain_mesh.h"

namespace wangscape {

struct SceneGround::Impl {
  std::optional<Terrain> terrain;  // empty: flat ground
  FlatGround flat;
  Extent area;                    // after the crop
  std::optional<EnuFrame> frame;  // flat ground: around the configured origin
  MasksConfig masks;
  std::optional<TerrainFilter> filter;  // with a DEM
  std::string description;
};

namespace {
std::string number(double value) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(10);
  out << value;
  return out.str();
}

std::optional<double> parse_number(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  double value = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (result.ec != std::errc() || result.ptr != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}
}  // namespace

std::array<double, 2> parse_lat_lon(const std::string& text) {
  const auto comma = text.find(',');
  const auto lat = comma == std::string::npos ? std::nullopt : parse_number(std::string_view(text).substr(0, comma));
  const auto lon = comma == std::string::npos ? std::nullopt : parse_number(std::string_view(text).substr(comma + 1));
  if (!lat || !lon || std::abs(*lat) > 90 || std::abs(*lon) > 180)
    throw Error("origin '" + text + "' is not LAT,LON in WGS 84 degrees (latitude -90..90, longitude -180..180)");
  return {*lat, *lon};
}

// "WIDTHxHEIGHT" in meters, both finite and > 0.
Extent parse_plane(const std::string& text) {
  const auto x = text.find('x');
  double w = 0, h = 0;
  std::size_t used_w = 0, used_h = 0;
  try {
    if (x != std::string::npos) {
      w = std::stod(text.substr(0, x), &used_w);
      h = std::stod(text.substr(x + 1), &used_h);
    }
  } catch (const std::exception&) {
    used_w = 0;
  }
  if (x == std::string::npos || used_w != x || used_h != text.size() - x - 1 || !(w > 0) || !(h > 0) ||
      !std::isfinite(w) || !std::isfinite(h))
    throw Error("--plane '" + text + "': expected WIDTHxHEIGHT in meters, e.g. 64x64");
  return {0, 0, w, h};
}

SceneGround SceneGround::load(const TerrainConfig& config, const MasksConfig& masks,
                              const std::optional<std::array<double, 4>>& area_latlon) {
  auto impl = std::make_shared<Impl>();
  impl->masks = masks;
  const Extent crop = config.crop ? Extent{(*config.crop)[0], (*config.crop)[1], (*config.crop)[2], (*config.crop)[3]}
                                  : Extent{-INFINITY, -INFINITY, INFINITY, INFINITY};
  if (!config.dem.empty()) {
    TerrainOptions options;
    if (config.origin_latitude) options.origin = LatLon{*config.origin_latitude, *config.origin_longitude};
    impl->terrain.emplace(Terrain::load(config.dem, options));
    impl->area = impl->terrain->extent().intersected(crop);
    const auto& dem = impl->terrain->dem();
    const auto spacing = impl->terrain->spacing_m();
    std::ostringstream d;
    d << config.dem.filename().string() << " (" << dem.width << " x " << dem.height << " samples, "
      << std::lround(spacing[0]) << " m)";
    impl->description = d.str();
  } else {
    const double half = config.flat_size / 2;
    impl->area = Extent{-half, -half, half, half}.intersected(crop);
    impl->flat = FlatGround{impl->area, 0.0};
    impl->frame.emplace(LatLon{config.origin_latitude.value_or(0.0), config.origin_longitude.value_or(0.0)});
    impl->description = "flat ground " + number(impl->area.width()) + " x " + number(impl->area.height()) + " m";
  }
  if (impl->area.empty())
    throw Error("terrain.crop [" + number((*config.crop)[0]) + ", " + number((*config.crop)[1]) + ", " +
                number((*config.crop)[2]) + ", " + number((*config.crop)[3]) + "] does not overlap the ground (" +
                impl->description + ")");
  if (impl->terrain) {
    TerrainFilterOptions filter;
    filter.max_height_m = masks.max_height;
    filter.min_height_m = masks.min_height;
    filter.max_slope_deg = masks.max_slope;
    if (!masks.mask.empty()) filter.mask_image = masks.mask;
    // Each file's errors name its key; terrain/ knows files, not keys.
    const auto keyed = [](const std::string& key, const auto& make) {
      try {
        return make();
      } catch (const Error& e) {
        throw Error(e.file(), e.place(), "'" + key + "' " + e.message());
      }
    };
    const Terrain& terrain = *impl->terrain;
    if (!masks.raster.empty())
      filter.masks.push_back(keyed("masks.raster", [&] { return GroundMask::raster(masks.raster, terrain); }));
    if (!masks.polygons.empty())
      filter.masks.push_back(keyed("masks.polygons", [&] {
        return GroundMask::polygons(masks.polygons, terrain,
                                    masks.polygons_outside ? PolygonSide::outside : PolygonSide::inside,
                                    masks.polygons_buffer_m);
      }));
    if (area_latlon) {
      filter.masks.push_back(
          keyed("tiles.area_latlon", [&] { return GroundMask::lat_lon_box(*area_latlon, terrain); }));
      if (filter.masks.back().allowed_count() == 0)
        throw Error("'tiles.area_latlon' misses DEM '" + config.dem.string() +
                    "': expected a latitude/longitude rectangle over its ground");
    }
    impl->filter.emplace(*impl->terrain, filter);
    impl->filter->check_satisfiable();
  } else {
    if ((masks.max_height && *masks.max_height < 0) || (masks.min_height && *masks.min_height > 0))
      throw Error("masks: the flat ground (height 0 m) is outside the height limits");
    if (!masks.mask.empty())
      throw Error(masks.mask, "", "a painted mask needs a DEM (terrain.dem) to be stretched over");
    for (const auto& [key, file] :
         {std::pair{"masks.raster", masks.raster}, std::pair{"masks.polygons", masks.polygons}})
      if (!file.empty())
        throw Error(file, "",
                    std::string("'") + key + "' needs a DEM (terrain.dem): flat ground has no CRS to place it in");
    if (area_latlon)
      throw Error("'tiles.area_latlon' needs a DEM (terrain.dem): flat ground has no CRS to place it in");
  }
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
  const auto s = sample(x, y);
  return s ? std::optional<double>(s->slope_degrees()) : std::nullopt;
}

std::optional<std::array<double, 3>> SceneGround::normal(double x, double y) const {
  const auto s = sample(x, y);
  return s ? std::optional<std::array<double, 3>>(s->normal()) : std::nullopt;
}

std::optional<GroundSample> SceneGround::sample(double x, double y) const {
  if (!impl_->area.contains(x, y)) return std::nullopt;
  if (impl_->terrain) return impl_->terrain->sample(x, y);
  return GroundSample{impl_->flat.z, 0, 0};
}

double SceneGround::height_or_error(double x, double y) const {
  if (const auto z = height(x, y)) return *z;
  const Extent& e = impl_->area;
  const std::string at = "east " + number(x) + " m, north " + number(y) + " m";
  const std::string extent = "east " + number(std::round(e.min_x)) + " .. " + number(std::round(e.max_x)) +
                             " m, north " + number(std::round(e.min_y)) + " .. " + number(std::round(e.max_y)) + " m";
  double col = 0, row = 0;
  const Terrain* t = terrain();
  const bool on_dem = t && e.contains(x, y) && t->map_to_sample(x, y, col, row) && col >= 0 && row >= 0 &&
                      col <= t->dem().width - 1 && row <= t->dem().height - 1;
  if (on_dem)
    throw Error(impl_->description + " has no height at " + at +
                ": a corner of the DEM cell there holds the no-data value");
  if (e.contains(x, y))
    throw Error(at + " is off the grid of " + impl_->description + ": its samples span " + extent +
                ", a box the grid, turned in the scene's frame, does not fill at its corners");
  throw Error(at + " is outside " + impl_->description + ", which spans " + extent);
}

std::array<double, 2> SceneGround::to_enu(double latitude, double longitude) const {
  const auto& frame = impl_->terrain ? impl_->terrain->frame() : *impl_->frame;
  return frame.to_enu({latitude, longitude});
}

Extent SceneGround::lat_lon_box_extent(const std::array<double, 4>& box) const {
  // The box's edges sampled densely: in the tangent plane a parallel bows, so the corners alone
  // would miss its middle.
  constexpr int kSteps = 256;
  Extent e{INFINITY, INFINITY, -INFINITY, -INFINITY};
  const auto add = [&](double lat, double lon) {
    const auto p = to_enu(lat, lon);
    e = {std::min(e.min_x, p[0]), std::min(e.min_y, p[1]), std::max(e.max_x, p[0]), std::max(e.max_y, p[1])};
  };
  for (int k = 0; k <= kSteps; ++k) {
    const double t = double(k) / kSteps;
    const double lat = box[0] + t * (box[2] - box[0]), lon = box[1] + t * (box[3] - box[1]);
    add(lat, box[1]);
    add(lat, box[3]);
    add(box[0], lon);
    add(box[2], lon);
  }
  // A metre of margin for what bows between the samples; the mask keeps the rectangle exactly.
  return {e.min_x - 1, e.min_y - 1, e.max_x + 1, e.max_y + 1};
}

std::array<double, 2> SceneGround::origin() const {
  const auto& frame = impl_->terrain ? impl_->terrain->frame() : *impl_->frame;
  return {frame.origin().lat, frame.origin().lon};
}

const Terrain* SceneGround::terrain() const { return impl_->terrain ? &*impl_->terrain : nullptr; }

Mesh SceneGround::mesh(std::size_t max_vertices) const {
  const Extent area = impl_->area;
  Mesh mesh;
  mesh.name = "terrain";
  // The one shading model's plain ground, so every engine shows this one colour without [ground].
  mesh.materials = {{"ground", ShadingSettings{}.ground_color, 0.9f, 0.0f}};
  if (impl_->terrain) {
    TerrainMeshOptions options;
    options.max_vertices = max_vertices;
    options.crop = area;
    auto terrain_mesh = make_terrain_mesh(*impl_->terrain, options);
    mesh.positions = std::move(terrain_mesh.positions);
    mesh.normals = std::move(terrain_mesh.normals);
    mesh.triangles = std::move(terrain_mesh.triangles);
  } else {
    // A flat square: 4 corners, 2 triangles, counter-clockwise seen from above.
    const float z = 0.0f;
    mesh.positions = {{float(area.min_x), float(area.min_y), z},
                      {float(area.max_x), float(area.min_y), z},
                      {float(area.max_x), float(area.max_y), z},
                      {float(area.min_x), float(area.max_y), z}};
    mesh.normals.assign(4, {0.0f, 0.0f, 1.0f});
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  }
  mesh.triangle_material.assign(mesh.triangles.size(), 0);
  return mesh;
}

void SceneGround::refine_mesh(Mesh& mesh, const Extent& over, int k, std::size_t max_new_triangles) const {
  if (!impl_->terrain || k < 2) return;
  const std::size_t triangle_count = mesh.triangles.size();
  const auto meets = [&](const std::array<std::uint32_t, 3>& triangle) {
    const auto &pa = mesh.positions[triangle[0]], &pb = mesh.positions[triangle[1]], &pc = mesh.positions[triangle[2]];
    const Extent box{std::min({pa[0], pb[0], pc[0]}), std::min({pa[1], pb[1], pc[1]}), std::max({pa[0], pb[0], pc[0]}),
                     std::max({pa[1], pb[1], pc[1]})};
    return !box.intersected(over).empty();
  };
  // A field over a whole DEM would multiply its mesh by k^2: k shrinks to the budget.
  const auto refined = std::size_t(std::count_if(mesh.triangles.begin(), mesh.triangles.end(), meets));
  while (k >= 2 && refined * std::size_t(k * k) > max_new_triangles) --k;
  if (k < 2) return;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint16_t> materials;
  triangles.reserve(triangle_count);
  materials.reserve(triangle_count);
  // Vertices on original edges, by (lower vertex, higher vertex, steps from the lower one).
  std::map<std::tuple<std::uint32_t, std::uint32_t, int>, std::uint32_t> edge_vertices;
  const auto add_vertex = [&](double x, double y, double fallback_z) {
    const auto z = height(x, y);
    const auto n = normal(x, y);
    mesh.positions.push_back({float(x), float(y), float(z.value_or(fallback_z))});
    mesh.normals.push_back(n ? std::array<float, 3>{float((*n)[0]), float((*n)[1]), float((*n)[2])}
                             : std::array<float, 3>{0, 0, 1});
    return std::uint32_t(mesh.positions.size() - 1);
  };
  // The vertex `step` k-ths of the way from u to v, shared by the two triangles of the edge and
  // computed from the lower index so both get the same bits.
  const auto edge_vertex = [&](std::uint32_t u, std::uint32_t v, int step) {
    if (step == 0) return u;
    if (step == k) return v;
    if (u > v) {
      std::swap(u, v);
      step = k - step;
    }
    const auto key = std::tuple{u, v, step};
    if (const auto found = edge_vertices.find(key); found != edge_vertices.end()) return found->second;
    const auto pu = mesh.positions[u], pv = mesh.positions[v];
    const double t = double(step) / k;
    const std::uint32_t w =
        add_vertex(pu[0] + (pv[0] - pu[0]) * t, pu[1] + (pv[1] - pu[1]) * t, pu[2] + (pv[2] - pu[2]) * t);
    edge_vertices.emplace(key, w);
    return w;
  };
  std::vector<std::uint32_t> grid;
  for (std::size_t t = 0; t < triangle_count; ++t) {
    const auto [a, b, c] = mesh.triangles[t];
    const auto pa = mesh.positions[a], pb = mesh.positions[b], pc = mesh.positions[c];
    if (!meets(mesh.triangles[t])) {
      triangles.push_back(mesh.triangles[t]);
      materials.push_back(mesh.triangle_material[t]);
      continue;
    }
    // Barycentric lattice: node (i, j) = a + i/k (b - a) + j/k (c - a), i + j <= k.
    grid.assign(std::size_t(k + 1) * (k + 1), 0);
    const auto node = [&](int i, int j) -> std::uint32_t& { return grid[std::size_t(j) * (k + 1) + i]; };
    for (int j = 0; j <= k; ++j)
      for (int i = 0; i + j <= k; ++i) {
        if (j == 0)
          node(i, j) = edge_vertex(a, b, i);
        else if (i == 0)
          node(i, j) = edge_vertex(a, c, j);
        else if (i + j == k)
          node(i, j) = edge_vertex(b, c, j);
        else {
          const double wb = double(i) / k, wc = double(j) / k, wa = 1 - wb - wc;
          node(i, j) = add_vertex(wa * pa[0] + wb * pb[0] + wc * pc[0], wa * pa[1] + wb * pb[1] + wc * pc[1],
                                  wa * pa[2] + wb * pb[2] + wc * pc[2]);
        }
      }
    for (int j = 0; j < k; ++j)
      for (int i = 0; i + j < k; ++i) {
        triangles.push_back({node(i, j), node(i + 1, j), node(i, j + 1)});
        materials.push_back(mesh.triangle_material[t]);
        if (i + j + 1 < k) {
          triangles.push_back({node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
          materials.push_back(mesh.triangle_material[t]);
        }
      }
  }
  mesh.triangles = std::move(triangles);
  mesh.triangle_material = std::move(materials);
}

PlacementStats SceneGround::place(const FilledTileSet& filled, const PlacementOptions& options,
                                  const std::function<void(const InstanceBatch&)>& sink,
                                  const std::function<bool(const TileCell&)>& also, const PointRule& point_rule) const {
  const Impl& impl = *impl_;
  const auto asked = [&](const TileCell& cell) { return !also || also(cell); };
  if (point_rule) return place_by_rule(filled, options, sink, asked, point_rule);
  if (!impl.terrain)  // the plane passed the masks at load
    return place_instances(filled, *this, options, sink, asked);
  const TerrainFilter& filter = *impl.filter;
  if (impl.masks.fair_edges)
    return place_instances(
        filled, *this, options, sink,
        [&](const TileCell& cell) { return asked(cell) && filter.tile_may_pass(cell.bounds); },
        [&](double x, double y, double z) { return filter.point_passes(x, y, z); });
  // tile_passes holds for all of a tile's ground, so its points need no test of their own.
  return place_instances(
      filled, *this, options, sink,
      [&](const TileCell& cell) { return asked(cell) && filter.tile_passes(cell.bounds); }, KeepAllPoints{});
}

// place() with a rule per point (species): the masks as place() applies them, then the rule.
template <class TileTest>
PlacementStats SceneGround::place_by_rule(const FilledTileSet& filled, const PlacementOptions& options,
                                          const std::function<void(const InstanceBatch&)>& sink, const TileTest& asked,
                                          const PointRule& point_rule) const {
  const Impl& impl = *impl_;
  const TerrainFilter* filter = impl.filter ? &*impl.filter : nullptr;
  const bool fair = impl.masks.fair_edges;
  return place_instances(
      filled, *this, options, sink,
      [&](const TileCell& cell) {
        return asked(cell) &&
               (!filter || (fair ? filter->tile_may_pass(cell.bounds) : filter->tile_passes(cell.bounds)));
      },
      [&](double x, double y, double z, std::uint8_t species, float rank) {
        return (!filter || !fair || filter->point_passes(x, y, z)) && point_rule(x, y, z, species, rank);
      });
}

bool SceneGround::flowers_grow_at(double x, double y, double z, const Extent& tile) const {
  const Impl& impl = *impl_;
  if (!impl.terrain) return impl.area.contains(x, y);
  return impl.masks.fair_edges ? impl.filter->point_passes(x, y, z) : impl.filter->tile_passes(tile);
}

void SceneGround::check_tile_size(double tile_size, const std::string& what) const {
  const Extent& e = impl_->area;
  if (!(tile_size > 0) || !std::isfinite(tile_size) || tile_size > std::min(e.width(), e.height()))
    throw Error(what + " " + number(tile_size) + " m does not fit " + impl_->description + " (" +
                number(std::round(e.width())) + " x " + number(std::round(e.height())) +
                " m): expected more than 0 and at most the ground's smaller side");
}

double SceneGround::growing_share() const {
  return impl_->filter ? impl_->filter->passing_share(impl_->masks.fair_edges) : 1.0;
}

std::string SceneGround::explain_empty(double tile_size) const {
  if (impl_->masks.fair_edges)
    return "no flower of the tiling stands on ground that passes the masks (height, slope, painted mask) of " +
           impl_->description;
  return "no " + number(tile_size) + " m tile lies wholly on ground that passes the masks of " + impl_->description +
         "; smaller tiles or fair edges keep the partial ones";
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

}  // namespace wangscape
