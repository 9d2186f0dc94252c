// Writing a scene folder: the scene's instance stream is run once and every batch is fanned
// out to each enabled writer (POV-Ray, Blender arrays, glTF, the GIS layer and cover); the folder is built beside the
// target and swapped in with renames, so a reader sees the old folder or the new one.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_file.h"

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

// Writes more files into the staging folder (its path) before it is published: what a stage
// above the exporters adds to a folder (the LDI pack), so that it is published with the rest.
using StagedWriter = std::function<void(const std::filesystem::path& staging_dir)>;

// Writes the exports `exports` enables plus `scene_text` as DIR/scene.toml into `out_dir`, and
// what the folder's readers need to open it fast (exporters/folder_state.h), then `also_write`'s
// files.
// The folder is staged as ".<name>.partial-<pid>" beside it; an existing `out_dir` must be a
// scene folder (it holds scene.toml) or empty, and is replaced whole, so no file of an earlier
// build stays behind. Throws Error naming the folder or file at fault; on failure `out_dir`
// is as it was.
// `scene_base_dir`, when given, is the folder the relative paths of `scene_text` resolve against
// (SceneConfig::base_dir): it is kept in DIR/scene_base.txt so that load_scene_folder_config
// finds the DEM and the masks again.
SceneFolderSummary write_scene_folder(const Scene& scene, const ExportsConfig& exports, const std::string& scene_text,
                                      const std::filesystem::path& out_dir, const SceneFolderObserver& observer = {},
                                      const std::filesystem::path& scene_base_dir = {},
                                      const StagedWriter& also_write = {});

// The scene file of a folder written by write_scene_folder (DIR/scene.toml), its relative paths
// resolved against the folder DIR/scene_base.txt names (the scene file's own folder at build
// time), or against DIR when that file is absent. make_scene of it gives the folder's Scene
// again. Throws Error naming DIR/scene.toml (missing, or the parser's file:line message).
SceneConfig load_scene_folder_config(const std::filesystem::path& dir);

// Throws Error when `out_dir` cannot be a scene folder: it exists and is not a folder, or is a
// folder that is neither empty nor an earlier scene folder (no scene.toml). Cheap: call it
// before assembling a scene, so a bad --out fails at once.
void check_scene_folder_target(const std::filesystem::path& out_dir);

// check_scene_folder_target, make_scene(config), then write_scene_folder.
SceneFolderSummary build_scene_folder(const SceneConfig& config, const std::filesystem::path& out_dir,
                                      const SceneFolderObserver& observer = {});

}  // namespace wangscape
