#include "renders/scene_build.h"

namespace wangscape {

SceneFolderSummary build_scene(const SceneConfig& config, const std::filesystem::path& out_dir,
                               const SceneBuildObserver& observer) {
  check_scene_folder_target(out_dir);  // before the scene is assembled
  const Scene scene = make_scene(config, observer.folder.stage);
  // The LDIs are sampled from the tile set, not from the placed field: a pass of their own,
  // into the staging folder, so the packs are published with the scene they were made from.
  StagedWriter pack;
  if (config.exports.ldi)
    pack = [&](const std::filesystem::path& staging) {
      build_scene_ldi_packs(scene, staging, ldi_options(config), observer.ldi);
    };
  return write_scene_folder(scene, config.exports, config.text, out_dir, observer.folder, config.base_dir, pack);
}

}  // namespace wangscape
