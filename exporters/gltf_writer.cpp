#include "exporters/gltf_writer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/atomic_file.h"
#include "core/binary_file.h"
#include "core/json_text.h"
#include "core/vecmath.h"
#include "exporters/export_support.h"
#include "exporters/image_io.h"

namespace wangscape {

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");

namespace {

using Json = nlohmann::ordered_json;
using Vec3f = std::array<float, 3>;

constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

// ENU (east, north, up) -> glTF (x, y, z) = (east, up, -north): a proper rotation, so
// winding and handedness are kept.
Vec3f to_gltf(const std::array<float, 3>& enu) { return {enu[0], enu[2], -enu[1]}; }
std::array<double, 3> to_gltf(const std::array<double, 3>& enu) { return {enu[0], enu[2], -enu[1]}; }

Vec3f unit_gltf_normal(const std::array<float, 3>& enu) {
  const auto n = to_gltf(enu);
  const double length = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
  if (!(length > 1e-12)) return {0, 1, 0};  // degenerate normals point up rather than fail validation
  return {float(n[0] / length), float(n[1] / length), float(n[2] / length)};
}

// Rotation about glTF +y (= ENU up) by yaw (radians, counter-clockwise seen from above), as
// a unit quaternion (x, y, z, w).
std::array<float, 4> yaw_quaternion(float yaw) {
  const double half = 0.5 * double(yaw);
  return {0.0f, float(std::sin(half)), 0.0f, float(std::cos(half))};
}

// A flower's rotation: its yaw, then with the scene's wind its lean at time 0, as the still of
// every other engine has it (scene/wind.h): about east (glTF +x) by -north, then about north
// (glTF -z) by east. Quaternions (x, y, z, w), composed in double.
std::array<float, 4> flower_rotation(float yaw, const std::optional<WindField>& wind, double east, double north) {
  if (!wind) return yaw_quaternion(yaw);
  using Q = std::array<double, 4>;
  const auto about = [](double x, double y, double z, double radians) {
    const double s = std::sin(0.5 * radians);
    return Q{x * s, y * s, z * s, std::cos(0.5 * radians)};
  };
  const auto times = [](const Q& a, const Q& b) {
    return Q{
        a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1], a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
        a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3], a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
  };
  constexpr double kRadiansPerDegree = std::numbers::pi / 180;
  const WindLean lean = wind->lean(east, north, 0);
  const Q q =
      times(times(about(0, 0, -1, lean.east * kRadiansPerDegree), about(1, 0, 0, -lean.north * kRadiansPerDegree)),
            about(0, 1, 0, double(yaw)));
  return {float(q[0]), float(q[1]), float(q[2]), float(q[3])};
}

// The binary chunk's static part (meshes) plus the glTF objects describing it.
class GltfBuilder {
 public:
  Json buffer_views = Json::array();
  Json accessors = Json::array();
  std::string bin;

  // Appends bytes as a new buffer view (4-byte aligned); returns its index.
  int add_view(const void* data, std::size_t size, int target) {
    const std::size_t offset = bin.size();
    bin.append(static_cast<const char*>(data), size);
    bin.resize((bin.size() + 3) & ~std::size_t(3), '\0');
    return add_view_at(offset, size, target);
  }

  int add_view_at(std::uint64_t offset, std::uint64_t size, int target) {
    Json view{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}};
    if (target) view["target"] = target;
    buffer_views.push_back(view);
    return int(buffer_views.size()) - 1;
  }

  int add_accessor(int view, int component_type, std::uint64_t count, const char* type, const Json& min = nullptr,
                   const Json& max = nullptr) {
    Json accessor{{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}};
    if (!min.is_null()) accessor["min"] = min;
    if (!max.is_null()) accessor["max"] = max;
    accessors.push_back(accessor);
    return int(accessors.size()) - 1;
  }

  int add_vec3(const std::vector<Vec3f>& values, int target, bool with_bounds) {
    const int view = add_view(values.data(), values.size() * sizeof(Vec3f), target);
    if (!with_bounds) return add_accessor(view, kFloat, values.size(), "VEC3");
    const Bounds3f bounds = bounds_of(values);
    return add_accessor(view, kFloat, values.size(), "VEC3", bounds.min, bounds.max);
  }

  // A glTF mesh for `mesh`: shared POSITION/NORMAL (and TEXCOORD_0 when `texture` is given:
  // the ENU rectangle an image is stretched over, north at the image's top), one primitive
  // per material used.
  Json add_mesh(const Mesh& mesh, const std::vector<std::uint32_t>& material_slots, const Extent* texture = nullptr) {
    std::vector<Vec3f> positions, normals;
    positions.reserve(mesh.vertex_count());
    normals.reserve(mesh.vertex_count());
    for (const auto& p : mesh.positions) positions.push_back(to_gltf(p));
    for (const auto& n : mesh.normals) normals.push_back(unit_gltf_normal(n));
    const int position = add_vec3(positions, kArrayBuffer, true);
    const int normal = add_vec3(normals, kArrayBuffer, false);
    Json attributes{{"POSITION", position}, {"NORMAL", normal}};
    if (texture) {
      std::vector<std::array<float, 2>> uv;
      uv.reserve(mesh.vertex_count());
      for (const auto& p : mesh.positions)
        uv.push_back(
            {float((p[0] - texture->min_x) / texture->width()), float((texture->max_y - p[1]) / texture->height())});
      const int view = add_view(uv.data(), uv.size() * sizeof(uv[0]), kArrayBuffer);
      attributes["TEXCOORD_0"] = add_accessor(view, kFloat, uv.size(), "VEC2");
    } else if (mesh.uvs.size() == mesh.positions.size()) {
      // A model's own uvs; glTF's v runs down the image, Wangscape's up.
      std::vector<std::array<float, 2>> uv;
      uv.reserve(mesh.uvs.size());
      for (const auto& t : mesh.uvs) uv.push_back({t[0], 1.0f - t[1]});
      const int view = add_view(uv.data(), uv.size() * sizeof(uv[0]), kArrayBuffer);
      attributes["TEXCOORD_0"] = add_accessor(view, kFloat, uv.size(), "VEC2");
    }

    Json primitives = Json::array();
    for (std::size_t slot = 0; slot < material_slots.size(); ++slot) {
      std::vector<std::uint32_t> indices;
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const std::size_t material = mesh.triangle_material.empty() ? 0 : mesh.triangle_material[t];
        if (material == slot) indices.insert(indices.end(), mesh.triangles[t].begin(), mesh.triangles[t].end());
      }
      if (indices.empty()) continue;
      const int view = add_view(indices.data(), indices.size() * sizeof(std::uint32_t), kElementArrayBuffer);
      primitives.push_back(Json{{"attributes", attributes},
                                {"indices", add_accessor(view, kUnsignedInt, indices.size(), "SCALAR")},
                                {"material", material_slots[slot]},
                                {"mode", 4}});
    }
    if (primitives.empty()) throw Error("mesh '" + mesh.name + "' has no triangles: glTF meshes cannot be empty");
    return Json{{"name", mesh.name}, {"primitives", primitives}};
  }
};

// Per-variant instance attributes streamed to temporary files beside the output.
class InstanceSpill {
 public:
  InstanceSpill(const std::filesystem::path& output, std::size_t variants, std::optional<WindField> wind)
      : wind_(std::move(wind)) {
    for (std::size_t v = 0; v < variants; ++v) {
      auto& files = variants_.emplace_back();
      for (int a = 0; a < 3; ++a) {
        static constexpr std::array<const char*, 3> names = {"translation", "rotation", "scale"};
        files.paths[a] = std::make_unique<AtomicPath>(
            output.parent_path() / (output.filename().string() + ".v" + std::to_string(v) + "." + names[a]));
        files.streams[a].open(files.paths[a]->temp_path(), std::ios::binary | std::ios::trunc);
        if (!files.streams[a]) throw Error("cannot write '" + output.string() + "': cannot create a temporary file");
      }
    }
  }

  void append(const InstanceBatch& batch) {
    for (std::size_t i = 0; i < batch.size(); ++i) {
      Variant& v = variants_[batch.variant[i]];
      const Vec3f t = to_gltf(std::array<float, 3>{batch.x[i], batch.y[i], batch.z[i]});
      const auto r = flower_rotation(batch.yaw[i], wind_, batch.x[i], batch.y[i]);
      const Vec3f s = {batch.scale[i], batch.scale[i], batch.scale[i]};
      v.streams[0].write(reinterpret_cast<const char*>(t.data()), sizeof t);
      v.streams[1].write(reinterpret_cast<const char*>(r.data()), sizeof r);
      v.streams[2].write(reinterpret_cast<const char*>(s.data()), sizeof s);
      v.bounds.extend(t);
      ++v.count;
    }
  }

  void close(const std::filesystem::path& output) {
    for (auto& v : variants_) {
      for (auto& stream : v.streams) {
        stream.close();
        if (stream.fail()) throw Error("cannot write '" + output.string() + "': temporary file write failed");
      }
    }
  }

  struct Variant {
    std::array<std::unique_ptr<AtomicPath>, 3> paths;  // removed when done (never committed)
    std::array<std::ofstream, 3> streams;
    Bounds3f bounds;
    std::uint64_t count = 0;
  };
  std::vector<Variant> variants_;
  std::optional<WindField> wind_;
};

void copy_file_into(std::ostream& out, const std::filesystem::path& path, const std::filesystem::path& output) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), std::streamsize(buffer.size()));
    out.write(buffer.data(), in.gcount());
  }
  if (!in.eof()) throw Error("cannot write '" + output.string() + "': cannot read back a temporary file");
}

// Camera node: glTF cameras look down -z with +y up; yfov is vertical.
Json camera_node(const Camera& camera, const RenderSettings& render, Json& cameras) {
  const double aspect = render.height > 0 ? double(render.width) / render.height : 1.0;
  const double hfov = camera.fov_degrees * 3.14159265358979323846 / 180.0;
  cameras.push_back(Json{{"type", "perspective"},
                         {"perspective",
                          {{"aspectRatio", aspect},
                           {"yfov", 2.0 * std::atan(std::tan(hfov / 2) / aspect)},
                           {"znear", 0.05},
                           {"zfar", 100000.0}}}});
  const auto position = to_gltf(camera.position);
  const auto target = to_gltf(camera.target);
  std::array<double, 3> f{target[0] - position[0], target[1] - position[1], target[2] - position[2]};
  const auto normalize = [](const Vector3d& v) { return length(v) > 0 ? normalized(v) : v; };
  f = normalize(f);
  std::array<double, 3> up{0, 1, 0};
  if (std::abs(f[1]) > 0.999999) up = {0, 0, -1};  // looking straight down: north is up
  const auto r = normalize(cross(f, up));
  const auto u = cross(r, f);
  // Rotation matrix columns: camera x = r, y = u, z = -f.
  const double m00 = r[0], m01 = u[0], m02 = -f[0];
  const double m10 = r[1], m11 = u[1], m12 = -f[1];
  const double m20 = r[2], m21 = u[2], m22 = -f[2];
  std::array<double, 4> q{};  // x, y, z, w
  const double trace = m00 + m11 + m22;
  if (trace > 0) {
    const double s = 0.5 / std::sqrt(trace + 1.0);
    q = {(m21 - m12) * s, (m02 - m20) * s, (m10 - m01) * s, 0.25 / s};
  } else if (m00 > m11 && m00 > m22) {
    const double s = 2.0 * std::sqrt(1.0 + m00 - m11 - m22);
    q = {0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s};
  } else if (m11 > m22) {
    const double s = 2.0 * std::sqrt(1.0 + m11 - m00 - m22);
    q = {(m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s};
  } else {
    const double s = 2.0 * std::sqrt(1.0 + m22 - m00 - m11);
    q = {(m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s};
  }
  return Json{{"name", "camera"}, {"camera", cameras.size() - 1}, {"translation", position}, {"rotation", q}};
}

// The materials: model materials are thin (petals, leaves), so double-sided.
Json material_list(const MaterialTable& table) {
  std::vector<bool> double_sided(table.materials.size(), false);
  for (const auto& slots : table.model_slots) {
    for (const auto slot : slots) double_sided[slot] = true;
  }
  Json materials = Json::array();
  for (std::size_t i = 0; i < table.materials.size(); ++i) {
    const Material& m = table.materials[i];
    materials.push_back(Json{{"name", m.name},
                             {"pbrMetallicRoughness",
                              {{"baseColorFactor", {m.base_color[0], m.base_color[1], m.base_color[2], 1.0f}},
                               {"metallicFactor", 0.0},
                               {"roughnessFactor", m.roughness}}},
                             {"doubleSided", bool(double_sided[i])},
                             {"extras", {{"translucency", m.translucency}}}});
  }
  return materials;
}

// The baked ground as the glTF image, sampler and texture of the terrain's materials (all null
// without a baked ground).
struct GroundImage {
  Json images, textures, samplers;
};

// The models' images (material_textures' PNGs, already in buffer views `views`, -1 for none) as
// images and textures of their materials, with alphaMode MASK where a material is a cutout
// (the PNG's alpha is 0 or 255 already, so any cutoff between cuts the same).
void add_material_images(const MaterialTable& table, const std::vector<int>& views, GroundImage& images,
                         Json& materials) {
  std::optional<std::size_t> sampler;  // repeated, linear: made with the first image
  for (std::size_t m = 0; m < views.size(); ++m) {
    if (views[m] < 0) continue;
    if (images.images.is_null()) images = GroundImage{Json::array(), Json::array(), Json::array()};
    if (!sampler) {
      images.samplers.push_back(Json{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}});
      sampler = images.samplers.size() - 1;
    }
    images.images.push_back(
        Json{{"name", table.materials[m].name}, {"bufferView", views[m]}, {"mimeType", "image/png"}});
    images.textures.push_back(Json{{"sampler", *sampler}, {"source", images.images.size() - 1}});
    auto& material = materials[m];
    material["pbrMetallicRoughness"]["baseColorTexture"] = Json{{"index", images.textures.size() - 1}};
    material["pbrMetallicRoughness"]["baseColorFactor"] = {1.0, 1.0, 1.0, 1.0};  // in the texels
    if (table.materials[m].alpha_cutoff > 0) {
      material["alphaMode"] = "MASK";
      material["alphaCutoff"] = 0.5;
    }
  }
}

GroundImage ground_image(int image_view, const MaterialTable& table, Json& materials) {
  GroundImage ground;
  if (image_view < 0) return ground;
  ground.images = Json::array({Json{{"name", "ground"}, {"bufferView", image_view}, {"mimeType", "image/png"}}});
  // Linear magnification, trilinear minification, clamped: the image covers the terrain once.
  ground.samplers = Json::array({Json{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 33071}, {"wrapT", 33071}}});
  ground.textures = Json::array({Json{{"sampler", 0}, {"source", 0}}});
  for (const auto slot : table.terrain_slots) {
    auto& pbr = materials[slot]["pbrMetallicRoughness"];
    pbr["baseColorTexture"] = Json{{"index", 0}};
    pbr["baseColorFactor"] = {1.0, 1.0, 1.0, 1.0};
  }
  return ground;
}

}  // namespace

struct GltfWriter::Impl {
  Impl(const Scene& s, const std::filesystem::path& p, const GltfOptions& o)
      : scene(s), path(p), options(o), table(build_material_table(s)) {}

  // finish(), step by step: the instanced nodes, the camera, the JSON document, the .glb file.
  void add_instanced_nodes();
  void add_camera(Json& cameras);
  Json document(std::uint64_t count, Json cameras, Json materials, GroundImage ground, std::uint64_t bin_size) const;
  std::uint64_t write_glb(std::string json, std::uint64_t bin_size) const;

  const Scene& scene;
  std::filesystem::path path;
  GltfOptions options;
  MaterialTable table;
  GltfBuilder builder{};
  Json meshes = Json::array();
  Json nodes = Json::array();
  Json root_children = Json::array();
  std::size_t first_model_mesh = 0;
  int ground_image_view = -1;               // buffer view of the baked ground PNG, -1 without one
  std::vector<int> material_image_views{};  // per material of the table: its PNG's view, or -1
  std::unique_ptr<InstanceSpill> spill{};
  std::vector<std::uint64_t> per_variant{};
  GltfSummary summary{};
};

GltfWriter::GltfWriter(const Scene& scene, const std::filesystem::path& path, const GltfOptions& options)
    : impl_(std::make_unique<Impl>(scene, path, options)) {
  if (!path.parent_path().empty()) {
    std::error_code error;
    std::filesystem::create_directories(path.parent_path(), error);
  }
  if (scene.terrain.vertex_count() > 0) check_mesh(scene.terrain, "terrain mesh '" + scene.terrain.name + "'");
  for (const Mesh& model : scene.models) check_mesh(model, "model mesh '" + model.name + "'");
  Impl& impl = *impl_;
  impl.nodes.push_back(Json{{"name", scene.name}});  // root, children filled at finish()
  if (scene.terrain.vertex_count() > 0) {
    const Extent* texture = scene.ground_texture ? &scene.ground_texture->extent : nullptr;
    impl.meshes.push_back(impl.builder.add_mesh(scene.terrain, impl.table.terrain_slots, texture));
    if (texture) {
      // The baked ground (the same pixels POV-Ray and Blender get), embedded as a PNG.
      const auto ground = encoded_ground(scene, impl.options.ground);
      impl.ground_image_view = impl.builder.add_view(ground->png().data(), ground->png().size(), 0);
    }
    impl.nodes.push_back(Json{{"name", "terrain"}, {"mesh", impl.meshes.size() - 1}});
    impl.root_children.push_back(impl.nodes.size() - 1);
  }
  for (const MaterialTexture& texture : material_textures(impl.table))
    impl.material_image_views.push_back(
        texture.file.empty() ? -1 : impl.builder.add_view(texture.png.data(), texture.png.size(), 0));
  impl.first_model_mesh = impl.meshes.size();
  for (std::size_t m = 0; m < scene.models.size(); ++m)
    impl.meshes.push_back(impl.builder.add_mesh(scene.models[m], impl.table.model_slots[m]));
  impl.per_variant.assign(scene.models.size(), 0);
  if (options.instancing == GltfInstancing::gpu_instancing)
    impl.spill = std::make_unique<InstanceSpill>(path, scene.models.size(), scene.wind);
}

GltfWriter::~GltfWriter() = default;

void GltfWriter::append(const InstanceBatch& batch) {
  Impl& impl = *impl_;
  if (impl.spill) {
    impl.spill->append(batch);
    return;
  }
  for (std::size_t i = 0; i < batch.size(); ++i) {
    const float s = batch.scale[i];
    impl.nodes.push_back(Json{{"mesh", impl.first_model_mesh + batch.variant[i]},
                              {"translation", to_gltf(std::array<float, 3>{batch.x[i], batch.y[i], batch.z[i]})},
                              {"rotation", flower_rotation(batch.yaw[i], impl.scene.wind, batch.x[i], batch.y[i])},
                              {"scale", {s, s, s}}});
    impl.root_children.push_back(impl.nodes.size() - 1);
    ++impl.per_variant[batch.variant[i]];
  }
}

// With GPU instancing, one node per variant whose instances are the spilled attributes: the
// accessors point into the binary chunk after the meshes, where write_glb() copies the files.
void GltfWriter::Impl::add_instanced_nodes() {
  spill->close(path);
  std::uint64_t offset = builder.bin.size();
  for (std::size_t v = 0; v < scene.models.size(); ++v) {
    const auto& variant = spill->variants_[v];
    per_variant[v] = variant.count;
    if (variant.count == 0) continue;  // accessors cannot be empty
    const std::uint64_t n = variant.count;
    const int translation = builder.add_accessor(builder.add_view_at(offset, n * 12, 0), kFloat, n, "VEC3",
                                                 variant.bounds.min, variant.bounds.max);
    const int rotation = builder.add_accessor(builder.add_view_at(offset + n * 12, n * 16, 0), kFloat, n, "VEC4");
    const int scale = builder.add_accessor(builder.add_view_at(offset + n * 28, n * 12, 0), kFloat, n, "VEC3");
    offset += n * 40;
    nodes.push_back(
        Json{{"name", scene.models[v].name + " instances"},
             {"mesh", first_model_mesh + v},
             {"extensions",
              {{"EXT_mesh_gpu_instancing",
                {{"attributes", {{"TRANSLATION", translation}, {"ROTATION", rotation}, {"SCALE", scale}}}}}}}});
    root_children.push_back(nodes.size() - 1);
  }
}

// The camera node, the last child of the root, which gets its children here.
void GltfWriter::Impl::add_camera(Json& cameras) {
  nodes.push_back(camera_node(scene.camera, scene.render, cameras));
  root_children.push_back(nodes.size() - 1);
  nodes[0]["children"] = root_children;
}

// The glTF JSON: asset, the scene with its extras (georeference, counts, sun), nodes, cameras,
// meshes, materials, the ground image, accessors, views and the one buffer.
Json GltfWriter::Impl::document(std::uint64_t count, Json cameras, Json materials, GroundImage ground,
                                std::uint64_t bin_size) const {
  Json georeference = Json::object();
  for (const auto& [key, value] : scene.georeference) georeference[key] = value;

  Json gltf;
  gltf["asset"] = Json{{"version", "2.0"}, {"generator", "wangscape"}};
  if (options.instancing == GltfInstancing::gpu_instancing && count > 0) {
    gltf["extensionsUsed"] = Json::array({"EXT_mesh_gpu_instancing"});
  }
  gltf["scene"] = 0;
  gltf["scenes"] = Json::array({Json{
      {"name", scene.name},
      {"nodes", {0}},
      {"extras",
       {{"georeference", georeference},
        {"coordinates", "glTF y-up: x = east, y = up, z = -north (meters)"},
        {"instance_count", count},
        {"instances_per_variant", per_variant},
        {"sun",
         {{"azimuth_degrees", scene.sun.azimuth_degrees}, {"elevation_degrees", scene.sun.elevation_degrees}}}}}}});
  gltf["nodes"] = nodes;
  gltf["cameras"] = cameras;
  if (!meshes.empty()) gltf["meshes"] = meshes;
  if (!materials.empty()) gltf["materials"] = materials;
  if (!ground.images.is_null()) {
    gltf["images"] = ground.images;
    gltf["samplers"] = ground.samplers;
    gltf["textures"] = ground.textures;
  }
  if (!builder.accessors.empty()) gltf["accessors"] = builder.accessors;
  if (!builder.buffer_views.empty()) gltf["bufferViews"] = builder.buffer_views;
  if (bin_size > 0) gltf["buffers"] = Json::array({Json{{"byteLength", bin_size}}});
  return gltf;
}

// The .glb: header, the JSON chunk padded with spaces, the binary chunk (meshes, the ground PNG,
// then the spilled instance files). Returns the file's size; refuses files over glTF's 4 GiB.
std::uint64_t GltfWriter::Impl::write_glb(std::string json, std::uint64_t bin_size) const {
  json.resize((json.size() + 3) & ~std::size_t(3), ' ');
  const std::uint64_t total = 12 + 8 + json.size() + (bin_size > 0 ? 8 + bin_size : 0);
  if (total > 0xffffffffull) {
    throw Error("cannot write '" + path.string() + "': " + std::to_string(total) +
                " bytes exceed glTF's 4 GiB limit; export fewer instances");
  }

  AtomicFile out(path);
  auto& stream = out.stream();
  stream.write("glTF", 4);
  put_u32(stream, 2);
  put_u32(stream, std::uint32_t(total));
  put_u32(stream, std::uint32_t(json.size()));
  stream.write("JSON", 4);
  stream.write(json.data(), std::streamsize(json.size()));
  if (bin_size > 0) {
    put_u32(stream, std::uint32_t(bin_size));
    stream.write("BIN\0", 4);
    stream.write(builder.bin.data(), std::streamsize(builder.bin.size()));
    if (spill) {
      for (const auto& variant : spill->variants_) {
        for (const auto& file : variant.paths) copy_file_into(stream, file->temp_path(), path);
      }
    }
  }
  out.commit();
  return total;
}

void GltfWriter::finish(const StreamTotals& totals) {
  Impl& impl = *impl_;
  const std::uint64_t count = totals.instances;
  if (impl.spill) impl.add_instanced_nodes();
  Json cameras = Json::array();
  impl.add_camera(cameras);
  Json materials = material_list(impl.table);
  GroundImage ground = ground_image(impl.ground_image_view, impl.table, materials);
  add_material_images(impl.table, impl.material_image_views, ground, materials);
  const std::uint64_t instance_bytes = impl.options.instancing == GltfInstancing::gpu_instancing ? count * 40 : 0;
  const std::uint64_t bin_size = impl.builder.bin.size() + instance_bytes;
  const Json gltf = impl.document(count, std::move(cameras), std::move(materials), std::move(ground), bin_size);
  const std::uint64_t total = impl.write_glb(json_text(gltf), bin_size);
  impl.spill.reset();  // its temporary files go now, before the folder they are in is published
  impl.summary = GltfSummary{impl.path, count, total};
}

const GltfSummary& GltfWriter::summary() const { return impl_->summary; }

GltfSummary write_gltf(const Scene& scene, const std::filesystem::path& path, const GltfOptions& options) {
  GltfWriter writer(scene, path, options);
  run_scene_stream(scene, writer);
  return writer.summary();
}

}  // namespace wangscape
