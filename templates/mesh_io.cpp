#include "templates/mesh_io.h"

#include <assimp/GltfMaterial.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <ostream>
#include <string_view>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "core/number_text.h"

namespace wangscape {
namespace {

// Assimp's steps: triangles only (points and lines are dropped), one vertex per distinct corner,
// every node's transform applied (so a scene graph becomes one mesh per material), normals where
// the file has none, and Assimp's own check of what its importer made.
constexpr unsigned kImportSteps = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
                                  aiProcess_PreTransformVertices | aiProcess_GenSmoothNormals |
                                  aiProcess_ValidateDataStructure;

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

// Largest image a material may map: 16384 x 16384 texels (1 GiB of RGBA).
constexpr double kMaxTexels = 16384.0 * 16384.0;

// A file name for the image's copy in a scene folder: letters, digits, '_' and '-' only.
std::string image_name(const std::string& text) {
  std::string name;
  for (const char c : text) name += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
  return name.empty() ? std::string("image") : name;
}

// Decodes an image through OpenImageIO (from `proxy` when given, else the file) to RGBA8.
std::shared_ptr<const TextureImage> decode_image(const std::string& file_name, OIIO::Filesystem::IOProxy* proxy,
                                                 const std::string& name, const std::string& source,
                                                 const std::string& place) {
  auto input = OIIO::ImageInput::open(file_name, nullptr, proxy);
  if (!input) throw Error(source, place, "cannot read its image " + file_name + ": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  const int channels = spec.nchannels;
  if (spec.width <= 0 || spec.height <= 0 || double(spec.width) * double(spec.height) > kMaxTexels || channels <= 0)
    throw Error(source, place,
                "its image " + file_name + " is " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                    " texels: expected at least 1 x 1 and at most 16384 x 16384");
  const std::size_t texels = std::size_t(spec.width) * std::size_t(spec.height);
  std::vector<std::uint8_t> pixels(texels * std::size_t(channels));
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data()))
    throw Error(source, place, "cannot read its image " + file_name + ": " + input->geterror());
  auto image = std::make_shared<TextureImage>();
  image->name = name;
  image->width = spec.width;
  image->height = spec.height;
  image->rgba.resize(texels * 4);
  // Grey is replicated; an image without alpha covers everything.
  const bool has_alpha = channels == 2 || channels >= 4;
  for (std::size_t i = 0; i < texels; ++i) {
    const std::uint8_t* from = &pixels[i * std::size_t(channels)];
    std::uint8_t* to = &image->rgba[i * 4];
    const bool grey = channels < 3;
    to[0] = from[0];
    to[1] = grey ? from[0] : from[1];
    to[2] = grey ? from[0] : from[2];
    to[3] = has_alpha ? from[grey ? 1 : 3] : 255;
  }
  return image;
}

// The image `reference` names: one the model file holds ("*0" in a GLB, or an embedded name),
// else a file relative to the model's folder (written with '\' by Windows exporters).
std::shared_ptr<const TextureImage> material_image(const aiScene& scene, const std::string& reference,
                                                   const std::filesystem::path& folder, const std::string& source,
                                                   const std::string& material) {
  const std::string place = "material '" + material + "'";
  const std::string model = std::filesystem::path(source).stem().string();
  if (const auto [held, index] = scene.GetEmbeddedTextureAndIndex(reference.c_str()); held != nullptr) {
    if (held->mHeight != 0 || held->pcData == nullptr)
      throw Error(source, place, "its image is held as raw texels: expected an encoded image (PNG, JPEG)");
    std::string hint = lowercase(held->achFormatHint);
    if (hint.empty() || !std::all_of(hint.begin(), hint.end(), [](unsigned char c) { return std::isalnum(c); }))
      hint = "png";
    OIIO::Filesystem::IOMemReader bytes(held->pcData, held->mWidth);
    return decode_image("held." + hint, &bytes, image_name(model + "_" + std::to_string(index)), source, place);
  }
  if (reference.starts_with('*') || folder.empty())
    throw Error(source, place, "its image '" + reference + "' is not in the file");
  std::string relative = reference;
  std::replace(relative.begin(), relative.end(), '\\', '/');
  const std::filesystem::path file = (folder / relative).lexically_normal();
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error))
    throw Error(source, place, "its image '" + reference + "' is not at " + file.string());
  return decode_image(file.string(), nullptr, image_name(file.stem().string()), source, place);
}

// Base colour (glTF's baseColorFactor, else the diffuse colour: an MTL's Kd), its image, the
// roughness where the file gives one, and alpha: glTF's MASK (BLEND is cut at its cutoff too,
// as Wangscape draws no partial coverage) or an MTL's map_d.
// How far into a file a PLY header's 'end_header' is looked for.
constexpr std::size_t kPlyHeaderLimit = 1 << 20;

// One image per reference: materials that share an image share its texels.
using ImageCache = std::map<std::string, std::shared_ptr<const TextureImage>>;

Material read_material(const aiScene& scene, const aiMaterial& source_material, const std::filesystem::path& folder,
                       const std::string& source, ImageCache& images) {
  Material material;
  aiString name;
  if (source_material.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) material.name = name.C_Str();
  if (material.name.empty()) material.name = "default";
  aiColor4D color(0.5f, 0.5f, 0.5f, 1.0f);
  if (source_material.Get(AI_MATKEY_BASE_COLOR, color) != AI_SUCCESS)
    source_material.Get(AI_MATKEY_COLOR_DIFFUSE, color);
  const auto unit = [](float value) { return std::isfinite(value) ? std::clamp(value, 0.0f, 1.0f) : 0.5f; };
  material.base_color = {unit(color.r), unit(color.g), unit(color.b)};
  float roughness = material.roughness;
  if (source_material.Get(AI_MATKEY_ROUGHNESS_FACTOR, roughness) == AI_SUCCESS) material.roughness = unit(roughness);
  aiString reference;
  if (source_material.GetTexture(aiTextureType_BASE_COLOR, 0, &reference) == AI_SUCCESS ||
      source_material.GetTexture(aiTextureType_DIFFUSE, 0, &reference) == AI_SUCCESS) {
    auto& image = images[reference.C_Str()];
    if (!image) image = material_image(scene, reference.C_Str(), folder, source, material.name);
    material.base_color_map = image;
  }
  aiString alpha_mode;
  float cutoff = 0.5f;
  if (source_material.Get(AI_MATKEY_GLTF_ALPHAMODE, alpha_mode) == AI_SUCCESS) {
    if (std::string(alpha_mode.C_Str()) != "OPAQUE") {
      source_material.Get(AI_MATKEY_GLTF_ALPHACUTOFF, cutoff);
      material.alpha_cutoff = std::isfinite(cutoff) ? std::clamp(cutoff, 1.0f / 256.0f, 1.0f) : 0.5f;
    }
  } else if (source_material.GetTextureCount(aiTextureType_OPACITY) > 0) {
    material.alpha_cutoff = cutoff;
  }
  if (!material.base_color_map) material.alpha_cutoff = 0;  // alpha comes from the image
  return material;
}

// Normals from the file (or Assimp's) if every one is usable, else computed.
void finish_normals(Mesh& mesh) {
  bool all_valid = mesh.normals.size() == mesh.positions.size();
  for (auto& n : mesh.normals) {
    if (!all_valid) break;
    const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    all_valid = length > 1e-12f && std::isfinite(length);
    if (all_valid)
      for (float& c : n) c /= length;
  }
  if (!all_valid) compute_vertex_normals(mesh);
}

// One Mesh from Assimp's scene: its triangle meshes concatenated, the materials they use in
// order of first use.
Mesh mesh_from_scene(const aiScene& scene, const std::filesystem::path& folder, const std::string& source) {
  Mesh mesh;
  std::vector<int> slot_of(scene.mNumMaterials, -1);
  bool any_uvs = false;
  ImageCache images;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& part = *scene.mMeshes[m];
    if (!(part.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || part.mNumVertices == 0) continue;
    if (part.mMaterialIndex >= scene.mNumMaterials) throw Error(source, "", "a mesh names a material it lacks");
    int& slot = slot_of[part.mMaterialIndex];
    if (slot < 0) {
      if (mesh.materials.size() > std::numeric_limits<std::uint16_t>::max())
        throw Error(source, "", "more than 65536 materials");
      slot = int(mesh.materials.size());
      mesh.materials.push_back(read_material(scene, *scene.mMaterials[part.mMaterialIndex], folder, source, images));
    }
    const std::size_t first = mesh.positions.size();
    if (first + part.mNumVertices > std::numeric_limits<std::uint32_t>::max())
      throw Error(source, "", "more than 2^32 vertices");
    for (unsigned v = 0; v < part.mNumVertices; ++v) {
      const aiVector3D& p = part.mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw Error(source, "mesh " + std::to_string(m) + ", vertex " + std::to_string(v),
                    "a position is not a finite number");
      mesh.positions.push_back({p.x, p.y, p.z});
      const aiVector3D n = part.mNormals ? part.mNormals[v] : aiVector3D(0, 0, 0);
      mesh.normals.push_back({n.x, n.y, n.z});
      const aiVector3D uv = part.mTextureCoords[0] ? part.mTextureCoords[0][v] : aiVector3D(0, 0, 0);
      mesh.uvs.push_back({std::isfinite(uv.x) ? uv.x : 0.0f, std::isfinite(uv.y) ? uv.y : 0.0f});
      any_uvs = any_uvs || part.mTextureCoords[0] != nullptr;
    }
    for (unsigned f = 0; f < part.mNumFaces; ++f) {
      const aiFace& face = part.mFaces[f];
      if (face.mNumIndices != 3) continue;  // a point or line Assimp kept beside triangles
      std::array<std::uint32_t, 3> triangle{};
      for (int corner = 0; corner < 3; ++corner) {
        if (face.mIndices[corner] >= part.mNumVertices)
          throw Error(source, "mesh " + std::to_string(m) + ", face " + std::to_string(f), "a vertex index is outside");
        triangle[corner] = std::uint32_t(first + face.mIndices[corner]);
      }
      mesh.triangles.push_back(triangle);
      mesh.triangle_material.push_back(std::uint16_t(slot));
    }
  }
  if (mesh.triangles.empty()) throw Error(source, "", "no triangles (expected faces, not only points or lines)");
  if (!any_uvs) mesh.uvs.clear();
  finish_normals(mesh);
  return mesh;
}

// Assimp 5.2's PLY reader never returns on a header without its 'end_header' line (found while
// testing this reader): such a file is refused before Assimp sees it. `head` is the file's start.
void refuse_unfinished_ply_header(std::string_view head, const std::string& source) {
  if (head.size() < 3 || lowercase(std::string(head.substr(0, 3))) != "ply") return;
  if (head.find("end_header") == std::string_view::npos)
    throw Error(source, "",
                "a PLY header without 'end_header' in its first " + std::to_string(kPlyHeaderLimit) + " bytes");
}

void configure(Assimp::Importer& importer) {
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
}

void require_writable(const std::ostream& out, const char* format) {
  if (!out) throw Error(std::string("writing ") + format + " failed (stream error)");
}

}  // namespace

Mesh load_mesh(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw Error(path, "", "no such model file");
  {
    std::ifstream in(path, std::ios::binary);
    std::string head(kPlyHeaderLimit, '\0');
    in.read(head.data(), std::streamsize(head.size()));
    head.resize(std::size_t(in.gcount()));
    refuse_unfinished_ply_header(head, source);
  }
  Assimp::Importer importer;
  configure(importer);
  const aiScene* scene = importer.ReadFile(source, kImportSteps);
  if (scene == nullptr) throw Error(path, "", std::string("not a model Assimp reads: ") + importer.GetErrorString());
  Mesh mesh = mesh_from_scene(*scene, std::filesystem::absolute(path, error).parent_path(), source);
  mesh.name = path.stem().string();
  return mesh;
}

Mesh read_model(std::span<const std::uint8_t> bytes, const std::string& extension, const std::string& source_name) {
  refuse_unfinished_ply_header(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), std::min(bytes.size(), kPlyHeaderLimit)),
      source_name);
  Assimp::Importer importer;
  configure(importer);
  const std::string hint = lowercase(extension.starts_with('.') ? extension.substr(1) : extension);
  const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), kImportSteps, hint.c_str());
  if (scene == nullptr)
    throw Error(source_name, "", std::string("not a model Assimp reads: ") + importer.GetErrorString());
  Mesh mesh = mesh_from_scene(*scene, {}, source_name);
  mesh.name = std::filesystem::path(source_name).stem().string();
  return mesh;
}

void write_obj(std::ostream& out, const Mesh& mesh) {
  std::string text = "# written by wangscape\no " + (mesh.name.empty() ? std::string("mesh") : mesh.name) + "\n";
  const auto append_vector = [&](const char* keyword, const std::array<float, 3>& v) {
    text += keyword;
    for (float c : v) {
      text += ' ';
      append_number(text, c);
    }
    text += '\n';
  };
  for (const auto& p : mesh.positions) append_vector("v", p);
  for (const auto& n : mesh.normals) append_vector("vn", n);
  const bool has_normals = mesh.normals.size() == mesh.positions.size();
  int current_material = -1;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int material = t < mesh.triangle_material.size() ? mesh.triangle_material[t] : 0;
    if (material != current_material && std::size_t(material) < mesh.materials.size()) {
      text += "usemtl " + mesh.materials[material].name + "\n";
      current_material = material;
    }
    text += 'f';
    for (std::uint32_t v : mesh.triangles[t]) {
      text += ' ';
      append_number(text, std::uint64_t(v) + 1);
      if (has_normals) {
        text += "//";
        append_number(text, std::uint64_t(v) + 1);
      }
    }
    text += '\n';
  }
  out.write(text.data(), std::streamsize(text.size()));
  require_writable(out, "OBJ");
}

void write_ply(std::ostream& out, const Mesh& mesh, PlyFormat format) {
  const bool binary = format == PlyFormat::binary_little_endian;
  const bool has_normals = mesh.normals.size() == mesh.positions.size();
  std::string text = "ply\nformat ";
  text += binary ? "binary_little_endian" : "ascii";
  text += " 1.0\ncomment written by wangscape\n";
  for (std::size_t i = 0; i < mesh.materials.size(); ++i) {
    const Material& m = mesh.materials[i];
    text += "comment material " + std::to_string(i) + " " + m.name;
    for (float c : m.base_color) {
      text += ' ';
      append_number(text, c);
    }
    text += '\n';
  }
  text += "element vertex " + std::to_string(mesh.positions.size()) + "\nproperty float x\nproperty float y\n";
  text += "property float z\n";
  if (has_normals) text += "property float nx\nproperty float ny\nproperty float nz\n";
  text += "element face " + std::to_string(mesh.triangles.size()) + "\n";
  text += "property list uchar uint vertex_indices\nproperty ushort material\nend_header\n";

  const auto material_of = [&](std::size_t t) -> std::uint16_t {
    return t < mesh.triangle_material.size() ? mesh.triangle_material[t] : 0;
  };
  if (binary) {
    // Bytes in little-endian order whatever the host.
    const auto put = [&](auto value) {
      unsigned char bytes[sizeof value];
      std::memcpy(bytes, &value, sizeof value);
      if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof value);
      text.append(reinterpret_cast<const char*>(bytes), sizeof value);
    };
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      for (float c : mesh.positions[v]) put(c);
      if (has_normals) {
        for (float c : mesh.normals[v]) put(c);
      }
    }
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      put(std::uint8_t(3));
      for (std::uint32_t i : mesh.triangles[t]) put(i);
      put(material_of(t));
    }
  } else {
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      const char* separator = "";
      for (float c : mesh.positions[v]) {
        text += separator;
        append_number(text, c);
        separator = " ";
      }
      if (has_normals) {
        for (float c : mesh.normals[v]) {
          text += ' ';
          append_number(text, c);
        }
      }
      text += '\n';
    }
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      text += '3';
      for (std::uint32_t i : mesh.triangles[t]) {
        text += ' ';
        append_number(text, std::uint64_t(i));
      }
      text += ' ';
      append_number(text, std::uint64_t(material_of(t)));
      text += '\n';
    }
  }
  out.write(text.data(), std::streamsize(text.size()));
  require_writable(out, "PLY");
}

Mesh load_user_model(const std::filesystem::path& path, const UserModelOptions& options) {
  if (!(options.scale > 0) || !std::isfinite(options.scale)) {
    throw Error(path.string() + ": model scale " + std::to_string(options.scale) + " is invalid: expected > 0");
  }
  Mesh mesh = load_mesh(path);
  // y-up to z-up is a quarter turn about +x: (x, y, z) -> (x, -z, y); it keeps handedness.
  const auto orient = [&](std::array<float, 3> v) -> std::array<float, 3> {
    return options.y_up ? std::array<float, 3>{v[0], -v[2], v[1]} : v;
  };
  for (auto& p : mesh.positions) {
    p = orient(p);
    for (float& c : p) c *= options.scale;
  }
  for (auto& n : mesh.normals) n = orient(n);
  if (options.ground_at_origin) {
    const MeshExtent extent = measure_extent(mesh);
    const float shift[3] = {-0.5f * (extent.min[0] + extent.max[0]), -0.5f * (extent.min[1] + extent.max[1]),
                            -extent.min[2]};
    for (auto& p : mesh.positions) {
      for (int axis = 0; axis < 3; ++axis) p[axis] += shift[axis];
    }
  }
  return mesh;
}

}  // namespace wangscape
