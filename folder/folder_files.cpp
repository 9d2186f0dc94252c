#include "folder/folder_files.h"

#include "exporters/povray_writer.h"

namespace wangscape {

namespace fs = std::filesystem;

// The one table of a scene folder's names (docs/scene-folder.md).
fs::path FolderFiles::scene_file() const { return root_ / "scene.toml"; }
fs::path FolderFiles::scene_base() const { return root_ / "scene_base.txt"; }
fs::path FolderFiles::tiles() const { return root_ / "tiles.json"; }
fs::path FolderFiles::state() const { return root_ / "scene.cache"; }
fs::path FolderFiles::pack() const { return root_ / "tiles.ldi"; }
fs::path FolderFiles::steep_pack() const { return root_ / "steep.ldi"; }
fs::path FolderFiles::sky_shares() const { return root_ / "sky.bin"; }
fs::path FolderFiles::ground_light() const { return root_ / "ground_light.bin"; }
fs::path FolderFiles::povray_scene() const { return root_ / kPovraySceneFile; }
fs::path FolderFiles::blender() const { return root_ / "blender"; }
fs::path FolderFiles::gltf() const { return root_ / "scene.glb"; }
fs::path FolderFiles::gis_plants() const { return root_ / "plants.gpkg"; }
fs::path FolderFiles::gis_cover() const { return root_ / "cover.tif"; }

}  // namespace wangscape
