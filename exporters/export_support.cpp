#include "exporters/export_support.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <mutex>
#include <set>

#include <GeographicLib/UTMUPS.hpp>

#include "core/atomic_file.h"
#include "core/color.h"
#include "core/number_text.h"
#include "exporters/image_io.h"
#include "scene/shading_light.h"

namespace wangscape {

Bounds3f bounds_of(std::span<const std::array<float, 3>> points) {
  Bounds3f bounds;
  for (const auto& p : points) bounds.extend(p);
  return bounds;
}

// The plain ground of the one shading model, so every engine shows the same one.
Material default_ground_material() { return Material{"ground", ShadingSettings{}.ground_color, 0.9f, 0.0f}; }

namespace {

bool same_material(const Material& a, const Material& b) {
  return a.name == b.name && a.base_color == b.base_color && a.roughness == b.roughness &&
         a.translucency == b.translucency && a.base_color_map == b.base_color_map && a.alpha_cutoff == b.alpha_cutoff;
}

std::vector<std::uint32_t> add_materials(std::vector<Material>& table, const std::vector<Material>& materials) {
  std::vector<std::uint32_t> slots;
  for (const Material& material : materials) {
    auto found =
        std::find_if(table.begin(), table.end(), [&](const Material& m) { return same_material(m, material); });
    if (found == table.end()) found = table.insert(table.end(), material);
    slots.push_back(static_cast<std::uint32_t>(found - table.begin()));
  }
  return slots;
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

bool is_number(const std::string& text) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

const std::string* find_value(const Georeference& georeference, const std::string& key) {
  for (const auto& [k, v] : georeference) {
    if (k == key) return &v;
  }
  return nullptr;
}

bool has_key(const std::vector<std::pair<std::string, std::string>>& properties, const std::string& key) {
  return std::any_of(properties.begin(), properties.end(), [&](const auto& p) { return p.first == key; });
}

// terrain/georef.h georeferences name the origin's UTM zone rather than an SRID: the scene
// then sits in WGS 84 / UTM (EPSG:326zz north, 327zz south) with the origin's easting and
// northing as BlenderGIS's "crs x"/"crs y". (ENU and the UTM grid differ by the meridian
// convergence the georeference also records; BlenderGIS assumes aligned axes.)
void add_utm_properties(const Georeference& georeference,
                        std::vector<std::pair<std::string, std::string>>& properties) {
  const std::string* zone_text = find_value(georeference, "utm_zone");
  const std::string* hemisphere = find_value(georeference, "utm_hemisphere");
  const std::string* latitude = find_value(georeference, "origin_latitude_deg");
  const std::string* longitude = find_value(georeference, "origin_longitude_deg");
  if (!zone_text || !hemisphere || !latitude || !longitude || has_key(properties, "SRID")) return;
  if (!is_number(*zone_text) || !is_number(*latitude) || !is_number(*longitude)) return;
  const int zone = std::stoi(*zone_text);
  if (zone < 1 || zone > 60) return;  // UPS (polar) zones have no EPSG UTM code
  const bool north = lowercase(*hemisphere) == "north";
  double x = 0, y = 0, gamma = 0, k = 0;
  int zone_used = 0;
  bool north_used = north;
  try {
    GeographicLib::UTMUPS::Forward(std::stod(*latitude), std::stod(*longitude), zone_used, north_used, x, y, gamma, k,
                                   zone);
  } catch (const std::exception&) {
    return;
  }
  // UTMUPS::Forward uses the false northing of the point's own hemisphere; follow the zone's.
  if (north_used != north) y += north ? -10000000.0 : 10000000.0;
  properties.insert(properties.begin(), {"SRID", "EPSG:" + std::to_string((north ? 32600 : 32700) + zone)});
  if (!has_key(properties, "crs x")) properties.emplace_back("crs x", number_text(x));
  if (!has_key(properties, "crs y")) properties.emplace_back("crs y", number_text(y));
}

}  // namespace

MaterialTable build_material_table(const Scene& scene) {
  MaterialTable table;
  if (scene.terrain.vertex_count() > 0) {
    table.terrain_slots = add_materials(table.materials, scene.terrain.materials.empty()
                                                             ? std::vector<Material>{default_ground_material()}
                                                             : scene.terrain.materials);
  }
  for (const Mesh& model : scene.models) {
    table.model_slots.push_back(add_materials(
        table.materials, model.materials.empty() ? std::vector<Material>{Material{"default"}} : model.materials));
  }
  return table;
}

std::vector<MaterialTexture> material_textures(const MaterialTable& table) {
  std::vector<MaterialTexture> textures(table.materials.size());
  std::set<std::string> taken;
  for (std::size_t m = 0; m < table.materials.size(); ++m) {
    const Material& material = table.materials[m];
    if (!material.base_color_map) continue;
    const TextureImage& image = *material.base_color_map;
    std::vector<std::uint8_t> rgba = image.rgba;
    const bool cutout = material.alpha_cutoff > 0;
    for (std::size_t i = 0; i + 3 < rgba.size(); i += 4) {
      for (std::size_t c = 0; c < 3; ++c)
        if (material.base_color[c] != 1.0f)
          rgba[i + c] = linear_to_srgb8(srgb8_to_linear(rgba[i + c]) * material.base_color[c]);
      rgba[i + 3] = !cutout || float(rgba[i + 3]) / 255.0f >= material.alpha_cutoff ? 255 : 0;
    }
    std::string name = "map_" + image.name;
    for (int k = 2; taken.contains(name); ++k) name = "map_" + image.name + "_" + std::to_string(k);
    taken.insert(name);
    textures[m] = {name + ".png", encode_png(image.width, image.height, 4, rgba)};
  }
  return textures;
}

void check_mesh(const Mesh& mesh, const std::string& what) {
  if (mesh.normals.size() != mesh.positions.size()) {
    throw Error(what + ": " + std::to_string(mesh.normals.size()) + " normals for " +
                std::to_string(mesh.positions.size()) + " positions (expected one per position)");
  }
  if (!mesh.triangle_material.empty() && mesh.triangle_material.size() != mesh.triangles.size()) {
    throw Error(what + ": " + std::to_string(mesh.triangle_material.size()) + " triangle materials for " +
                std::to_string(mesh.triangles.size()) + " triangles");
  }
  const auto vertex_count = mesh.positions.size();
  for (const auto& triangle : mesh.triangles) {
    for (const std::uint32_t index : triangle) {
      if (index >= vertex_count) {
        throw Error(what + ": triangle index " + std::to_string(index) + " outside its " +
                    std::to_string(vertex_count) + " vertices");
      }
    }
  }
  const std::size_t material_count = std::max<std::size_t>(1, mesh.materials.size());
  for (const std::uint16_t slot : mesh.triangle_material) {
    if (slot >= material_count) {
      throw Error(what + ": triangle material " + std::to_string(slot) + " but only " + std::to_string(material_count) +
                  " materials");
    }
  }
}

std::vector<std::pair<std::string, std::string>> blendergis_properties(const Georeference& georeference) {
  // BlenderGIS key -> georeference keys that carry it (lowercase), first match wins.
  static const std::vector<std::pair<std::string, std::vector<std::string>>> aliases = {
      {"SRID", {"srid", "epsg", "crs_epsg", "crs_srid", "crs"}},
      {"crs x", {"crs x", "crs_x", "origin_easting", "origin_x", "easting"}},
      {"crs y", {"crs y", "crs_y", "origin_northing", "origin_y", "northing"}},
      {"latitude", {"latitude", "origin_latitude", "origin_latitude_deg", "lat"}},
      {"longitude", {"longitude", "origin_longitude", "origin_longitude_deg", "lon"}},
  };
  std::vector<std::pair<std::string, std::string>> properties;
  for (const auto& [blendergis_key, names] : aliases) {
    for (const std::string& name : names) {
      const auto found = std::find_if(georeference.begin(), georeference.end(),
                                      [&](const auto& pair) { return lowercase(pair.first) == name; });
      if (found == georeference.end()) continue;
      std::string value = found->second;
      if (blendergis_key == "SRID") {
        // BlenderGIS wants "EPSG:nnnn"; accept a bare code too. A WKT is no SRID.
        if (is_number(value)) value = "EPSG:" + value;
        if (lowercase(value).rfind("epsg:", 0) != 0) continue;
        value = "EPSG:" + value.substr(5);
      } else if (!is_number(value)) {
        continue;
      }
      properties.emplace_back(blendergis_key, value);
      break;
    }
  }
  add_utm_properties(georeference, properties);
  return properties;
}

const std::string& EncodedGround::png() const {
  std::call_once(encoded_, [this] { png_ = encode_png(bake_->image); });
  return png_;
}

std::shared_ptr<const EncodedGround> encoded_ground(const Scene& scene, std::shared_ptr<const EncodedGround> given) {
  return given ? std::move(given) : std::make_shared<const EncodedGround>(scene.ground_texture);
}

}  // namespace wangscape
