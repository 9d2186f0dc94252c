// The scene file (TOML): everything a scene is made from (`wangscape build`, and later the LDI
// build, the viewer and batch renders). Every key,
// its meaning and its default are documented in docs/scene-file.md; unknown keys are errors
// naming the key and its line.
#pragma once

#include "core/error.h"
#include "generator/tiling.h"
#include "scene/wind.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace wangscape {

// [terrain]
struct TerrainConfig {
  std::filesystem::path dem;                  // empty = flat ground at height 0
  std::optional<double> origin_latitude;      // WGS 84 degrees; default: the DEM's center
  std::optional<double> origin_longitude;     // WGS 84 degrees
  std::optional<std::array<double, 4>> crop;  // [min_east, min_north, max_east, max_north], ENU m
  double flat_size = 200.0;                   // meters, side of the flat ground without a DEM
};

// [tiles]
struct TilesConfig {
  std::string set = "cohen8";  // built-in tile set name or a tile-set JSON path
  double tile_size = 4.0;      // meters
  int points_per_tile = 20;    // flowers per tile
  int relaxation_rounds = 8;   // Lloyd-style relaxation of each tile's points
  std::uint64_t seed = 1;      // tiling, points and flower yaw/scale
  TilingAlgorithm algorithm = TilingAlgorithm::scanline;
  std::optional<std::array<double, 4>> area;  // where flowers grow, ENU m; default: the ground's extent
  // Where flowers grow as [min_lat, min_lon, max_lat, max_lon], WGS 84 degrees (instead of area):
  // the tiling covers its ENU box, a mask on the ground keeps the rectangle itself.
  std::optional<std::array<double, 4>> area_latlon;
  bool interior_variation = false;  // variant, yaw, scale from the world tile and index, not the tile's point
};

// [masks]
struct MasksConfig {
  std::optional<double> max_height;  // meters; no flowers above
  std::optional<double> min_height;  // meters; no flowers below
  std::optional<double> max_slope;   // degrees; no flowers on steeper ground
  std::filesystem::path mask;        // painted mask image over the ground (white = flowers); empty = none
  std::filesystem::path raster;      // georeferenced raster in any CRS, warped onto the DEM (non-zero = flowers)
  std::filesystem::path polygons;    // OGR layer of polygons (GeoPackage, Shapefile, GeoJSON); empty = none
  bool polygons_outside = false;     // polygons_keep = "outside": flowers outside the polygons, not inside
  double polygons_buffer_m = 0;      // meters the polygons grow by before the test (negative: shrink)
  bool fair_edges = true;            // thin the field out towards mask borders instead of a hard cut
};

// [models]
struct ModelsConfig {
  int variants = 11;
  std::size_t triangle_budget = 6000;  // per sunflower
  std::uint64_t seed = 1;
  // A user's models replacing the sunflowers: files (one variant each) or a folder (its model
  // files by name); empty = sunflowers.
  std::vector<std::filesystem::path> mesh;
  bool mesh_y_up = false;              // up_axis = "y": the mesh file is y-up and is turned z-up
  bool mesh_objects_variants = false;  // mesh_objects = "variants": each object of a file is a variant
  double scale = 1.0;                  // uniform scale of every model
  double scale_jitter = 0.1;           // each flower scaled by 1 +- this (uniform)
  std::optional<double> facing;        // compass degrees the flower heads face; default: random
  double facing_jitter = 30.0;         // degrees, +- around `facing`
};

// [[species]]: one kind of plant of a meadow (docs/scene-file.md). Several share one Poisson tile
// set, each with its own radii, density and rules; without any the field is [models]' flowers.
struct SpeciesConfig {
  std::string name;                                       // unique; other species' exclusion names it
  std::string model = "grass";                            // a plant kind (templates/plants.h) or, with `mesh`, a file
  std::vector<std::filesystem::path> mesh;                // a user's models instead of a plant kind ([models] mesh)
  bool mesh_y_up = false;                                 // up_axis = "y"
  bool mesh_objects_variants = false;                     // mesh_objects = "variants"
  int variants = 4;                                       // model variants (a mesh: as many as its files or objects)
  std::optional<std::size_t> triangle_budget;             // per model; default: the kind's (triangle_budget_range)
  std::optional<std::uint64_t> seed;                      // default: models.seed
  double scale = 1.0;                                     // uniform scale of the species' models
  std::optional<double> tight_radius;                     // meters; default: the models' extent (largest variant)
  std::optional<double> packing_radius;                   // meters; default: from the species' density
  double share = 1.0;                                     // relative density among the species
  bool edge_objects = false;                              // placed across tile edges, never across a corner
  std::optional<double> min_height, max_height;           // meters
  std::optional<double> min_slope, max_slope;             // degrees
  std::optional<std::array<double, 2>> aspect;            // compass degrees [from, to], clockwise (may wrap past north)
  std::filesystem::path mask;                             // painted mask over the ground (white = grows); empty = none
  std::vector<std::pair<std::string, double>> exclusion;  // (other species, meters kept from it)
  // Piecewise-linear density (0..1) of the terrain: [[height m, density], ...] and [[slope
  // degrees, density], ...], x increasing, held flat beyond the ends; both multiply.
  std::vector<std::array<double, 2>> density_by_height, density_by_slope;
};

// [camera]: position and target, each either ENU meters or latitude/longitude; a height
// above the ground replaces the third coordinate.
struct CameraPoint {
  std::optional<std::array<double, 3>> enu;         // [east, north, up] meters
  std::optional<std::array<double, 2>> enu_ground;  // [east, north]; up = ground + height_above_ground
  std::optional<double> latitude, longitude;        // WGS 84 degrees
  double height_above_ground = 2.0;                 // meters (used without a full ENU point)
};

struct CameraConfig {
  CameraPoint position;
  CameraPoint target;
  std::optional<double> heading;  // compass degrees, with pitch instead of a target
  double pitch = 0.0;             // degrees above the horizontal
  double fov = 50.0;              // horizontal field of view, degrees
};

// [sun]: azimuth/elevation, or a date and time (with a UTC offset) at the origin.
struct SunConfig {
  double azimuth = 135.0;                 // compass degrees (0 north, 90 east)
  double elevation = 35.0;                // degrees above the horizon
  std::optional<std::int64_t> time_unix;  // seconds since 1970-01-01 UTC, from `time`
  std::string time_text;                  // as written, for messages
  double strength = 1.0;
};

// [image]
struct ImageConfig {
  int width = 640, height = 360;
  int antialias = 3;  // POV-Ray antialias depth (1 = off)
  int threads = 0;    // 0 = all cores
  bool radiosity = false;
};

// [ground]: the ground's look (scene/ground_look.h). Without the section the exporters keep
// their plain ground.
struct GroundConfig {
  std::string look = "both";        // "materials", "texture" or "both" (texture detail over the materials)
  double noise_scale = 256.0;       // meters per noise tile
  int noise_lattice = 16;           // lattice cells per noise tile side (power of two)
  std::uint64_t seed = 1;           // noise gradients and both hashed tilings
  double pumice_above = 1400.0;     // meters: meadow soil below, pumice above
  double snow_above = 2300.0;       // meters: snow above
  double height_blend = 80.0;       // meters over which one material fades into the next
  double rock_slope = 32.0;         // degrees: rock on steeper ground
  double slope_blend = 6.0;         // degrees
  std::string exemplar = "meadow";  // shipped exemplar name (meadow, pumice) or an image path
  std::string exemplar2;            // optional second exemplar (corner-marked tiles)
  // meters: the texture is exemplar's below this height and exemplar2's above it, switching
  // along the contour (corner marks from the terrain); empty = marks at random
  std::optional<double> exemplar2_above;
  double texture_scale = 64.0;    // meters per texture tile
  int texture_pixels = 64;        // pixels per texture tile side
  double texture_strength = 0.6;  // with look = "both": 0 = materials only, 1 = full texture detail
  int bake_pixels = 2048;         // longer side of the baked ground texture
};

// [camera_aware]: export only what the camera sees (docs/scene-file.md). Distances are meters
// from the camera; unset ones follow from the image width and field of view.
struct CameraAwareConfig {
  std::optional<bool> enabled;        // default: on when [tiles] gives no area
  std::optional<double> near;         // full models closer than this
  std::optional<double> far;          // proxies up to this; beyond it, the field texture
  std::optional<double> sun_margin;   // meters toward the sun kept for shadows falling into view
  std::size_t proxy_triangles = 400;  // triangle budget of the proxy sunflowers
  bool far_texture = true;            // the flowers beyond `far` as a texture in the ground bake
};

// Where the plants of a GIS file stand: in the DEM's CRS, or in WGS 84 longitude and latitude.
enum class GisCrsChoice { dem, wgs84 };

// [exports]
struct ExportsConfig {
  bool povray = true;
  bool blender = false;
  bool gltf = false;
  bool ldi = false;  // DIR/tiles.ldi: the tiles as pre-shaded LDIs (renders/, docs/ldi-pack-format.md)
  bool gis = false;  // DIR/plants.gpkg (a point layer) and DIR/cover.tif (plants per m2); needs a DEM
  GisCrsChoice gis_crs = GisCrsChoice::dem;  // the CRS of plants.gpkg (cover.tif is on the DEM's grid)
};

// [ldi]: the view the tiles' LDIs are sampled for.
struct LdiConfig {
  double head_height = 1.7;  // meters: the viewer's eye above the ground
  int levels = 7;            // levels of detail, 1 .. 7 tiles away by default
  int directions = 8;        // view directions around a tile
  int sky_rays = 8;          // ambient-occlusion rays per sample
};

struct SceneConfig {
  std::filesystem::path source;    // the TOML file (or "<embedded default scene>")
  std::filesystem::path base_dir;  // relative paths in the file resolve against it
  std::string name = "wangscape";
  TerrainConfig terrain;
  TilesConfig tiles;
  MasksConfig masks;
  ModelsConfig models;
  std::vector<SpeciesConfig> species;  // [[species]], in file order (species index = class)
  CameraConfig camera;
  SunConfig sun;
  ImageConfig image;
  std::optional<GroundConfig> ground;  // [ground], when the file has it
  std::optional<WindConfig> wind;      // [wind], when the file has it (scene/wind.h)
  CameraAwareConfig camera_aware;
  ExportsConfig exports;
  LdiConfig ldi;
  std::string text;  // the TOML as read (copied into the output folder)
  // The line of every key the file gave ("camera.position" -> 31), so errors found after
  // parsing (a camera off the DEM) still name the file and the line.
  std::map<std::string, int> key_lines;

  // An Error "<source>:<line>: '<key>' <what>" (no line when the key came from a default).
  Error error_at(std::string_view key, const std::string& what) const;
};

// Seconds since 1970-01-01 UTC of a local date and time with its UTC offset (minutes east).
std::int64_t unix_seconds_utc(int year, int month, int day, int hour, int minute, int second, int offset_minutes);

// Parses TOML text. `source` names it in messages; `base_dir` resolves relative paths.
// Throws Error "<source>:<line>: <what>" for syntax errors, unknown keys, wrong
// types and values out of range.
SceneConfig parse_scene_config(std::string_view toml_text, const std::filesystem::path& source,
                               const std::filesystem::path& base_dir);
// Scene files are small; anything larger is not one (docs/limits.md).
inline constexpr std::uintmax_t kMaxSceneFileBytes = 1u << 20;
// The farthest a camera or its target may be from the scene's origin, and the most a height above
// the ground may be: 10,000 km, beyond any ground a scene holds.
inline constexpr double kMaxCameraMeters = 1e7;

// Reads and parses a scene file; relative paths resolve against its folder. Refuses a file
// that is not a regular file or is over kMaxSceneFileBytes, naming it.
SceneConfig load_scene_config(const std::filesystem::path& file);

// The default scene (templates/scenes/default.toml, embedded in the program). Its data
// paths (data/SainteHelens.dem) resolve against the source tree or the installed data folder.
SceneConfig default_scene_config();
// The default scene as a file to save and edit: its data paths made absolute.
std::string default_scene_text_for_saving();
std::string_view default_scene_text();
// The folder the default scene's data (data/...) and the shipped templates
// (templates/exemplars/...) resolve against: $WANGSCAPE_DATA_DIR, the source tree, or an
// ancestor of the executable holding data/.
std::filesystem::path data_root();

}  // namespace wangscape
