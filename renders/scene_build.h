// `wangscape build`: a scene file to a published scene folder (folder/scene_folder.h), its stages
// the folder's own (the writers, the state kept for the readers) and, with [exports] ldi, the LDI
// stage renders/ldi contributes (the two packs, the sky shares and the ground light): a build
// that fails or is killed at any stage leaves the previous folder as it was, or no folder.
#pragma once

#include <filesystem>

#include "folder/scene_folder.h"
#include "renders/ldi/ldi_scene.h"
#include "scene/scene_file.h"

namespace wangscape {

struct SceneBuildObserver {
  SceneFolderObserver folder;  // stages and the field's placement
  LdiSceneObserver ldi;        // the LDI pack's progress
};

// Builds `config` into `out_dir`. Throws Error naming the file or folder at fault; on failure
// `out_dir` is as it was.
SceneFolderSummary build_scene(const SceneConfig& config, const std::filesystem::path& out_dir,
                               const SceneBuildObserver& observer = {});

}  // namespace wangscape
