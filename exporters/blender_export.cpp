#include "exporters/blender_export.h"

#include <algorithm>
#include <array>
#include <bit>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/json_text.h"
#include "exporters/export_support.h"
#include "exporters/image_io.h"
#include "exporters/zip_writer.h"
#include "scene/shading_light.h"
#include "templates/blender_addon.h"

namespace wangscape {

static_assert(std::endian::native == std::endian::little,
              "the Blender arrays are little-endian and written as they lie in memory");

namespace {

using Json = nlohmann::ordered_json;

template <typename T>
constexpr std::string_view dtype_name() {
  if constexpr (std::is_same_v<T, float>) return "float32";
  if constexpr (std::is_same_v<T, std::uint32_t>) return "uint32";
  if constexpr (std::is_same_v<T, std::uint16_t>) return "uint16";
}

template <typename T>
void write_values(std::ofstream& stream, std::span<const T> values) {
  stream.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size_bytes()));
}

// Writes the flat array `values` (count elements of `components` values each) to
// folder/file and returns its manifest entry.
template <typename T>
Json write_array(const std::filesystem::path& folder, const std::string& file, std::span<const T> values,
                 std::size_t components, std::uint64_t& bytes) {
  AtomicFile out(folder / file);
  write_values(out.stream(), values);
  out.commit();
  bytes += values.size_bytes();
  return Json{
      {"file", file}, {"dtype", dtype_name<T>()}, {"components", components}, {"count", values.size() / components}};
}

Json bounds_json(const Bounds3f& bounds) {
  if (bounds.empty()) return nullptr;
  return Json{{"min", bounds.min}, {"max", bounds.max}};
}

// One mesh as four arrays: positions, normals (float32 xyz), indices (uint32 x3) and the
// material slot of each triangle (uint16).
Json write_mesh(const Mesh& mesh, const std::string& prefix, const std::vector<std::uint32_t>& slots,
                const std::filesystem::path& folder, std::uint64_t& bytes) {
  check_mesh(mesh, "mesh '" + mesh.name + "'");
  const auto flat_floats = [](const std::vector<std::array<float, 3>>& v) {
    return std::span<const float>(v.empty() ? nullptr : v.front().data(), v.size() * 3);
  };
  std::vector<std::uint16_t> triangle_slots = mesh.triangle_material;
  triangle_slots.resize(mesh.triangles.size(), 0);  // absent: material 0 everywhere

  Json entry;
  entry["name"] = mesh.name;
  entry["vertex_count"] = mesh.vertex_count();
  entry["triangle_count"] = mesh.triangle_count();
  entry["positions"] = write_array(folder, prefix + "_positions.f32", flat_floats(mesh.positions), 3, bytes);
  entry["normals"] = write_array(folder, prefix + "_normals.f32", flat_floats(mesh.normals), 3, bytes);
  entry["indices"] =
      write_array(folder, prefix + "_indices.u32",
                  std::span<const std::uint32_t>(mesh.triangles.empty() ? nullptr : mesh.triangles.front().data(),
                                                 mesh.triangles.size() * 3),
                  3, bytes);
  entry["material_indices"] =
      write_array(folder, prefix + "_materials.u16", std::span<const std::uint16_t>(triangle_slots), 1, bytes);
  entry["material_slots"] = slots;
  if (mesh.uvs.size() == mesh.positions.size() && !mesh.uvs.empty())  // a model's own, v up
    entry["uvs"] = write_array(folder, prefix + "_uvs.f32",
                               std::span<const float>(mesh.uvs.front().data(), mesh.uvs.size() * 2), 2, bytes);
  entry["bounds"] = bounds_json(bounds_of(mesh.positions));
  return entry;
}

// The instance arrays, one file per attribute, filled batch by batch from the stream.
class InstanceArrays {
 public:
  explicit InstanceArrays(const std::filesystem::path& folder) {
    for (std::size_t i = 0; i < kFiles.size(); ++i) files_[i] = std::make_unique<AtomicFile>(folder / kFiles[i]);
  }

  void append(const InstanceBatch& batch) {
    write_values(files_[0]->stream(), std::span<const float>(batch.x));
    write_values(files_[1]->stream(), std::span<const float>(batch.y));
    write_values(files_[2]->stream(), std::span<const float>(batch.z));
    write_values(files_[3]->stream(), std::span<const float>(batch.yaw));
    write_values(files_[4]->stream(), std::span<const float>(batch.scale));
    write_values(files_[5]->stream(), std::span<const std::uint16_t>(batch.variant));
    for (std::size_t i = 0; i < batch.size(); ++i) {
      bounds_.extend({batch.x[i], batch.y[i], batch.z[i]});
      if (batch.variant[i] >= per_variant_.size()) per_variant_.resize(batch.variant[i] + 1, 0);
      ++per_variant_[batch.variant[i]];
    }
  }

  Json commit(std::uint64_t count, std::size_t model_count, std::uint64_t& bytes) {
    for (auto& file : files_) file->commit();
    per_variant_.resize(std::max(per_variant_.size(), model_count), 0);
    bytes += count * (5 * sizeof(float) + sizeof(std::uint16_t));
    Json entry;
    entry["count"] = count;
    entry["per_variant"] = per_variant_;
    entry["bounds"] = bounds_json(bounds_);
    static constexpr std::array<const char*, 6> names = {"x", "y", "z", "yaw", "scale", "variant"};
    for (std::size_t i = 0; i < names.size(); ++i) {
      entry[names[i]] =
          Json{{"file", kFiles[i]}, {"dtype", i < 5 ? "float32" : "uint16"}, {"components", 1}, {"count", count}};
    }
    return entry;
  }

 private:
  static constexpr std::array<const char*, 6> kFiles = {"instances_x.f32",     "instances_y.f32",
                                                        "instances_z.f32",     "instances_yaw.f32",
                                                        "instances_scale.f32", "instances_variant.u16"};
  std::array<std::unique_ptr<AtomicFile>, 6> files_;
  Bounds3f bounds_;
  std::vector<std::uint64_t> per_variant_;
};

Json material_json(const Material& material) {
  return Json{{"name", material.name},
              {"base_color", material.base_color},
              {"roughness", material.roughness},
              {"translucency", material.translucency}};
}

}  // namespace

int blender_cycles_samples(const RenderSettings& render, const BlenderExportOptions& options) {
  if (options.cycles_samples > 0) return options.cycles_samples;
  return 16 * std::max(1, render.antialias_samples);
}

struct BlenderWriter::Impl {
  Impl(const Scene& s, const std::filesystem::path& f, const BlenderExportOptions& o)
      : scene(s), folder(f), options(o) {}
  const Scene& scene;
  std::filesystem::path folder;
  BlenderExportOptions options;
  std::uint64_t bytes = 0;
  Json files = Json::array();
  Json terrain = nullptr;
  Json ground_texture = nullptr;  // {"file", "extent": [min_x, min_y, max_x, max_y]} or null
  Json models = Json::array();
  std::vector<MaterialTexture> textures{};  // per material of the table (PNG bytes dropped once written)
  std::unique_ptr<InstanceArrays> arrays{};
  BlenderExportSummary summary{};

  void list_files(const Json& mesh_entry) {
    for (const char* key : {"positions", "normals", "indices", "material_indices", "uvs"})
      if (mesh_entry.contains(key)) files.push_back(mesh_entry[key]["file"]);
  }
};

BlenderWriter::BlenderWriter(const Scene& scene, const std::filesystem::path& folder,
                             const BlenderExportOptions& options)
    : impl_(std::make_unique<Impl>(scene, folder, options)) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) throw Error("cannot create Blender export folder '" + folder.string() + "': " + error.message());
  Impl& impl = *impl_;
  const MaterialTable table = build_material_table(scene);
  if (scene.terrain.vertex_count() > 0) {
    impl.terrain = write_mesh(scene.terrain, "terrain", table.terrain_slots, folder, impl.bytes);
    impl.list_files(impl.terrain);
    if (scene.ground_texture) {
      // The scene's baked [ground] look; the add-on maps it over `extent` by vertex position.
      const Extent& e = scene.ground_texture->extent;
      write_file_atomically(folder / "ground.png", encoded_ground(scene, impl.options.ground)->png());
      impl.bytes += std::filesystem::file_size(folder / "ground.png", error);
      impl.ground_texture = Json{{"file", "ground.png"}, {"extent", {e.min_x, e.min_y, e.max_x, e.max_y}}};
      impl.files.push_back("ground.png");
    }
  }
  // The models' images: the add-on maps them through each model's uvs.
  impl.textures = material_textures(table);
  for (MaterialTexture& texture : impl.textures) {
    if (texture.file.empty()) continue;
    write_file_atomically(folder / texture.file, texture.png);
    impl.bytes += texture.png.size();
    impl.files.push_back(texture.file);
    texture.png.clear();
  }
  for (std::size_t i = 0; i < scene.models.size(); ++i) {
    char prefix[32];
    std::snprintf(prefix, sizeof prefix, "model_%04zu", i);
    impl.models.push_back(write_mesh(scene.models[i], prefix, table.model_slots[i], folder, impl.bytes));
    // [[species]]: the model's species (the add-on gives every instance a species attribute).
    if (const auto species = scene.field ? scene.field->species_of_model(i) : std::nullopt)
      impl.models.back()["species"] = *species;
    impl.list_files(impl.models.back());
  }
  impl.arrays = std::make_unique<InstanceArrays>(folder);
}

BlenderWriter::~BlenderWriter() = default;

void BlenderWriter::append(const InstanceBatch& batch) { impl_->arrays->append(batch); }

void BlenderWriter::finish(const StreamTotals& totals) {
  Impl& impl = *impl_;
  const Scene& scene = impl.scene;
  const auto& options = impl.options;
  const MaterialTable table = build_material_table(scene);
  const std::uint64_t count = totals.instances;
  Json instances = impl.arrays->commit(count, scene.models.size(), impl.bytes);
  for (const char* key : {"x", "y", "z", "yaw", "scale", "variant"}) impl.files.push_back(instances[key]["file"]);

  Json manifest;
  manifest["format"] = Json{{"name", kBlenderFormatName}, {"version", kBlenderFormatVersion}};
  manifest["scene"] = scene.name;
  manifest["byte_order"] = "little";
  manifest["coordinates"] = "ENU meters: x east, y north, z up";
  manifest["counts"] = Json{{"terrain_vertices", scene.terrain.vertex_count()},
                            {"terrain_triangles", scene.terrain.triangle_count()},
                            {"models", scene.models.size()},
                            {"materials", table.materials.size()},
                            {"instances", count}};
  manifest["files"] = impl.files;
  manifest["materials"] = Json::array();
  for (std::size_t m = 0; m < table.materials.size(); ++m) {
    Json material = material_json(table.materials[m]);
    if (m < impl.textures.size() && !impl.textures[m].file.empty()) {
      // The image's texels already hold the base colour and a 0-or-255 alpha (material_textures).
      material["image"] = impl.textures[m].file;
      material["alpha_clip"] = table.materials[m].alpha_cutoff > 0;
    }
    manifest["materials"].push_back(material);
  }
  manifest["terrain"] = impl.terrain;
  manifest["ground_texture"] = impl.ground_texture;
  manifest["models"] = impl.models;
  if (scene.field && scene.field->species) manifest["species"] = scene.field->species->names();
  manifest["instances"] = instances;
  manifest["camera"] = Json{
      {"position", scene.camera.position}, {"target", scene.camera.target}, {"fov_degrees", scene.camera.fov_degrees}};
  manifest["sun"] = Json{{"azimuth_degrees", scene.sun.azimuth_degrees},
                         {"elevation_degrees", scene.sun.elevation_degrees},
                         {"strength", scene.sun.strength},
                         {"direction", scene.sun.direction()}};
  // The one shading model's light (scene/shading_light.h), so Cycles shows what the Embree
  // reference and the view show: linear RGB, the sun's already times its strength.
  const ShadingSettings light = with_sun(ShadingSettings{}, scene.sun);
  const SkyGradient sky = sky_gradient(light);
  manifest["light"] = Json{{"sun_color", light.sun_color},
                           {"sky_color", light.sky_color},
                           {"sky_horizon", sky.horizon},
                           {"sky_zenith", sky.zenith},
                           {"exposure", light.exposure}};
  if (scene.wind) {
    // The wind's lean (scene/wind.h), evaluated by the add-on's geometry nodes at the scene time.
    Json waves = Json::array();
    for (const WindWave& w : scene.wind->waves)
      waves.push_back(Json{{"k_east", w.k_east},
                           {"k_north", w.k_north},
                           {"k_time", w.k_time},
                           {"phase", w.phase},
                           {"amplitude_east", w.amplitude_east},
                           {"amplitude_north", w.amplitude_north}});
    manifest["wind"] =
        Json{{"base_east", scene.wind->base.east}, {"base_north", scene.wind->base.north}, {"waves", waves}};
  }
  manifest["render"] = Json{{"width", scene.render.width},
                            {"height", scene.render.height},
                            {"samples", blender_cycles_samples(scene.render, options)},
                            {"threads", scene.render.threads}};
  Json georeference = Json::object();
  for (const auto& [key, value] : scene.georeference) georeference[key] = value;
  manifest["georeference"] = georeference;
  Json blendergis = Json::object();
  for (const auto& [key, value] : blendergis_properties(scene.georeference)) {
    if (key == "SRID") {
      blendergis[key] = value;
    } else {
      blendergis[key] = std::stod(value);
    }
  }
  manifest["blendergis"] = blendergis;
  manifest["addon"] = options.write_addon_zip ? Json("wangscape_import.zip") : Json(nullptr);

  if (options.write_addon_zip) {
    const std::string zip = blender_addon_zip();
    write_file_atomically(impl.folder / "wangscape_import.zip", zip);
    impl.bytes += zip.size();
  }

  const std::string text = json_text(manifest, 2) + "\n";
  impl.summary.manifest = impl.folder / "manifest.json";
  write_file_atomically(impl.summary.manifest, text);
  impl.summary.instance_count = count;
  impl.summary.bytes_written = impl.bytes + text.size();
}

const BlenderExportSummary& BlenderWriter::summary() const { return impl_->summary; }

BlenderExportSummary export_blender(const Scene& scene, const std::filesystem::path& folder,
                                    const BlenderExportOptions& options) {
  BlenderWriter writer(scene, folder, options);
  run_scene_stream(scene, writer);
  return writer.summary();
}

}  // namespace wangscape
