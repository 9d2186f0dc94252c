// The view tests' worlds: a tiny flat field of sunflowers and its coarse LDI pack, built here by
// Embree (tests/renders/ldi_view_test.cpp, frame_cache_test.cpp).
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include "renders/ldi/ldi_scene.h"
#include "renders/scene_build.h"
#include "renders/view/view_world.h"
#include "scene/scene.h"
#include "scene/scene_file.h"

namespace wangscape::view_test {

namespace fs = std::filesystem;

inline fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("wangscape_ldi_view_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

// A flat field over `area` (ENU m), its pack built with 3 levels x 4 directions at a coarse
// resolution, and the view's world over both.
// With `full_pack`, the pack has the scene file's defaults (7 levels x 8 directions, 512 pixels).
// The view's world of the scene file `text`, with its pack (see tiny_world).
// With `steep_pack`, the steep sets' pack too, built beside it as `wangscape build` does (the
// view's world reads them instead of sampling them).
inline std::shared_ptr<const ViewWorld> world_of(const std::string& text, const std::string& name,
                                                 bool full_pack = false, bool steep_pack = false) {
  const SceneConfig config = parse_scene_config(text, name + ".toml", fs::temp_directory_path());
  Scene scene = make_scene(config);
  LdiBuildOptions options;
  if (!full_pack) {
    options.view.levels = steep_pack ? 4 : 3;  // (with three, the steep sets outweigh the pack: not written)
    options.view.directions = 4;
    options.view.image_width = 128;
  }
  options.shading.ao_rays = 0;
  if (!steep_pack) {
    const fs::path pack = scratch(name + ".ldi");
    build_scene_ldi_pack(scene, pack, options);
    return std::make_shared<const ViewWorld>(std::move(scene), pack);
  }
  const fs::path folder = scratch(name);
  fs::create_directories(folder);
  const FolderFiles files(folder);
  build_scene_ldi_packs(scene, files, options);
  return std::make_shared<const ViewWorld>(std::move(scene), files.pack(), options.shading, nullptr,
                                           ViewWorld::Prepared{files.steep_pack(), {}, {}});
}

// The scene file of tiny_world.
inline std::string tiny_scene(const std::string& area, const std::string& flat_size = "60.0",
                              const std::string& points_per_tile = "10") {
  return "name = \"view test\"\n[terrain]\nflat_size = " + flat_size +
         "\n[tiles]\nset = \"cohen8\"\n"
         "tile_size = 4.0\npoints_per_tile = " +
         points_per_tile + "\nseed = 5\narea = " + area +
         "\n[models]\nvariants = 2\ntriangle_budget = 400\n[sun]\nazimuth = 200.0\nelevation = 40.0\n";
}

inline std::shared_ptr<const ViewWorld> tiny_world(const std::string& area, const std::string& name,
                                                   const std::string& flat_size = "60.0", bool full_pack = false,
                                                   const std::string& points_per_tile = "10") {
  return world_of(tiny_scene(area, flat_size, points_per_tile), name, full_pack);
}

inline const std::shared_ptr<const ViewWorld>& field() {
  static const auto world = tiny_world("[-12.0, -12.0, 12.0, 12.0]", "field");
  return world;
}

// A tiny field over `area` with the LDI export and the [ldi] table `ldi` (its lines), built by
// build_scene into scratch(name) as `wangscape build` builds a folder.
inline fs::path built_ldi_folder(const std::string& name, const std::string& area, const std::string& ldi) {
  const fs::path out = scratch(name);
  const std::string text = tiny_scene(area) + "[exports]\npovray = false\nldi = true\n[ldi]\n" + ldi;
  build_scene(parse_scene_config(text, name + ".toml", fs::temp_directory_path()), out);
  return out;
}

// A file's bytes.
inline std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

inline Camera looking(double x, double y, double z, double tx, double ty, double tz, double fov = 60) {
  return {{x, y, z}, {tx, ty, tz}, fov};
}

}  // namespace wangscape::view_test
