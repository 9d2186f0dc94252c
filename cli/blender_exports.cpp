// Plugs the Blender-array and glTF exporters into the scene pipeline (cli/scene_pipeline.h):
// `[exports] blender = true` writes DIR/blender/ (manifest.json, arrays, the add-on zip),
// `[exports] gltf = true` writes DIR/scene.glb.
#include "cli/command.h"
#include "cli/scene_pipeline.h"
#include "exporters/blender_export.h"
#include "exporters/gltf_writer.h"

namespace wangscape::cli {

void register_blender_gltf_exporters() {
  auto& hooks = scene_exporter_hooks();
  hooks.blender = [](const Scene& scene, const SceneConfig&, const std::filesystem::path& staging_dir,
                     const std::filesystem::path&) { export_blender(scene, staging_dir / "blender"); };
  hooks.gltf = [](const Scene& scene, const SceneConfig&, const std::filesystem::path& staging_dir,
                  const std::filesystem::path&) { write_gltf(scene, staging_dir / "scene.glb"); };
}

}  // namespace wangscape::cli
