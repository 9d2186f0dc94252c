#include "cli/scene_pipeline.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>

#include "cli/scene_ground.h"
#include "exporters/atomic_file.h"
#include "exporters/povray_writer.h"
#include "generator/placement.h"
#include "generator/poisson_tiles.h"
#include "generator/tiling.h"
#include "templates/mesh_io.h"
#include "templates/sunflower.h"

namespace wangscape::cli {

namespace {

namespace fs = std::filesystem;

void say(const PipelineObserver& observer, const std::string& message) {
  if (observer.stage) observer.stage(message);
}

// ---- models ---------------------------------------------------------------------------------

void scale_mesh(Mesh& mesh, double factor) {
  if (factor == 1.0) return;
  for (auto& p : mesh.positions)
    for (auto& c : p) c = static_cast<float>(c * factor);
}

std::vector<Mesh> make_models(const ModelsConfig& config) {
  std::vector<Mesh> models;
  if (!config.mesh.empty()) {
    models.push_back(load_mesh(config.mesh));
    if (models.back().name.empty()) models.back().name = config.mesh.filename().string();
  } else {
    SunflowerOptions options;
    options.variant_count = config.variants;
    options.seed = config.seed;
    options.triangle_budget = config.triangle_budget;
    for (auto& model : make_sunflower_variants(options)) models.push_back(std::move(model.mesh));
  }
  for (auto& mesh : models) scale_mesh(mesh, config.scale);
  return models;
}

// ---- the field: tiles laid over the ground, flowers where the masks allow -------------------

struct Field {
  SceneGround ground;
  FilledTileSet filled;
  PlacementOptions placement;
  std::optional<double> facing_yaw;  // radians, counter-clockwise from east; empty = the tile's yaw
  double facing_jitter = 0;          // radians

  // The configured facing, spread over +- jitter by the point's own uniform yaw (so it stays a
  // function of the point's identity).
  float yaw_of(float point_yaw) const {
    const double u = point_yaw / (2 * std::numbers::pi);
    return float(*facing_yaw + (2 * u - 1) * facing_jitter);
  }

  void place(const std::function<void(const InstanceBatch&)>& sink) const {
    if (!facing_yaw) {
      ground.place(filled, placement, sink);
      return;
    }
    InstanceBatch turned;
    ground.place(filled, placement, [&](const InstanceBatch& batch) {
      turned = batch;
      for (auto& yaw : turned.yaw) yaw = yaw_of(yaw);
      sink(turned);
    });
  }
};

std::shared_ptr<const Field> make_field(const SceneConfig& config, const SceneGround& ground, std::size_t model_count) {
  auto field = std::make_shared<Field>();
  field->ground = ground;
  Extent area = ground.extent();
  if (config.tiles.area) {
    const auto& a = *config.tiles.area;
    area = {std::max(area.min_x, a[0]), std::max(area.min_y, a[1]), std::min(area.max_x, a[2]),
            std::min(area.max_y, a[3])};
    if (!(area.width() > 0 && area.height() > 0))
      throw Error(config.source.string() + ": tiles.area does not overlap the ground (" + ground.description() + ")");
  }
  const double tile_size = config.tiles.tile_size;
  const double tiles_x = std::ceil(area.width() / tile_size) + 1, tiles_y = std::ceil(area.height() / tile_size) + 1;
  const double estimate = tiles_x * tiles_y * config.tiles.points_per_tile;
  constexpr double kMaxInstances = 50e6;
  if (estimate > kMaxInstances)
    throw Error(config.source.string() + ": the field would hold up to " + std::to_string(std::llround(estimate)) +
                " flowers (" + std::to_string(std::llround(tiles_x)) + " x " + std::to_string(std::llround(tiles_y)) +
                " tiles); limit it with tiles.area or a larger tiles.tile_size (at most 50 million)");
  field->placement.tile_size = tile_size;
  field->placement.algorithm = parse_tiling_algorithm(config.tiles.algorithm);
  field->placement.seed = config.tiles.seed;
  field->placement.area = area;

  PoissonFillOptions fill;
  fill.points_per_tile = config.tiles.points_per_tile;
  fill.seed = config.tiles.seed;
  fill.relax_rounds = config.tiles.relaxation_rounds;
  fill.variants = int(std::max<std::size_t>(1, model_count));
  fill.min_scale = 1.0 - config.models.scale_jitter;
  fill.max_scale = 1.0 + config.models.scale_jitter;
  field->filled = fill_poisson_tiles(builtin_tileset(config.tiles.set), fill);
  if (config.models.facing) {
    // Compass (clockwise from north) to yaw (counter-clockwise from east).
    field->facing_yaw = (90.0 - *config.models.facing) * std::numbers::pi / 180;
    field->facing_jitter = config.models.facing_jitter * std::numbers::pi / 180;
  }
  return field;
}

// ---- camera and sun -----------------------------------------------------------------------------

std::array<double, 3> resolve_point(const CameraPoint& point, const SceneGround& ground, const SceneConfig& config,
                                    const std::string& key, const std::array<double, 3>& fallback) {
  if (point.enu) return *point.enu;
  std::array<double, 2> xy{fallback[0], fallback[1]};
  if (point.enu_ground) {
    xy = *point.enu_ground;
  } else if (point.latitude) {
    xy = ground.to_enu(*point.latitude, *point.longitude);
  } else {
    return fallback;
  }
  const auto h = ground.height(xy[0], xy[1]);
  if (!h)
    throw Error(config.source.string() + ": camera." + key + " (east " + std::to_string(xy[0]) + " m, north " +
                std::to_string(xy[1]) + " m) is not over the ground (" + ground.description() + ")");
  return {xy[0], xy[1], *h + point.height_above_ground};
}

Camera make_camera(const SceneConfig& config, const SceneGround& ground, const Extent& field) {
  const auto& c = config.camera;
  // Defaults: stand at the middle of the field's southern edge, look north across it.
  const double cx = (field.min_x + field.max_x) / 2, cy = field.min_y + 1.0;
  std::array<double, 3> default_position{cx, cy, ground.height(cx, cy).value_or(0) + c.position.height_above_ground};
  Camera camera;
  camera.fov_degrees = c.fov;
  camera.position = resolve_point(c.position, ground, config, "position", default_position);
  if (c.heading) {
    const double heading = *c.heading * std::numbers::pi / 180, pitch = c.pitch * std::numbers::pi / 180;
    camera.target = {camera.position[0] + 100 * std::sin(heading) * std::cos(pitch),
                     camera.position[1] + 100 * std::cos(heading) * std::cos(pitch),
                     camera.position[2] + 100 * std::sin(pitch)};
  } else {
    const double tx = (field.min_x + field.max_x) / 2, ty = (field.min_y + field.max_y) / 2;
    std::array<double, 3> default_target{tx, ty, ground.height(tx, ty).value_or(0) + c.target.height_above_ground};
    camera.target = resolve_point(c.target, ground, config, "target", default_target);
  }
  const double dx = camera.target[0] - camera.position[0], dy = camera.target[1] - camera.position[1],
               dz = camera.target[2] - camera.position[2];
  if (std::sqrt(dx * dx + dy * dy + dz * dz) < 1e-6)
    throw Error(config.source.string() + ": the camera's position and target are the same point");
  if (std::sqrt(dx * dx + dy * dy) < 1e-6)
    throw Error(config.source.string() + ": the camera looks straight up or down; move camera.target sideways");
  return camera;
}

Sun make_sun(const SceneConfig& config, const SceneGround& ground) {
  Sun sun;
  sun.strength = config.sun.strength;
  if (config.sun.time_unix) {
    const auto origin = ground.origin();
    const auto position = solar_position(origin[0], origin[1], *config.sun.time_unix);
    sun.azimuth_degrees = position.azimuth_degrees;
    sun.elevation_degrees = position.elevation_degrees;
    if (sun.elevation_degrees <= 0)
      throw Error(config.source.string() + ": sun.time " + config.sun.time_text + " is night at the origin (sun " +
                  std::to_string(sun.elevation_degrees) + " degrees below the horizon)");
  } else {
    sun.azimuth_degrees = config.sun.azimuth;
    sun.elevation_degrees = config.sun.elevation;
  }
  return sun;
}

}  // namespace

Scene make_scene(const SceneConfig& config, const PipelineObserver& observer) {
  Scene scene;
  scene.name = config.name;
  say(observer, config.terrain.dem.empty() ? "making flat ground" : "loading terrain " + config.terrain.dem.string());
  const auto ground = SceneGround::load(config.terrain, config.masks);
  scene.terrain = ground.mesh();
  scene.georeference = ground.georeference();

  say(observer, config.models.mesh.empty()
                    ? "building " + std::to_string(config.models.variants) + " sunflower variants (" +
                          std::to_string(config.models.triangle_budget) + " triangles each)"
                    : "loading model " + config.models.mesh.string());
  scene.models = make_models(config.models);

  say(observer, "filling tile set " + config.tiles.set + " with " + std::to_string(config.tiles.points_per_tile) +
                    " points per tile");
  const auto field = make_field(config, ground, scene.models.size());
  scene.instances = [field](const std::function<void(const InstanceBatch&)>& sink) { field->place(sink); };
  say(observer, "placing flowers");
  std::uint64_t count = 0;
  scene.instances([&](const InstanceBatch& batch) { count += batch.size(); });
  scene.instance_count = count;

  scene.camera = make_camera(config, ground, *field->placement.area);
  scene.sun = make_sun(config, ground);
  scene.render.width = config.image.width;
  scene.render.height = config.image.height;
  scene.render.antialias_samples = config.image.antialias;
  scene.render.threads = config.image.threads;
  scene.render.radiosity = config.image.radiosity;
  return scene;
}

SceneExporterHooks& scene_exporter_hooks() {
  static SceneExporterHooks hooks;
  return hooks;
}

namespace {
// Moves the staged files into out_dir: one rename of the whole folder when out_dir does not
// exist, else one rename per file (each atomic).
void publish(const fs::path& staging, const fs::path& out_dir) {
  std::error_code ec;
  if (!fs::exists(out_dir)) {
    fs::rename(staging, out_dir, ec);
    if (!ec) return;
    throw Error("cannot create '" + out_dir.string() + "': " + ec.message());
  }
  if (!fs::is_directory(out_dir)) throw Error("cannot write into '" + out_dir.string() + "': not a folder");
  for (const auto& entry : fs::directory_iterator(staging)) {
    fs::rename(entry.path(), out_dir / entry.path().filename(), ec);
    if (ec) throw Error("cannot write '" + (out_dir / entry.path().filename()).string() + "': " + ec.message());
  }
  fs::remove_all(staging, ec);
}
}  // namespace

BuildSummary build_scene_folder(const SceneConfig& config, const fs::path& out_dir_in,
                                const PipelineObserver& observer) {
  const auto start = std::chrono::steady_clock::now();
  const auto& hooks = scene_exporter_hooks();
  if (config.exports.blender && !hooks.blender)
    throw Error(config.source.string() + ": exports.blender = true, but this wangscape has no Blender exporter");
  if (config.exports.gltf && !hooks.gltf)
    throw Error(config.source.string() + ": exports.gltf = true, but this wangscape has no glTF exporter");

  const Scene scene = make_scene(config, observer);
  BuildSummary summary;
  summary.instances = scene.instance_count;

  auto out_dir = fs::absolute(out_dir_in).lexically_normal();
  if (out_dir.filename().empty()) out_dir = out_dir.parent_path();
  std::error_code ec;
  fs::create_directories(out_dir.parent_path(), ec);
  const fs::path staging =
      out_dir.parent_path() / ("." + out_dir.filename().string() + ".partial-" + std::to_string(::getpid()));
  fs::remove_all(staging, ec);
  if (!fs::create_directory(staging, ec) || ec)
    throw Error("cannot create '" + staging.string() + "' beside the output folder: " + ec.message());
  try {
    if (config.exports.povray) {
      say(observer, "writing POV-Ray scene (" + std::to_string(scene.instance_count) + " flowers)");
      PovrayExportOptions options;
      options.final_dir = out_dir;
      if (observer.instances_written)
        options.on_instances = [&](std::uint64_t done) { observer.instances_written(done, scene.instance_count); };
      summary.bytes = write_povray_scene(scene, staging, options).total_bytes;
    }
    if (config.exports.blender) {
      say(observer, "writing Blender scene");
      hooks.blender(scene, config, staging, out_dir);
    }
    if (config.exports.gltf) {
      say(observer, "writing glTF scene");
      hooks.gltf(scene, config, staging, out_dir);
    }
    write_file_atomically(staging / "scene.toml", config.text);
    publish(staging, out_dir);
  } catch (...) {
    fs::remove_all(staging, ec);
    throw;
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace wangscape::cli
