#include "scene/scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/memory_budget.h"
#include "core/number_text.h"
#include "generator/tiling.h"
#include "scene/far_field.h"
#include "scene/tileset_file.h"
#include "templates/mesh_io.h"
#include "templates/sunflower.h"

namespace wangscape {

namespace {

void say(const StageObserver& stage, const std::string& message) {
  if (stage) stage(message);
}

// DEM cells under a field sown by area or of species are cut into this many squares a side (30 m
// cells: 3.75 m), each of two triangles on the bilinear surface.
constexpr int kFieldGroundSubdivisions = 8;

// ---- models ---------------------------------------------------------------------------------

// The sunflowers of [models] (variants, budget, seed), scaled.
std::vector<Mesh> make_sunflowers(const ModelsConfig& config) {
  std::vector<Mesh> models;
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

// [models]' variants: a user's models, else the sunflowers.
std::vector<Mesh> make_models(const SceneConfig& scene_config) {
  const ModelsConfig& config = scene_config.models;
  std::vector<Mesh> models;
  if (!config.mesh.empty()) {
    models = load_user_variants(scene_config, "models.mesh", config.mesh, config.mesh_y_up,
                                config.mesh_objects_variants, config.scale);
    // Several variants are told apart by number: two folders may hold a "tulip.obj" each.
    if (models.size() > 1)
      for (std::size_t v = 0; v < models.size(); ++v) models[v].name += "_" + std::to_string(v);
    return models;
  }
  return make_sunflowers(config);
}

// ---- the field: tiles laid over the ground, flowers where the masks allow -------------------

// Camera-aware export is on by default for a field over the whole ground (no [tiles] area).
bool camera_aware(const SceneConfig& config) {
  return config.camera_aware.enabled.value_or(!config.tiles.area && !config.tiles.area_latlon);
}

// The Poisson fill of the field's tile set, [tiles] set (its cost told first: it can take a minute).
void fill_field_tiles(SceneField& field, const SceneConfig& config, const PoissonFillOptions& fill,
                      const StageObserver& stage) {
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
    field.filled = fill_poisson_tiles(set, fill);
  } catch (const Error& e) {
    throw config.error_at("tiles.points_per_tile", e.what());
  }
}

}  // namespace

Extent field_area(const SceneConfig& config, const SceneGround& ground) {
  Extent area = ground.extent();
  if (config.tiles.area) {
    const auto& a = *config.tiles.area;
    area = area.intersected({a[0], a[1], a[2], a[3]});
  } else if (config.tiles.area_latlon) {
    area = area.intersected(ground.lat_lon_box_extent(*config.tiles.area_latlon));
  }
  return area;
}

namespace {

std::shared_ptr<SceneField> make_field(const SceneConfig& config, const SceneGround& ground, std::size_t model_count,
                                       const SpeciesModels& species_models, const StageObserver& stage,
                                       const FilledTileSet* prefilled) {
  auto field = std::make_shared<SceneField>();
  field->ground = ground;
  const char* area_key = config.tiles.area_latlon ? "tiles.area_latlon" : "tiles.area";
  const Extent area = field_area(config, ground);
  if (area.empty()) throw config.error_at(area_key, "does not overlap the ground (" + ground.description() + ")");
  const double tile_size = config.tiles.tile_size;
  const double tiles_x = std::ceil(area.width() / tile_size) + 1, tiles_y = std::ceil(area.height() / tile_size) + 1;
  const double estimate = tiles_x * tiles_y * config.tiles.points_per_tile;
  // With camera-aware export the limit applies to what the camera sees (checked once it stands).
  if (estimate > kMaxFieldInstances && !camera_aware(config))
    throw config.error_at("tiles.area", "gives a field of up to " + std::to_string(std::llround(estimate)) +
                                            " flowers (" + std::to_string(std::llround(tiles_x)) + " x " +
                                            std::to_string(std::llround(tiles_y)) +
                                            " tiles); limit it with tiles.area or a larger tiles.tile_size, or "
                                            "export what the camera sees ([camera_aware] enabled = true, far) "
                                            "(at most 50 million)");
  // What the field holds a tile of its whole area: a byte in the scene folder's grid of placed
  // tiles (folder/folder_state.h), and 2 bytes more for a scanline or bottom-left tiling,
  // computed for the whole area and held by the placement and the far field (a hashed tiling is
  // computed row by row).
  const bool held_tiling = config.tiles.algorithm != TilingAlgorithm::hash;
  const std::string held = held_tiling ? "placed-tile grid and " + std::string(to_string(config.tiles.algorithm)) +
                                             " tiling (3 bytes a tile)"
                                       : std::string("placed-tile grid (1 byte a tile)");
  if (const auto excess =
          memory_estimate_excess("gives a field of " + fixed_text(tiles_x, 0) + " x " + fixed_text(tiles_y, 0) +
                                     " tiles of " + number_text(tile_size) + " m, whose " + held,
                                 tiles_x * tiles_y * (held_tiling ? 3.0 : 1.0)))
    throw config.error_at(
        config.tiles.area || config.tiles.area_latlon ? area_key
        : config.terrain.dem.empty()                  ? "terrain.flat_size"
                                                      : "terrain.dem",
        *excess + "; limit it with tiles.area or a larger tiles.tile_size" +
            (held_tiling ? ", or use tiles.algorithm = \"hash\" (a complete set: 1 byte a tile)" : ""));
  field->placement.tile_size = tile_size;
  field->placement.algorithm = config.tiles.algorithm;
  field->placement.seed = config.tiles.seed;
  field->placement.area = area;

  PoissonFillOptions fill;
  fill.points_per_tile = config.tiles.points_per_tile;
  fill.seed = config.tiles.seed;
  fill.relax_rounds = config.tiles.relaxation_rounds;
  fill.variants = int(std::max<std::size_t>(1, model_count));
  fill.min_scale = 1.0 - config.models.scale_jitter;
  fill.max_scale = 1.0 + config.models.scale_jitter;
  if (!config.species.empty()) {
    // (A filled set kept by the build has its classes; their models may not have been made.)
    if (!prefilled) fill.classes = species_classes(config, species_models, fill);
    field->species = std::make_shared<const SpeciesRules>(config, ground);
  }
  if (prefilled) {
    field->filled = *prefilled;  // with its tile set: tiles.set is not read again
  } else {
    fill_field_tiles(*field, config, fill, stage);
  }
  if (config.tiles.interior_variation)
    field->placement.world_attributes =
        PlacementOptions::WorldAttributes{config.tiles.seed, fill.variants, fill.min_scale, fill.max_scale};
  if (config.models.facing) {
    // Compass (clockwise from north) to yaw (counter-clockwise from east).
    field->facing_yaw = (90.0 - *config.models.facing) * std::numbers::pi / 180;
    field->facing_jitter = config.models.facing_jitter * std::numbers::pi / 180;
  }
  return field;
}

// The camera's view of the field: distances from the image and the models, the window, and the
// limit on what the camera sees.
std::shared_ptr<const CameraView> make_view(const SceneConfig& config, const SceneField& field, const Scene& scene) {
  const auto& c = config.camera_aware;
  // A 30 cm head: full models while it spans 8 pixels or more, proxies down to one pixel.
  const double head = 0.3 * config.models.scale;
  CameraViewOptions options;
  options.far = c.far.value_or(distance_for_pixels(head, 1, config.image.width, config.camera.fov));
  options.near =
      std::min(options.far, c.near.value_or(distance_for_pixels(head, 8, config.image.width, config.camera.fov)));
  if (c.near && *c.near > options.far)
    throw config.error_at("camera_aware.near",
                          "is beyond camera_aware.far (" + significant_text(options.far, 6) + " m)");
  double height = 0, reach = 0;
  for (std::size_t v = 0; v < std::size_t(field.filled.variants) && v < scene.models.size(); ++v)
    for (const auto& p : scene.models[v].positions) {
      height = std::max<double>(height, p[2]);
      reach = std::max<double>(reach, std::hypot(p[0], p[1]));
    }
  const double max_scale = 1 + config.models.scale_jitter;
  options.flower_height = height * max_scale;
  options.flower_reach = reach * max_scale;
  const double elevation = std::max(scene.sun.elevation_degrees, 1.0) * std::numbers::pi / 180;
  options.sun_margin = c.sun_margin.value_or(std::min(200.0, options.flower_height / std::tan(elevation)));
  const double aspect = double(config.image.width) / config.image.height;
  return std::make_shared<const CameraView>(scene.camera, scene.sun, aspect, options);
}

// Refuses a view that holds more than kMaxFieldInstances flowers, counting the visible tiles.
void check_visible_flowers(const SceneConfig& config, const SceneField& field) {
  const double s = field.placement.tile_size;
  const TileRange range = clip_range(tile_range(field.view->window(), s), tile_range(*field.placement.area, s));
  const std::uint64_t visible = tbb::parallel_reduce(
      tbb::blocked_range<std::int64_t>(range.j0, range.j1), std::uint64_t{0},
      [&](const tbb::blocked_range<std::int64_t>& rows, std::uint64_t count) {
        for (std::int64_t j = rows.begin(); j < rows.end(); ++j)
          for (std::int64_t i = range.i0; i < range.i1; ++i) {
            const double x = double(i) * s, y = double(j) * s;
            count += field.tile_in_view(TileCell{i, j, 0, Extent{x, y, x + s, y + s}});
          }
        return count;
      },
      std::plus<>());
  const double estimate = double(visible) * config.tiles.points_per_tile;
  if (estimate > kMaxFieldInstances)
    throw config.error_at("camera_aware.far", "lets the camera see up to " + std::to_string(std::llround(estimate)) +
                                                  " flowers (" + std::to_string(visible) +
                                                  " visible tiles); lower camera_aware.far or give a tiles.area "
                                                  "(at most 50 million)");
}

// ---- camera and sun// ---- camera and sun
// -----------------------------------------------------------------------------

// A camera inside the hill renders the hill's inside (or nothing): refused. A look-at point
// below the surface still gives a valid direction, so only the position is checked.
void check_camera_above_ground(const std::array<double, 3>& p, const SceneGround& ground, const SceneConfig& config,
                               const std::string& key_at_fault) {
  const auto h = ground.height(p[0], p[1]);
  if (h && p[2] < *h)
    throw config.error_at(key_at_fault, "puts the camera " + significant_text(*h - p[2], 6) +
                                            " m below the ground (up " + significant_text(p[2], 6) +
                                            " m, the ground is at " + significant_text(*h, 6) +
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
    throw config.error_at(key_at_fault, "(east " + significant_text(xy[0], 6) + " m, north " +
                                            significant_text(xy[1], 6) + " m) is not over the ground (" +
                                            ground.description() + ")");
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
                                            significant_text(-sun.elevation_degrees, 6) +
                                            " degrees below the horizon)");
  } else {
    sun.azimuth_degrees = config.sun.azimuth;
    sun.elevation_degrees = config.sun.elevation;
  }
  return sun;
}

// The camera-aware export's proxies of scene.models (`species_models`' variants with [[species]]), in their order: the
// procedural plants again at [camera_aware] proxy_triangles, a user's models' stand-ins of at most as many triangles
// (their figures into scene.stand_ins).
std::vector<Mesh> make_proxies(const SceneConfig& config, const SpeciesModels& species_models, Scene& scene,
                               const StageObserver& stage) {
  const std::size_t budget = config.camera_aware.proxy_triangles;
  if (!config.species.empty()) {
    say(stage, "building the proxies of " + std::to_string(config.species.size()) + " species (at most " +
                   std::to_string(budget) + " triangles each)");
    return make_species_proxies(config, scene.models, species_models.variants, budget, scene.stand_ins);
  }
  if (!config.models.mesh.empty()) {
    say(stage, "simplifying " + std::to_string(scene.models.size()) + " models into stand-ins (at most " +
                   std::to_string(budget) + " triangles each)");
    StandInOptions options;
    options.max_triangles = budget;
    return make_stand_ins(scene.models, options, scene.stand_ins);
  }
  say(stage, "building " + std::to_string(config.models.variants) + " proxy sunflowers (" + std::to_string(budget) +
                 " triangles each)");
  ModelsConfig proxies = config.models;
  proxies.triangle_budget = std::min(budget, config.models.triangle_budget);
  std::vector<Mesh> models = make_sunflowers(proxies);
  for (Mesh& model : models) model.name += " proxy";
  return models;
}

}  // namespace

std::size_t full_model_count(const Scene& scene) {
  const std::size_t proxy_offset = scene.field ? scene.field->proxy_offset : 0;
  return proxy_offset ? proxy_offset : scene.models.size();
}

std::optional<std::size_t> SceneField::species_of_model(std::size_t model) const {
  if (!species) return std::nullopt;
  if (proxy_offset && model >= proxy_offset) model -= proxy_offset;
  const auto cls = class_of_variant(filled, int(model));
  return cls ? std::optional<std::size_t>(std::size_t(*cls)) : std::nullopt;
}

float SceneField::yaw_of(float point_yaw) const {
  if (!facing_yaw) return point_yaw;
  // A function of the point's identity only, so replicated points agree across tiles.
  const double u = point_yaw / (2 * std::numbers::pi);
  return float(*facing_yaw + (2 * u - 1) * facing_jitter);
}

bool SceneField::tile_in_view(const TileCell& cell) const {
  if (!view) return true;
  // The ground's heights over the tile, from its corners and centre (DEM cells are much larger
  // than a tile, so a meter of slack covers the bilinear bend between them).
  const Extent& b = cell.bounds;
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& [x, y] : {std::pair{b.min_x, b.min_y},
                             {b.max_x, b.min_y},
                             {b.min_x, b.max_y},
                             {b.max_x, b.max_y},
                             {(b.min_x + b.max_x) / 2, (b.min_y + b.max_y) / 2}})
    if (const auto z = ground.height(x, y)) {
      lo = std::min(lo, *z);
      hi = std::max(hi, *z);
    }
  if (lo > hi) return view->tile_visible(b, view->position()[2] - 1e4, view->position()[2] + 1e4);
  return view->tile_visible(b, lo - 1, hi + 1);
}

FieldReport SceneField::place(const InstanceSink& sink) const { return place_window(std::nullopt, sink); }

FieldReport SceneField::place_in(const Extent& window, const InstanceSink& sink) const {
  return place_window(window, sink);
}

FieldReport SceneField::place_window(const std::optional<Extent>& window, const InstanceSink& sink) const {
  FieldReport report;
  const TileRange whole = tile_range(*placement.area, placement.tile_size);
  report.field_tiles = std::uint64_t(whole.width()) * std::uint64_t(whole.height());
  std::atomic<std::uint64_t> visible{0};
  const auto in_view = [&](const TileCell& cell) {
    if (!tile_in_view(cell)) return false;
    visible.fetch_add(1, std::memory_order_relaxed);
    return true;
  };
  InstanceBatch out;
  const auto pass_on = [&](const InstanceBatch& batch) {
    if (!facing_yaw && !view) {
      report.models += batch.size();
      sink(batch);
      return;
    }
    out.clear();
    out.reserve(batch.size());
    for (std::size_t k = 0; k < batch.size(); ++k) {
      std::uint16_t variant = batch.variant[k];
      if (view) {
        const double d = view->distance(batch.x[k], batch.y[k], batch.z[k]);
        if (d > view->options().far) continue;
        if (d > view->options().near && proxy_offset) variant = static_cast<std::uint16_t>(variant + proxy_offset);
      }
      ++(variant >= proxy_offset && proxy_offset ? report.proxies : report.models);
      out.push_back(batch.x[k], batch.y[k], batch.z[k], yaw_of(batch.yaw[k]), batch.scale[k], variant, batch.tile[k],
                    batch.rank[k]);
    }
    if (!out.empty()) sink(out);
  };
  SceneGround::PointRule rule;
  if (species)
    rule = [rules = species.get()](double x, double y, double z, std::uint8_t s, float rank) {
      return rules->keeps(x, y, z, s, rank);
    };
  PlacementStats stats;
  if (view) {
    PlacementOptions windowed = placement;
    windowed.window = window ? window->intersected(view->window()) : view->window();
    stats = ground.place(filled, windowed, pass_on, in_view, rule);
    report.visible_tiles = visible.load();
  } else if (window) {
    PlacementOptions windowed = placement;
    windowed.window = *window;
    stats = ground.place(filled, windowed, pass_on, {}, rule);
    report.visible_tiles = report.field_tiles;
  } else {
    stats = ground.place(filled, placement, pass_on, {}, rule);
    report.visible_tiles = report.field_tiles;
  }
  report.placed_tiles = stats.tiles_kept;
  report.culled_tiles = report.field_tiles - report.visible_tiles;
  return report;
}

Scene make_scene(const SceneConfig& config, const StageObserver& stage, const ScenePrebuilt* prebuilt) {
  Scene scene;
  scene.name = config.name;
  say(stage, config.terrain.dem.empty() ? "making flat ground" : "loading terrain " + config.terrain.dem.string());
  SceneGround ground;
  try {
    ground = SceneGround::load(config.terrain, config.masks, config.tiles.area_latlon);
  } catch (const Error& e) {
    // Name the scene file: the DEM or a mask limit came from it.
    if (!e.file().empty()) throw;
    throw Error(config.source, "", e.message());
  }
  scene.terrain = ground.mesh();
  scene.georeference = ground.georeference();

  SpeciesModels species_models;  // with [[species]]: their models, variants and radii
  const SceneModels* kept = prebuilt && prebuilt->models ? &*prebuilt->models : nullptr;
  if (kept) {
    const auto full = kept->models.begin() + std::ptrdiff_t(kept->full_models);
    scene.models.assign(kept->models.begin(), full);
  } else if (config.species.empty()) {
    say(stage, config.models.mesh.empty()
                   ? "building " + std::to_string(config.models.variants) + " sunflower variants (" +
                         std::to_string(config.models.triangle_budget) + " triangles each)"
                   : "loading the models of models.mesh");
    scene.models = make_models(config);
  } else {
    say(stage, "building the models of " + std::to_string(config.species.size()) + " species");
    species_models = make_species_models(config);
    scene.models = std::move(species_models.models);
  }

  const auto field =
      make_field(config, ground, scene.models.size(), species_models, stage, prebuilt ? &prebuilt->filled : nullptr);
  scene.field = field;
  scene.field_area = *field->placement.area;
  // Plants stand on the DEM's bilinear surface; the mesh the renderers draw must follow it under
  // the field, not the cells' two flat triangles: in the default field those strayed from it by
  // up to 2.5 m (3.7 % of the sunflowers more than 0.2 m under the drawn ground, some hidden
  // whole), and plants a few centimetres tall were buried. A field sown over the whole DEM
  // (camera-aware, no area) is not cut unless it has species: its mesh would grow many times.
  if (!config.species.empty() || config.tiles.area || config.tiles.area_latlon)
    ground.refine_mesh(scene.terrain, scene.field_area, kFieldGroundSubdivisions);
  scene.camera = make_camera(config, ground, scene.field_area);
  scene.sun = make_sun(config, ground);
  if (config.wind && config.wind->strength > 0) scene.wind = wind_field(*config.wind);
  if (camera_aware(config)) {
    field->view = make_view(config, *field, scene);
    check_visible_flowers(config, *field);
    field->proxy_offset = scene.models.size();
    if (kept)
      scene.models.insert(scene.models.end(), kept->models.begin() + std::ptrdiff_t(kept->full_models),
                          kept->models.end());
    else
      for (Mesh& proxy : make_proxies(config, species_models, scene, stage)) scene.models.push_back(std::move(proxy));
  }
  if (kept) scene.stand_ins = kept->stand_ins;
  auto report = std::make_shared<FieldReport>();
  scene.last_placement = report;
  scene.instances = [field, report](const InstanceSink& sink) { *report = field->place(sink); };

  const bool far_texture = field->view && config.camera_aware.far_texture;
  if (prebuilt) {
    scene.ground_texture = prebuilt->ground_texture;
  } else if (config.ground || far_texture) {
    // The far field lives in the bake: camera-aware export bakes [ground]'s defaults without one.
    const GroundConfig ground_config = config.ground.value_or(GroundConfig{});
    SceneConfig with_ground = config;
    with_ground.ground = ground_config;
    say(stage, "baking the ground's look (" + ground_config.look + ", " + std::to_string(ground_config.bake_pixels) +
                   " pixels)");
    const auto exemplars = load_ground_exemplars(with_ground);
    std::shared_ptr<const GroundLook> look;
    try {
      // The field (which owns the ground) outlives the look: both live as long as the Scene.
      look = std::make_shared<const GroundLook>(ground_config, exemplars,
                                                [field](double x, double y) { return field->ground.height(x, y); });
    } catch (const Error& e) {
      // The texture tiles' limits (exemplar smaller than a tile) come from these keys.
      throw config.error_at("ground.texture_pixels", e.message());
    }
    auto bake = bake_ground(*look, ground, ground_config.bake_pixels);
    if (far_texture) {
      say(stage, "painting the field beyond " + significant_text(field->view->options().far, 6) + " m into the ground");
      // What would stand there: the proxies (the full models when the scene has none).
      const auto first = scene.models.begin() + std::ptrdiff_t(field->proxy_offset);
      const std::vector<Mesh> beyond(first, first + std::ptrdiff_t(field->filled.variants));
      paint_far_field(bake, *field, FieldTexture(*field, beyond, field->view->far_view_direction(), scene.sun),
                      *field->view);
    }
    scene.ground_texture = std::make_shared<const GroundBake>(std::move(bake));
    scene.ground_look = std::move(look);
  }

  scene.render.width = config.image.width;
  scene.render.height = config.image.height;
  scene.render.antialias_samples = config.image.antialias;
  scene.render.threads = config.image.threads;
  scene.render.radiosity = config.image.radiosity;
  return scene;
}

}  // namespace wangscape
