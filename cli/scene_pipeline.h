// The main job as functions: a scene file (SceneConfig) -> the assembled Scene (terrain mesh,
// sunflower models, the lazily placed instance stream, camera above the ground, sun) -> the
// exporters the file enables, written into an output folder all at once.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "cli/scene_config.h"
#include "exporters/scene.h"

namespace wangscape::cli {

// Stage messages and progress (the CLI shows them on stderr when it is a terminal).
struct PipelineObserver {
  std::function<void(const std::string& message)> stage;                           // "loading terrain ..."
  std::function<void(std::uint64_t done, std::uint64_t total)> instances_written;  // while exporting
};

// Assembles the Scene a config describes. Terrain, models and the instance count are computed
// here; the instances themselves are placed again each time Scene::instances is called (the
// stream is deterministic and owns everything it needs). Throws Error, Error,
// Error or Error naming what is wrong.
Scene make_scene(const SceneConfig& config, const PipelineObserver& observer = {});

// Exporters besides POV-Ray plug in here (Blender arrays, glTF): each is called with the scene
// and the staging folder, whose contents become `final_dir` once every exporter succeeded.
using SceneExporter =
    std::function<void(const Scene& scene, const SceneConfig& config, const std::filesystem::path& staging_dir,
                       const std::filesystem::path& final_dir)>;
struct SceneExporterHooks {
  SceneExporter blender;  // run when [exports] blender = true
  SceneExporter gltf;     // run when [exports] gltf = true
};
// The process-wide hooks; set them before build_scene_folder runs (e.g. in a register_* function).
SceneExporterHooks& scene_exporter_hooks();

struct BuildSummary {
  std::uint64_t instances = 0;
  std::uint64_t bytes = 0;  // POV-Ray files
  double seconds = 0;
};

// Runs the pipeline and writes every enabled export, plus a copy of the scene file
// (DIR/scene.toml), into `out_dir`. Everything is written into a staging folder beside it first:
// on failure nothing changes in `out_dir`. An existing folder keeps files the build does not write.
BuildSummary build_scene_folder(const SceneConfig& config, const std::filesystem::path& out_dir,
                                const PipelineObserver& observer = {});

}  // namespace wangscape::cli
