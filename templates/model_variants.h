// The variants a user's models give ([models] mesh, [[species]] model in docs/scene-file.md): each
// file named one variant, a folder its model files sorted by name, one variant each, and with
// objects as variants each object of a file one variant.
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include "templates/mesh.h"
#include "templates/mesh_io.h"

namespace wangscape {

// At most this many variants a species or [models] (the `variants` keys' own limit).
constexpr std::size_t kMaxModelVariants = 1000;

// The model files (is_model_file_name) of `folder`, sorted by name; not its subfolders. Throws
// Error naming the folder when it holds none.
std::vector<std::filesystem::path> model_files_in(const std::filesystem::path& folder);

// The variants of the files and folders `named`, in order: a file one variant (load_user_model),
// or with `objects_as_variants` one variant an object (load_mesh_objects), each object's footprint
// (x-y box) centred on the origin and its heights kept; a folder its model_files_in.
// Each mesh is named as its loader names it. Throws Error naming the file at fault, or the
// folder or file that takes the count beyond kMaxModelVariants.
std::vector<Mesh> load_model_variants(const std::vector<std::filesystem::path>& named, bool objects_as_variants,
                                      const UserModelOptions& options);

}  // namespace wangscape
