#include "scene/scene.h"

#include <cmath>
#include <numbers>

#include "generator/tiling.h"
#include "scene/tileset_file.h"
#include "templates/mesh_io.h"
#include "templates/sunflower.h"

namespace wangscape {

namespace {

void say(const StageObserver& stage, const std::string& message) {
  if (stage) stage(message);
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// ---- models ---------------------------------------------------------------------------------

std::vector<Mesh> make_models(const ModelsConfig& config) {
  std::vector<Mesh> models;
  if (!config.mesh.empty()) {
    UserModelOptions options;
    options.scale = static_cast<float>(config.scale);
    options.y_up = config.mesh_y_up;
    options.ground_at_origin = false;  // the file's origin is the model's ground contact point
    models.push_back(load_user_model(config.mesh, options));
    if (models.back().name.empty()) models.back().name = config.mesh.filename().string();
    return models;
  }
  SunflowerOptions options;
  options.variant_count = config.variants;
  options.seed = config.seed;
  options.triangle_budget = config.triangle_budget;
  for (auto& model : make_sunflower_variants(options)) {
    if (config.scale != 1.0)
      for (auto& p : model.mesh.positions)
        for (auto& c : p) c = static_cast<float>(c * config.scale);
    models.push_back(std::move(model.mesh));
  }
  return models;
}

// ---- the field: tiles laid over the ground, flowers where the masks allow -------------------

std::shared_ptr<const SceneField> make_field(const SceneConfig& config, const SceneGround& ground,
                                             std::size_t model_count, const StageObserver& stage) {
  auto field = std::make_shared<SceneField>();
  field->ground = ground;
  Extent area = ground.extent();
  if (config.tiles.area) {
    const auto& a = *config.tiles.area;
    area = area.intersected({a[0], a[1], a[2], a[3]});
    if (area.empty()) throw config.error_at("tiles.area", "does not overlap the ground (" + ground.description() + ")");
  }
  const double tile_size = config.tiles.tile_size;
  const double tiles_x = std::ceil(area.width() / tile_size) + 1, tiles_y = std::ceil(area.height() / tile_size) + 1;
  const double estimate = tiles_x * tiles_y * config.tiles.points_per_tile;
  if (estimate > kMaxFieldInstances)
    throw config.error_at("tiles.area", "gives a field of up to " + std::to_string(std::llround(estimate)) +
                                            " flowers (" + std::to_string(std::llround(tiles_x)) + " x " +
                                            std::to_string(std::llround(tiles_y)) +
                                            " tiles); limit it with tiles.area or a larger tiles.tile_size "
                                            "(at most 50 million)");
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
  TileSet set;
  try {
    set = load_tileset(config.tiles.set);  // a built-in name, or a tile-set JSON file
  } catch (const Error& e) {
    throw config.error_at("tiles.set", e.what());
  }
  const auto fill_cost = estimate_poisson_fill(set, fill);
  say(stage, "filling tile set " + config.tiles.set + " with " + std::to_string(config.tiles.points_per_tile) +
                 " points per tile (" + std::to_string(std::llround(fill_cost.points)) + " points, about " +
                 std::to_string(std::llround(std::ceil(fill_cost.seconds))) + " s)");
  try {
    field->filled = fill_poisson_tiles(set, fill);
  } catch (const Error& e) {
    throw config.error_at("tiles.points_per_tile", e.what());
  }
  if (config.models.facing) {
    // Compass (clockwise from north) to yaw (counter-clockwise from east).
    field->facing_yaw = (90.0 - *config.models.facing) * std::numbers::pi / 180;
    field->facing_jitter = config.models.facing_jitter * std::numbers::pi / 180;
  }
  return field;
}

// ---- camera and sun -----------------------------------------------------------------------------

// A camera inside the hill renders the hill's inside (or nothing): refused. A look-at point
// below the surface still gives a valid direction, so only the position is checked.
void check_camera_above_ground(const std::array<double, 3>& p, const SceneGround& ground, const SceneConfig& config,
                               const std::string& key_at_fault) {
  const auto h = ground.height(p[0], p[1]);
  if (h && p[2] < *h)
    throw config.error_at(key_at_fault, "puts the camera " + number(*h - p[2]) + " m below the ground (up " +
                                            number(p[2]) + " m, the ground is at " + number(*h) +
                                            " m there); raise it above the ground");
}

std::array<double, 3> resolve_point(const CameraPoint& point, const SceneGround& ground, const SceneConfig& config,
                                    const std::string& key, const std::array<double, 3>& fallback) {
  if (point.enu) {
    if (key == "position") check_camera_above_ground(*point.enu, ground, config, "camera.position");
    return *point.enu;
  }
  std::array<double, 2> xy{fallback[0], fallback[1]};
  std::string key_at_fault = "camera." + key;
  if (point.enu_ground) {
    xy = *point.enu_ground;
  } else if (point.latitude) {
    xy = ground.to_enu(*point.latitude, *point.longitude);
    key_at_fault = key == "position" ? "camera.latitude" : "camera.target_latitude";
  } else {
    if (key == "position") check_camera_above_ground(fallback, ground, config, "camera.height_above_ground");
    return fallback;
  }
  const auto h = ground.height(xy[0], xy[1]);
  if (!h)
    throw config.error_at(key_at_fault, "(east " + number(xy[0]) + " m, north " + number(xy[1]) +
                                            " m) is not over the ground (" + ground.description() + ")");
  const std::array<double, 3> resolved{xy[0], xy[1], *h + point.height_above_ground};
  if (key == "position") check_camera_above_ground(resolved, ground, config, "camera.height_above_ground");
  return resolved;
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
    throw config.error_at("camera.target", "is the same point as camera.position");
  if (std::sqrt(dx * dx + dy * dy) < 1e-6)
    throw config.error_at("camera.target", "is straight above or below the camera; move it sideways");
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
      throw config.error_at("sun.time", config.sun.time_text + " is night at the origin (the sun is " +
                                            number(-sun.elevation_degrees) + " degrees below the horizon)");
  } else {
    sun.azimuth_degrees = config.sun.azimuth;
    sun.elevation_degrees = config.sun.elevation;
  }
  return sun;
}

}  // namespace

float SceneField::yaw_of(float point_yaw) const {
  if (!facing_yaw) return point_yaw;
  // A function of the point's identity only, so replicated points agree across tiles.
  const double u = point_yaw / (2 * std::numbers::pi);
  return float(*facing_yaw + (2 * u - 1) * facing_jitter);
}

PlacementStats SceneField::place(const InstanceSink& sink) const {
  if (!facing_yaw) return ground.place(filled, placement, sink);
  InstanceBatch turned;
  return ground.place(filled, placement, [&](const InstanceBatch& batch) {
    turned = batch;
    for (auto& yaw : turned.yaw) yaw = yaw_of(yaw);
    sink(turned);
  });
}

Scene make_scene(const SceneConfig& config, const StageObserver& stage) {
  Scene scene;
  scene.name = config.name;
  say(stage, config.terrain.dem.empty() ? "making flat ground" : "loading terrain " + config.terrain.dem.string());
  SceneGround ground;
  try {
    ground = SceneGround::load(config.terrain, config.masks);
  } catch (const Error& e) {
    // Name the scene file: the DEM or a mask limit came from it.
    if (!e.file().empty() && e.file() != config.source) throw;
    throw Error(config.source, "", e.message());
  }
  scene.terrain = ground.mesh();
  scene.georeference = ground.georeference();

  say(stage, config.models.mesh.empty()
                 ? "building " + std::to_string(config.models.variants) + " sunflower variants (" +
                       std::to_string(config.models.triangle_budget) + " triangles each)"
                 : "loading model " + config.models.mesh.string());
  scene.models = make_models(config.models);

  const auto field = make_field(config, ground, scene.models.size(), stage);
  scene.field = field;
  scene.field_area = *field->placement.area;
  scene.instances = [field](const InstanceSink& sink) { field->place(sink); };

  if (config.ground) {
    say(stage, "baking the ground's look (" + config.ground->look + ", " + std::to_string(config.ground->bake_pixels) +
                   " pixels)");
    const auto exemplars = load_ground_exemplars(config);
    std::shared_ptr<const GroundLook> look;
    try {
      // The field (which owns the ground) outlives the look: both live as long as the Scene.
      look = std::make_shared<const GroundLook>(*config.ground, exemplars,
                                                [field](double x, double y) { return field->ground.height(x, y); });
    } catch (const Error& e) {
      // The texture tiles' limits (exemplar smaller than a tile) come from these keys.
      throw config.error_at("ground.texture_pixels", e.message());
    }
    scene.ground_texture = std::make_shared<const GroundBake>(bake_ground(*look, ground, config.ground->bake_pixels));
    scene.ground_look = std::move(look);
  }

  scene.camera = make_camera(config, ground, scene.field_area);
  scene.sun = make_sun(config, ground);
  scene.render.width = config.image.width;
  scene.render.height = config.image.height;
  scene.render.antialias_samples = config.image.antialias;
  scene.render.threads = config.image.threads;
  scene.render.radiosity = config.image.radiosity;
  return scene;
}

}  // namespace wangscape
