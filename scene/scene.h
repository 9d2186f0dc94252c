// The Scene value every consumer reads (exporters, renders, the viewer and batch renders to
// come): the terrain mesh, the model variants, camera, sun, render settings, georeference, and
// the field of flowers with its instance stream. make_scene assembles it from a scene file.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/extent.h"
#include "generator/instances.h"
#include "generator/placement.h"
#include "generator/poisson_tiles.h"
#include "scene/camera_view.h"
#include "scene/ground_look.h"
#include "scene/scene_file.h"
#include "scene/scene_ground.h"
#include "scene/species.h"
#include "scene/sun.h"
#include "scene/wind.h"
#include "templates/mesh.h"
#include "templates/stand_in.h"

namespace wangscape {

struct Camera {
  std::array<double, 3> position{0, 0, 2};  // ENU meters
  std::array<double, 3> target{10, 0, 0};   // ENU meters
  double fov_degrees = 50.0;                // horizontal field of view
};

struct RenderSettings {
  int width = 640;
  int height = 360;
  int antialias_samples = 1;  // POV-Ray +A depth / Cycles samples scale
  bool radiosity = false;     // POV-Ray radiosity switch
  int threads = 0;            // 0 = all cores
};

// Georeference carried into every manifest and header: ordered (key, value) strings, e.g.
// ("crs_wkt", ...), ("origin_latitude", "46.2"), ("units", "meters"), ("vertical_datum", ...).
using Georeference = std::vector<std::pair<std::string, std::string>>;

using InstanceSink = std::function<void(const InstanceBatch&)>;
// Places the scene's instances and hands them to the sink batch by batch, tile rows from
// south to north. Each call places the whole field again: run it once and fan the batches out.
using InstanceStream = std::function<void(const InstanceSink& sink)>;

// What one run of a field's stream laid, and (camera-aware) what the camera saw.
struct FieldReport {
  std::uint64_t field_tiles = 0;    // tiles of the tiling over the whole field area
  std::uint64_t visible_tiles = 0;  // tiles the camera view kept (all of them without one)
  std::uint64_t placed_tiles = 0;   // visible tiles the masks kept
  std::uint64_t culled_tiles = 0;   // field tiles outside the view (never laid)
  std::uint64_t models = 0;         // instances of the full models
  std::uint64_t proxies = 0;        // instances of the proxies (camera-aware, near .. far)
};

// The field: a filled tile set laid over the ground, flowers where the masks allow.
struct SceneField {
  SceneGround ground;
  FilledTileSet filled;
  PlacementOptions placement;        // placement.area is set: the area the field covers
  std::optional<double> facing_yaw;  // radians, counter-clockwise from east; empty = the tile's yaw
  double facing_jitter = 0;          // radians
  // Camera-aware export: only tiles the view keeps are laid (placement.window is its window);
  // flowers between near and far become variant + proxy_offset, beyond far none. Empty: all.
  std::shared_ptr<const CameraView> view;
  std::size_t proxy_offset = 0;  // 0: no proxies (the full models go on to far)
  // [[species]]: each point is kept only where its species' rules and density let it grow; their
  // count and names in class order. Empty without [[species]].
  std::shared_ptr<const SpeciesRules> species;

  // The species (class) of model `model` of Scene::models, a proxy counting as its full model's;
  // nothing without species or past the models.
  std::optional<std::size_t> species_of_model(std::size_t model) const;

  // Places every instance (thread-safe, deterministic).
  FieldReport place(const InstanceSink& sink) const;
  // The same instances place() gives, of the tiles that meet `window` (ENU meters) only: what a
  // renderer needs around a point of view (thread-safe, deterministic).
  FieldReport place_in(const Extent& window, const InstanceSink& sink) const;
  // Whether the camera view keeps the tile (true without a view). Thread-safe.
  bool tile_in_view(const TileCell& cell) const;
  // The yaw (radians) an instance of a point with tile yaw `point_yaw` gets: the configured
  // facing spread over +- jitter by the point's own uniform yaw, or the point's yaw.
  float yaw_of(float point_yaw) const;

 private:
  FieldReport place_window(const std::optional<Extent>& window, const InstanceSink& sink) const;
};

struct Scene {
  std::string name = "wangscape";
  Mesh terrain;                             // ENU meters; may be empty (no terrain)
  std::vector<Mesh> models;                 // one per variant; InstanceBatch::variant indexes this
  std::vector<StandInFigures> stand_ins;    // the figures of the user's models' stand-ins among `models`
  InstanceStream instances;                 // may be empty (no instances)
  Extent field_area;                        // where instances may stand (ENU m); rows of the stream go south to north
  std::shared_ptr<const SceneField> field;  // what the stream places (empty for hand-made scenes)
  // The counts of the stream's last run (set by the field's stream; empty for hand-made scenes).
  std::shared_ptr<FieldReport> last_placement;
  Camera camera;
  Sun sun;
  RenderSettings render;
  Georeference georeference;
  // [ground]: the look (what renderers sample) and its bake over the terrain (what the
  // exporters write: made once here, shared by every writer). Both empty without [ground].
  std::shared_ptr<const GroundLook> ground_look;
  std::shared_ptr<const GroundBake> ground_texture;
  // [wind] with a strength above 0: every plant leans about its base by wind->lean(east, north,
  // seconds); empty when calm (the outputs then as without the section).
  std::optional<WindField> wind;
};

// The most flowers a field (or a scatter) may hold, counted before masks (with camera-aware
// export: the visible tiles' flowers): above it the outputs would outgrow what POV-Ray can hold
// (about 1.4 GB per million flowers) and the disk.
inline constexpr double kMaxFieldInstances = 50e6;

// Where the field is planted, ENU meters: the ground's extent, cut to [tiles] area or to the ENU
// box of [tiles] area_latlon (whose mask, on the ground, keeps the rectangle itself); empty when
// they miss the ground.
Extent field_area(const SceneConfig& config, const SceneGround& ground);

// Stage messages while a scene is assembled (a program shows them, e.g. on a terminal).
using StageObserver = std::function<void(const std::string& message)>;

// The models a scene's build made: Scene::models and what else make_scene derives from them.
struct SceneModels {
  std::vector<Mesh> models;               // Scene::models: the full models, then (camera-aware) their proxies
  std::size_t full_models = 0;            // the models before the proxies (all of them without proxies)
  std::vector<StandInFigures> stand_ins;  // Scene::stand_ins
};

// How many of scene.models are full models: its field's proxy_offset where it has proxies, else all.
std::size_t full_model_count(const Scene& scene);

// What a scene folder's build already made (folder/scene_folder.h keeps it in the folder), so
// that a reader of the folder need not make it again: the filled tile set (the Poisson fill and
// its relaxation), the baked ground (the look, and the far field painted into it) and the models
// (the sunflowers' tessellation, a user's models read and turned, their stand-ins).
struct ScenePrebuilt {
  FilledTileSet filled;
  std::shared_ptr<const GroundBake> ground_texture;  // null: the build baked no ground
  std::optional<SceneModels> models;                 // empty: made again (a folder kept without them)
};

// Assembles the Scene a scene file describes: ground and masks, terrain mesh, models, the
// filled tile set, camera above the ground, sun. Places nothing: the stream does that when run.
// With `prebuilt` (of this same config), the filled tile set (tiles.set is not read), the ground
// bake and the models where it has them (no model file is read) are taken from it, and
// Scene::ground_look stays empty. Throws Error naming the file and the line of the key at fault.
Scene make_scene(const SceneConfig& config, const StageObserver& stage = {}, const ScenePrebuilt* prebuilt = nullptr);

}  // namespace wangscape
