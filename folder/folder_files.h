// Where a scene folder's files are (docs/scene-folder.md): every name of a scene folder is spelled
// in folder_files.cpp and nowhere else. Readers and the build's stages ask a FolderFiles for a
// file's path, under the published folder or under its staging folder. The POV-Ray export's own
// files are its writer's (exporters/povray_writer.h); the folder names only its entry.
#pragma once

#include <cstdint>
#include <filesystem>

namespace wangscape {

class FolderFiles {
 public:
  // The format of what the build keeps for its readers (scene.cache): version 2 adds the set's
  // tile at each placed cell, version 3 the scene's models; a version 1 or 2 folder still opens
  // (its readers run the tiling again, make the models again), a folder of another version is
  // refused, with what to do.
  static constexpr std::uint32_t kFormatVersion = 3;
  static constexpr std::uint32_t kOldestFormatVersion = 1;

  explicit FolderFiles(std::filesystem::path root) : root_(std::move(root)) {}
  const std::filesystem::path& root() const { return root_; }

  // The scene file as built (always there), and the folder its relative paths resolve against
  // (one line; only when the scene file had relative paths).
  std::filesystem::path scene_file() const;
  std::filesystem::path scene_base() const;
  // What the readers need to open the folder fast (folder/folder_state.h): the filled tile set
  // and the versioned cache (the scene file's fingerprint, the placed tiles, the baked ground, the
  // models).
  std::filesystem::path tiles() const;
  std::filesystem::path state() const;
  // [exports] ldi: the tiles' LDI pack, the steep sets' pack, the flowers' sky shares and the
  // light the plants leave on the ground under them.
  std::filesystem::path pack() const;
  std::filesystem::path steep_pack() const;
  std::filesystem::path sky_shares() const;
  std::filesystem::path ground_light() const;
  // The writers' outputs: the POV-Ray scene (its entry file), the Blender folder, the glTF file,
  // the GIS plant layer and its cover.
  std::filesystem::path povray_scene() const;
  std::filesystem::path blender() const;
  std::filesystem::path gltf() const;
  std::filesystem::path gis_plants() const;
  std::filesystem::path gis_cover() const;

 private:
  std::filesystem::path root_;
};

}  // namespace wangscape
