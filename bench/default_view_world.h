// The default scene's view world for the view benchmarks: its pack built once per run into a
// temporary file (about 25 s), mapped, and removed.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <memory>
#include <string>

#include "renders/ldi/ldi_scene.h"
#include "renders/view/view_world.h"
#include "scene/scene.h"
#include "scene/scene_file.h"

namespace wangscape::bench {

// The default scene's world, and the same world lit without sun-shadow rays (BM_ViewRayCastUnshadowed),
// both from one pack built once per run.
struct Worlds {
  std::shared_ptr<const ViewWorld> lit, unshadowed;
};

inline const Worlds& default_worlds() {
  static const Worlds worlds = [] {
    const SceneConfig config = default_scene_config();
    const std::filesystem::path pack =
        std::filesystem::temp_directory_path() / ("wangscape-view-bench-" + std::to_string(::getpid()) + ".ldi");
    Scene scene = make_scene(config);
    build_scene_ldi_pack(scene, pack, ldi_options(config));
    ShadingSettings unshadowed = ldi_options(config).shading;
    unshadowed.shadows = false;
    Worlds made{std::make_shared<const ViewWorld>(std::move(scene), pack, ldi_options(config).shading),
                std::make_shared<const ViewWorld>(make_scene(config), pack, unshadowed)};
    std::filesystem::remove(pack);  // the pack stays mapped
    return made;
  }();
  return worlds;
}

inline std::shared_ptr<const ViewWorld> default_world() { return default_worlds().lit; }

}  // namespace wangscape::bench
