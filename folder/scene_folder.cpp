#include "folder/scene_folder.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <vector>

#include "core/atomic_file.h"
#include "core/staged_folder.h"
#include "core/text_file.h"
#include "exporters/blender_export.h"
#include "exporters/export_support.h"
#include "exporters/gis_writer.h"
#include "exporters/gltf_writer.h"
#include "exporters/povray_writer.h"
#include "exporters/scene_writer.h"
#include "folder/pack_light.h"

namespace wangscape {

namespace fs = std::filesystem;

namespace {

void say(const SceneFolderObserver& observer, const std::string& message) {
  if (observer.stage) observer.stage(message);
}

// The enabled exports' writers, each with its name for the progress line; the ground is encoded
// once, here, for every writer that writes or embeds it.
struct Writers {
  std::vector<std::unique_ptr<SceneWriter>> owned;
  std::vector<SceneWriter*> all;
  std::string names;
  const PovrayWriter* povray = nullptr;

  void add(std::unique_ptr<SceneWriter> writer, const char* name) {
    all.push_back(writer.get());
    owned.push_back(std::move(writer));
    names += (names.empty() ? "" : ", ") + std::string(name);
  }
};

Writers make_writers(const FolderBuild& build) {
  const Scene& scene = build.scene;
  const ExportsConfig& exports = build.source.exports;
  const auto ground = scene.ground_texture ? std::make_shared<const EncodedGround>(scene.ground_texture) : nullptr;
  Writers writers;
  if (exports.povray) {
    PovrayExportOptions options;
    options.final_dir = build.target;
    options.ground = ground;
    auto povray = std::make_unique<PovrayWriter>(scene, build.staging.root(), options);
    writers.povray = povray.get();
    writers.add(std::move(povray), "POV-Ray");
  }
  if (exports.blender) {
    BlenderExportOptions options;
    options.ground = ground;
    writers.add(std::make_unique<BlenderWriter>(scene, build.staging.blender(), options), "Blender");
  }
  if (exports.gltf) {
    GltfOptions options;
    options.ground = ground;
    writers.add(std::make_unique<GltfWriter>(scene, build.staging.gltf(), options), "glTF");
  }
  if (exports.gis)
    writers.add(
        std::make_unique<GisWriter>(scene, build.staging.gis_plants(), build.staging.gis_cover(), exports.gis_crs),
        "GIS");
  return writers;
}

// The writers' stage: the scene's instance stream run once, each batch to every writer; the same
// pass notes the tiles that receive flowers, for the kept state.
void write_exports(FolderBuild& build) {
  Writers writers = make_writers(build);
  if (writers.all.empty()) return;
  const Scene& scene = build.scene;
  const SceneFolderObserver& observer = build.observer;
  std::optional<PlacedTileCollector> placed;
  if (scene.field) placed.emplace(*scene.field);
  say(observer, "placing flowers and writing " + writers.names);
  const Extent& area = scene.field_area;
  const auto on_batch = [&](const InstanceBatch& batch) {
    if (placed) placed->add(batch);
    if (!observer.placing || batch.empty() || !(area.height() > 0)) return;
    observer.placing(std::clamp((batch.y.back() - area.min_y) / area.height(), 0.0, 1.0));
  };
  const StreamTotals totals = run_scene_stream(scene, writers.all, on_batch);
  SceneFolderSummary& summary = build.summary;
  summary.instances = totals.instances;
  summary.per_variant = totals.per_variant;
  if (scene.last_placement) summary.field = *scene.last_placement;
  summary.stand_ins = scene.stand_ins;
  if (observer.placing) observer.placing(1.0);
  if (writers.povray) summary.povray_bytes = writers.povray->stats().total_bytes;
  if (placed) build.placed = placed->result();
}

// The state kept for the readers: the placed tiles from the writers' pass, or from a pass of
// their own when nothing else placed the field.
void keep_state(FolderBuild& build) {
  if (!build.scene.field) return;
  if (!build.placed) build.placed = place_tiles(*build.scene.field);
  write_folder_state(build.staging, build.source.scene_text, build.scene, *build.placed);
}

// The scene file as built, and the folder its relative paths resolve against.
void keep_scene_file(FolderBuild& build) {
  write_file_atomically(build.staging.scene_file(), build.source.scene_text);
  if (!build.source.scene_base.empty())
    write_file_atomically(build.staging.scene_base(),
                          fs::absolute(build.source.scene_base).lexically_normal().string() + "\n");
}

bool files_resolve(const SceneConfig& c) {
  std::error_code ec;
  for (const fs::path& p : {c.terrain.dem, c.masks.mask})
    if (!p.empty() && !fs::exists(p, ec)) return false;
  return std::all_of(c.models.mesh.begin(), c.models.mesh.end(), [&](const fs::path& p) { return fs::exists(p, ec); });
}

// The folder's scene file, parsed against the folder of the one rule (SceneFolder::open).
SceneConfig read_scene_file(const FolderFiles& files) {
  const fs::path file = files.scene_file();
  const std::string text = read_text_file(file, kMaxSceneFileBytes, "scene file");
  std::error_code ec;
  if (fs::is_regular_file(files.scene_base(), ec)) {
    std::string line = read_text_file(files.scene_base(), 1 << 16, "scene base file");
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    if (!line.empty()) return parse_scene_config(text, file, line);
  }
  SceneConfig config = parse_scene_config(text, file, files.root());
  if (files_resolve(config)) return config;
  SceneConfig from_data = parse_scene_config(text, file, data_root());
  return files_resolve(from_data) ? from_data : config;
}

}  // namespace

void SceneFolder::check_target(const fs::path& out_dir_in) {
  if (out_dir_in.empty()) throw Error("the output folder is empty: give a folder name");
  const auto out_dir = fs::absolute(out_dir_in).lexically_normal();
  std::error_code ec;
  if (!fs::exists(out_dir, ec)) return;
  if (!fs::is_directory(out_dir, ec)) throw Error(out_dir, "", "exists and is not a folder");
  const fs::path scene_file = FolderFiles(out_dir).scene_file();
  if (fs::is_empty(out_dir, ec) || fs::is_regular_file(scene_file, ec)) return;
  throw Error(out_dir, "",
              "exists and is not a scene folder (it has no " + scene_file.filename().string() +
                  "); give a new or empty folder, or an earlier build's");
}

SceneFolderSummary SceneFolder::write(const Scene& scene, const FolderSource& source, const fs::path& out_dir,
                                      const SceneFolderObserver& observer, const std::vector<FolderStage>& more) {
  const auto start = std::chrono::steady_clock::now();
  check_target(out_dir);
  StagedFolder staged(out_dir);
  const FolderFiles staging(staged.path());
  FolderBuild build{scene, source, staging, staged.target(), observer, {}, {}};
  std::vector<FolderStage> stages{write_exports, keep_state};
  stages.insert(stages.end(), more.begin(), more.end());
  stages.emplace_back(keep_scene_file);
  for (const FolderStage& stage : stages) stage(build);
  staged.publish(observer.warning);
  build.summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return build.summary;
}

SceneFolderSummary SceneFolder::build(const SceneConfig& config, const fs::path& out_dir,
                                      const SceneFolderObserver& observer, const std::vector<FolderStage>& more) {
  check_target(out_dir);  // before the (long) scene assembly
  const Scene scene = wangscape::make_scene(config, observer.stage);
  return write(scene, {config.exports, config.text, config.base_dir}, out_dir, observer, more);
}

SceneFolder SceneFolder::open(const fs::path& dir, Parts parts) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(dir, "", "no such scene folder (make one with wangscape build)");
  SceneFolder folder{FolderFiles(dir)};
  const FolderFiles& files = folder.files_;
  if (!fs::is_regular_file(files.scene_file(), ec))
    throw Error(files.scene_file(), "", "missing: the folder was not written by wangscape build");
  if (parts == Parts::pack && !fs::is_regular_file(files.pack(), ec))
    throw Error(files.pack(), "", "missing: build the folder from a scene with [exports] ldi = true");
  // The pack before the scene file's files: a corrupt pack is refused before anything is assembled.
  if (parts != Parts::scene_file && fs::is_regular_file(files.pack(), ec))
    folder.pack_ = std::make_shared<const LdiPack>(files.pack());
  folder.config_ = read_scene_file(files);
  if (parts == Parts::scene_file) return folder;
  folder.state_ = read_folder_state(files, folder.config_.text);
  const LdiPack* pack = folder.pack_.get();
  folder.light_ = pack && pack->info().light ? recorded_light(*pack->info().light) : scene_file_light(folder.config_);
  if (parts != Parts::pack) return folder;
  if (fs::is_regular_file(files.steep_pack(), ec))
    folder.steep_pack_ = std::make_shared<const LdiPack>(files.steep_pack());
  if (fs::is_regular_file(files.sky_shares(), ec)) folder.sky_shares_ = files.sky_shares();
  if (fs::is_regular_file(files.ground_light(), ec)) folder.ground_light_ = files.ground_light();
  return folder;
}

Scene SceneFolder::make_scene(const StageObserver& stage) const {
  return wangscape::make_scene(config_, stage, &state_.prebuilt);
}

}  // namespace wangscape
