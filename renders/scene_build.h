// `wangscape build`: a scene file to a published scene folder. The one owner of a folder's
// build: the scene is made once, the writers' files, what the readers need to open it fast
// (exporters/folder_state.h) and, with [exports] ldi, the LDI pack (renders/ldi/ldi_scene.h) are
// all staged together and published in one swap (exporters/scene_folder.h): a build that fails
// or is killed at any stage leaves the previous folder as it was, or no folder.
#pragma once

#include <filesystem>

#include "exporters/scene_folder.h"
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
