// A scene folder (docs/scene-folder.md) as one type: where its files are (folder/folder_files.h),
// its build as a list of stages staged beside the target and published in one swap, and opening
// it for a reader with one message for each way a folder can be unusable.
//
// The build's stages, in order: the writers (the scene's instance stream run once, every batch
// fanned out to each enabled export: POV-Ray, Blender arrays, glTF, the GIS layer and cover), the
// state kept for the readers (folder/folder_state.h), the stages the builder hands in (the LDI
// pack, renders/ldi/ldi_scene.h: never called from here), and the scene file. Only then is the
// folder swapped in: a reader sees the old folder or the new one.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "folder/folder_files.h"
#include "folder/folder_state.h"
#include "folder/ldi_pack.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "scene/shading_light.h"

namespace wangscape {

struct SceneFolderObserver {
  StageObserver stage;                           // "writing POV-Ray scene ..."
  std::function<void(double fraction)> placing;  // 0..1 of the field's rows placed and written
  StageObserver warning;                         // what the user should know even off a terminal
};

struct SceneFolderSummary {
  std::uint64_t instances = 0;
  std::vector<std::uint64_t> per_variant;
  std::uint64_t povray_bytes = 0;         // POV-Ray files
  std::optional<FieldReport> field;       // tiles visible, placed and culled, models and proxies (a scene's field)
  std::vector<StandInFigures> stand_ins;  // the user's models' stand-ins (Scene::stand_ins)
  double seconds = 0;
};

// What a folder is built from besides its Scene: the exports it enables, the scene file's text
// (kept as the folder's scene file) and the folder its relative paths resolve against (kept
// beside it, so that open() finds the DEM and the masks again; empty: the scene file's folder
// is not kept).
struct FolderSource {
  ExportsConfig exports;
  std::string scene_text;
  std::filesystem::path scene_base;
};

// What the stages of one build share: the scene, where they write (the staging folder), where it
// will be published, and the summary and placed tiles the stages fill in.
struct FolderBuild {
  const Scene& scene;
  const FolderSource& source;
  const FolderFiles& staging;
  const std::filesystem::path& target;  // the folder once published (POV-Ray's Library_Path)
  const SceneFolderObserver& observer;
  SceneFolderSummary summary;
  std::optional<PlacedTiles> placed;  // the field's tiles that received a flower, once a stage found them
};
// One stage of a build: writes its files into build.staging.
using FolderStage = std::function<void(FolderBuild& build)>;

class SceneFolder {
 public:
  // ---- building ----

  // Throws Error when `out_dir` cannot be a scene folder: it exists and is not a folder, or is a
  // folder that is neither empty nor an earlier scene folder (no scene file). Cheap: call it
  // before assembling a scene, so a bad --out fails at once.
  static void check_target(const std::filesystem::path& out_dir);
  // Runs the stages (the writers, the kept state, `more`, the scene file) into a folder staged as
  // ".<name>.partial-<pid>" beside `out_dir`, then publishes it in one swap; an existing `out_dir`
  // is replaced whole, so no file of an earlier build stays behind. Throws Error naming the folder
  // or file at fault; on failure `out_dir` is as it was.
  static SceneFolderSummary write(const Scene& scene, const FolderSource& source, const std::filesystem::path& out_dir,
                                  const SceneFolderObserver& observer = {}, const std::vector<FolderStage>& more = {});
  // check_target, make_scene(config), then write() with the config's exports, text and folder.
  static SceneFolderSummary build(const SceneConfig& config, const std::filesystem::path& out_dir,
                                  const SceneFolderObserver& observer = {}, const std::vector<FolderStage>& more = {});

  // ---- opening ----

  // What open() reads, each with the ones before: the scene file; the state the build kept and
  // the light its pack was shaded with (the pack opened where the folder has one); the pack,
  // which must be there, with the steep sets' pack, the sky shares and the ground light where the
  // folder has them.
  enum class Parts { scene_file, state, pack };
  // Opens the scene folder DIR. The scene file's relative paths resolve by one rule: against the
  // folder the build kept (the scene file's own at build time), else against DIR; where its files
  // are still not found (a folder from before that was kept), against the data folder
  // (data_root(), as the default scene's are). Throws Error naming the file at fault, one message
  // for each: no such folder; no scene file (not written by `wangscape build`); no kept state or
  // another version of it (an older build), a scene file edited since the build, a corrupt state;
  // no pack (built without [exports] ldi), a corrupt pack.
  static SceneFolder open(const std::filesystem::path& dir, Parts parts = Parts::state);

  const FolderFiles& files() const { return files_; }
  const SceneConfig& config() const { return config_; }
  // Parts::state on: the field's tiles that received a flower (with the set's tile at each, but
  // from a version 1 scene.cache: placed_set_tiles gives them), and the folder's Scene as its build
  // made it (make_scene of config() with the kept tile set, ground bake and models; the models
  // made again from a scene.cache older than version 3). Throws Error as make_scene does.
  const PlacedTiles& placed() const { return state_.placed; }
  Scene make_scene(const StageObserver& stage = {}) const;
  // Parts::state on: the light the pack was shaded with, before the sun (with_sun of the scene's
  // sun gives the pack's): the pack's record (folder/pack_light.h), or for a folder whose pack
  // records none (an older pack, or no pack) the light its scene file's [ldi] section gives.
  const ShadingSettings& light() const { return light_; }
  // Parts::pack: the pack, mapped once; the steep sets' pack, the sky shares' file and the ground
  // light's, null and empty where the folder has none (built before them: the view makes them).
  const std::shared_ptr<const LdiPack>& pack() const { return pack_; }
  const std::shared_ptr<const LdiPack>& steep_pack() const { return steep_pack_; }
  const std::filesystem::path& sky_shares() const { return sky_shares_; }
  const std::filesystem::path& ground_light() const { return ground_light_; }

 private:
  explicit SceneFolder(FolderFiles files) : files_(std::move(files)) {}
  FolderFiles files_;
  SceneConfig config_;
  FolderState state_;
  ShadingSettings light_;
  std::shared_ptr<const LdiPack> pack_, steep_pack_;
  std::filesystem::path sky_shares_, ground_light_;
};

}  // namespace wangscape
