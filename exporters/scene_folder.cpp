#include "exporters/scene_folder.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <vector>

#include "core/atomic_file.h"
#include "core/staged_folder.h"
#include "core/text_file.h"
#include "exporters/blender_export.h"
#include "exporters/export_support.h"
#include "exporters/folder_state.h"
#include "exporters/gis_writer.h"
#include "exporters/gltf_writer.h"
#include "exporters/povray_writer.h"
#include "exporters/scene_writer.h"

namespace wangscape {

namespace fs = std::filesystem;

namespace {

// One line: the absolute folder the relative paths of scene.toml resolve against.
constexpr const char* kSceneBaseFile = "scene_base.txt";
// [exports] gis: the plants as a GeoPackage point layer, and their cover as a GeoTIFF.
constexpr const char* kGisPlantsFile = "plants.gpkg";
constexpr const char* kGisCoverFile = "cover.tif";

void say(const SceneFolderObserver& observer, const std::string& message) {
  if (observer.stage) observer.stage(message);
}

}  // namespace

void check_scene_folder_target(const fs::path& out_dir_in) {
  if (out_dir_in.empty()) throw Error("the output folder is empty: give a folder name");
  const auto out_dir = fs::absolute(out_dir_in).lexically_normal();
  std::error_code ec;
  if (!fs::exists(out_dir, ec)) return;
  if (!fs::is_directory(out_dir, ec)) throw Error(out_dir, "", "exists and is not a folder");
  if (fs::is_empty(out_dir, ec) || fs::is_regular_file(out_dir / kFolderSceneFile, ec)) return;
  throw Error(out_dir, "",
              "exists and is not a scene folder (it has no scene.toml); give a new or empty folder, or an earlier "
              "build's");
}

SceneFolderSummary write_scene_folder(const Scene& scene, const ExportsConfig& exports, const std::string& scene_text,
                                      const fs::path& out_dir_in, const SceneFolderObserver& observer,
                                      const fs::path& scene_base_dir, const StagedWriter& also_write) {
  const auto start = std::chrono::steady_clock::now();
  check_scene_folder_target(out_dir_in);
  StagedFolder staged(out_dir_in);
  const fs::path& out_dir = staged.target();
  const fs::path& staging = staged.path();

  SceneFolderSummary summary;
  {  // the writers live until the folder is published
    std::unique_ptr<PovrayWriter> povray;
    std::unique_ptr<BlenderWriter> blender;
    std::unique_ptr<GltfWriter> gltf;
    std::unique_ptr<GisWriter> gis;
    std::vector<SceneWriter*> writers;
    std::vector<std::string> names;
    // The ground is encoded once, here, for every writer that writes or embeds it.
    const auto ground = scene.ground_texture ? std::make_shared<const EncodedGround>(scene.ground_texture) : nullptr;
    if (exports.povray) {
      PovrayExportOptions options;
      options.final_dir = out_dir;
      options.ground = ground;
      povray = std::make_unique<PovrayWriter>(scene, staging, options);
      writers.push_back(povray.get());
      names.emplace_back("POV-Ray");
    }
    if (exports.blender) {
      BlenderExportOptions options;
      options.ground = ground;
      blender = std::make_unique<BlenderWriter>(scene, staging / "blender", options);
      writers.push_back(blender.get());
      names.emplace_back("Blender");
    }
    if (exports.gltf) {
      GltfOptions options;
      options.ground = ground;
      gltf = std::make_unique<GltfWriter>(scene, staging / "scene.glb", options);
      writers.push_back(gltf.get());
      names.emplace_back("glTF");
    }
    if (exports.gis) {
      gis = std::make_unique<GisWriter>(scene, staging / kGisPlantsFile, staging / kGisCoverFile, exports.gis_crs);
      writers.push_back(gis.get());
      names.emplace_back("GIS");
    }
    // The tiles that receive flowers, for the folder's readers (folder_state.h): collected from
    // the writers' pass, or from a pass of their own when nothing else places the field.
    std::optional<PlacedTileCollector> placed;
    if (scene.field) placed.emplace(*scene.field);
    if (!writers.empty()) {
      std::string list;
      for (const auto& name : names) list += (list.empty() ? "" : ", ") + name;
      say(observer, "placing flowers and writing " + list);
      const Extent& area = scene.field_area;
      const auto on_batch = [&](const InstanceBatch& batch) {
        if (placed) placed->add(batch);
        if (!observer.placing || batch.empty() || !(area.height() > 0)) return;
        observer.placing(std::clamp((batch.y.back() - area.min_y) / area.height(), 0.0, 1.0));
      };
      const StreamTotals totals = run_scene_stream(scene, writers, on_batch);
      summary.instances = totals.instances;
      summary.per_variant = totals.per_variant;
      if (scene.last_placement) summary.field = *scene.last_placement;
      summary.stand_ins = scene.stand_ins;
      if (observer.placing) observer.placing(1.0);
    }
    if (povray) summary.povray_bytes = povray->stats().total_bytes;
    if (scene.field) {
      const PlacedTiles tiles = writers.empty() ? place_tiles(*scene.field) : placed->result();
      write_folder_state(staging, scene_text, scene, tiles);
    }
    if (also_write) also_write(staging);
    write_file_atomically(staging / kFolderSceneFile, scene_text);
    if (!scene_base_dir.empty())
      write_file_atomically(staging / kSceneBaseFile, fs::absolute(scene_base_dir).lexically_normal().string() + "\n");
    staged.publish(observer.warning);
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

SceneFolderSummary build_scene_folder(const SceneConfig& config, const fs::path& out_dir,
                                      const SceneFolderObserver& observer) {
  // Refuse an unusable folder before the (long) scene assembly.
  check_scene_folder_target(out_dir);
  const Scene scene = make_scene(config, observer.stage);
  return write_scene_folder(scene, config.exports, config.text, out_dir, observer, config.base_dir);
}

SceneConfig load_scene_folder_config(const fs::path& dir) {
  const fs::path file = dir / kFolderSceneFile;
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw Error(file, "", "is missing: give a folder written by `wangscape build`");
  const std::string text = read_text_file(file, kMaxSceneFileBytes, "scene file");
  fs::path base = dir;
  if (fs::is_regular_file(dir / kSceneBaseFile, ec)) {
    std::string line = read_text_file(dir / kSceneBaseFile, 1 << 16, "scene base file");
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    if (!line.empty()) base = line;
  }
  return parse_scene_config(text, file, base);
}

}  // namespace wangscape
