#include "templates/model_variants.h"

#include <algorithm>

#include "core/error.h"

namespace wangscape {

namespace {

// The objects of one file stand apart in it (they cannot all stand on its origin): each is moved
// so that its footprint (x-y box) is centred on the origin, its heights kept.
void centre_footprint(Mesh& mesh) {
  const MeshExtent extent = measure_extent(mesh);
  const float dx = -0.5f * (extent.min[0] + extent.max[0]), dy = -0.5f * (extent.min[1] + extent.max[1]);
  for (auto& p : mesh.positions) {
    p[0] += dx;
    p[1] += dy;
  }
}

}  // namespace

std::vector<std::filesystem::path> model_files_in(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> files;
  std::error_code error;
  for (auto it = std::filesystem::directory_iterator(folder, error);
       !error && it != std::filesystem::directory_iterator(); it.increment(error))
    if (it->is_regular_file(error) && is_model_file_name(it->path())) files.push_back(it->path());
  if (error) throw Error(folder, "", "cannot list the folder: " + error.message());
  if (files.empty())
    throw Error(folder, "",
                "the folder holds no model file (expected .obj, .gltf, .glb, .fbx, .dae, .ply or another "
                "format Assimp reads)");
  // By name, so that the variants keep their numbers whatever order the file system lists them in.
  std::sort(files.begin(), files.end(),
            [](const auto& a, const auto& b) { return a.filename().string() < b.filename().string(); });
  return files;
}

std::vector<Mesh> load_model_variants(const std::vector<std::filesystem::path>& named, bool objects_as_variants,
                                      const UserModelOptions& options) {
  std::vector<Mesh> variants;
  const auto add = [&](const std::filesystem::path& file) {
    if (!objects_as_variants) {
      variants.push_back(load_user_model(file, options));
    } else {
      for (Mesh& object : load_mesh_objects(file)) {
        to_model_space(object, options);
        centre_footprint(object);
        variants.push_back(std::move(object));
      }
    }
    if (variants.size() > kMaxModelVariants)
      throw Error(file, "",
                  "takes the model variants to " + std::to_string(variants.size()) + "; at most " +
                      std::to_string(kMaxModelVariants) + " are drawn");
  };
  for (const std::filesystem::path& path : named) {
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
      for (const auto& file : model_files_in(path)) add(file);
    } else {
      add(path);
    }
  }
  return variants;
}

}  // namespace wangscape
