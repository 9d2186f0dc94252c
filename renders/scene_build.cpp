#include "renders/scene_build.h"

#include "renders/trace/field_sky.h"

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
      // The flowers' sky share the view shades with, estimated once here instead of on its first frame.
      if (observer.ldi.stage) observer.ldi.stage("estimating the flowers' share of the sky");
      write_sky_shares(staging / kFolderSkyFile,
                       bake_field_sky(scene, with_sun(ldi_options(config).shading, scene.sun)));
    };
  return write_scene_folder(scene, config.exports, config.text, out_dir, observer.folder, config.base_dir, pack);
}

}  // namespace wangscape
