#include "renders/scene_build.h"

namespace wangscape {

SceneFolderSummary build_scene(const SceneConfig& config, const std::filesystem::path& out_dir,
                               const SceneBuildObserver& observer) {
  std::vector<FolderStage> stages;
  if (config.exports.ldi) stages.push_back(ldi_folder_stage(ldi_options(config), observer.ldi));
  return SceneFolder::build(config, out_dir, observer.folder, stages);
}

}  // namespace wangscape
