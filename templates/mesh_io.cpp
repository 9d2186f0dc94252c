#include "templates/mesh_io.h"

#include <assimp/BaseImporter.h>
#include <assimp/GltfMaterial.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <istream>
#include <limits>
#include <map>
#include <memory>
#include <ostream>
#include <sstream>
#include <string_view>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "core/number_text.h"

namespace wangscape {
namespace {

// Assimp's steps: triangles (polygons split; points and lines stay, and are skipped below), one
// vertex per distinct corner, every node's transform applied (so a scene graph becomes one mesh
// per material), normals where the file has none, and Assimp's own check of what its importer
// made. Not aiProcess_SortByPType: in Assimp 5.2 it crashes (SIGBUS) on a mutated PLY the
// model_file fuzzer found (fuzz/corpus/model_file/regress-sort-by-ptype-bus.seed).
constexpr unsigned kImportSteps = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
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

// One Mesh from Assimp's meshes `parts` of `scene`: their triangles concatenated, the materials they use in
// order of first use.
Mesh mesh_from_scene(const aiScene& scene, const std::filesystem::path& folder, const std::string& source,
                     const std::vector<unsigned>& parts) {
  Mesh mesh;
  std::vector<int> slot_of(scene.mNumMaterials, -1);
  bool any_uvs = false;
  ImageCache images;
  for (const unsigned m : parts) {
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

}  // namespace

// ---- PLY: read by hand -------------------------------------------------------------------
// Assimp 5.2's PLY reader never returns on some damaged headers (a missing end_header, a stray
// byte in an element line) and one of its steps crashes on another: the model_file fuzzer found
// all three within seconds (fuzz/corpus/model_file/regress-*). This reader was fuzzed for 10^6
// runs before Assimp came; it also keeps write_ply's `comment material` colours.

namespace {

std::vector<std::string_view> split_whitespace(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

template <class Number>
bool parse_number(std::string_view token, Number& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return error == std::errc() && end == token.data() + token.size() && std::isfinite(value);
}

bool parse_integer(std::string_view token, long long& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return error == std::errc() && end == token.data() + token.size();
}

// A material by name, grey until the file colours it.
Material material_named(const std::string& name) { return Material{name, {0.5f, 0.5f, 0.5f}, 0.5f, 0.0f}; }

}  // namespace

namespace {

enum class PlyScalar { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

bool parse_scalar(std::string_view name, PlyScalar& type) {
  static constexpr std::pair<std::string_view, PlyScalar> kNames[] = {
      {"char", PlyScalar::int8},      {"int8", PlyScalar::int8},       {"uchar", PlyScalar::uint8},
      {"uint8", PlyScalar::uint8},    {"short", PlyScalar::int16},     {"int16", PlyScalar::int16},
      {"ushort", PlyScalar::uint16},  {"uint16", PlyScalar::uint16},   {"int", PlyScalar::int32},
      {"int32", PlyScalar::int32},    {"uint", PlyScalar::uint32},     {"uint32", PlyScalar::uint32},
      {"float", PlyScalar::float32},  {"float32", PlyScalar::float32}, {"double", PlyScalar::float64},
      {"float64", PlyScalar::float64}};
  for (const auto& [text, value] : kNames) {
    if (text == name) {
      type = value;
      return true;
    }
  }
  return false;
}

std::size_t scalar_size(PlyScalar type) {
  switch (type) {
    case PlyScalar::int8:
    case PlyScalar::uint8:
      return 1;
    case PlyScalar::int16:
    case PlyScalar::uint16:
      return 2;
    case PlyScalar::int32:
    case PlyScalar::uint32:
    case PlyScalar::float32:
      return 4;
    case PlyScalar::float64:
      return 8;
  }
  return 0;
}

struct PlyProperty {
  std::string name;
  PlyScalar type = PlyScalar::float32;  // for lists: the item type
  bool is_list = false;
  PlyScalar count_type = PlyScalar::uint8;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

// Values of ASCII PLY: one element instance per line.
class PlyAsciiReader {
 public:
  PlyAsciiReader(std::istream& in, const std::string& source, std::size_t header_lines)
      : in_(in), source_(source), line_number_(header_lines) {}

  void begin(const std::string& element, std::size_t index) {
    element_ = &element;
    index_ = index;
    do {
      ++line_number_;
      if (!std::getline(in_, line_)) fail("unexpected end of file");
      tokens_ = split_whitespace(line_);
    } while (tokens_.empty());
    next_token_ = 0;
  }
  double next(PlyScalar type) {
    if (next_token_ >= tokens_.size()) fail("too few values on the line");
    // float properties parse straight to float: written floats come back bit for bit.
    float single = 0;
    double value = 0;
    const bool ok = type == PlyScalar::float32 ? parse_number(tokens_[next_token_], single)
                                               : parse_number(tokens_[next_token_], value);
    if (!ok) fail("'" + std::string(tokens_[next_token_]) + "' is not a finite number");
    ++next_token_;
    return type == PlyScalar::float32 ? double(single) : value;
  }
  [[noreturn]] void fail(const std::string& message) const {
    throw Error(source_ + ":" + std::to_string(line_number_) + ": " + *element_ + " " + std::to_string(index_) + ": " +
                message);
  }

 private:
  std::istream& in_;
  const std::string& source_;
  std::size_t line_number_;
  std::string line_;
  std::vector<std::string_view> tokens_;
  std::size_t next_token_ = 0;
  const std::string* element_ = nullptr;
  std::size_t index_ = 0;
};

// Values of binary_little_endian PLY.
class PlyBinaryReader {
 public:
  PlyBinaryReader(std::istream& in, const std::string& source) : in_(in), source_(source) {}

  void begin(const std::string& element, std::size_t index) {
    element_ = &element;
    index_ = index;
  }
  double next(PlyScalar type) {
    unsigned char bytes[8];
    const std::size_t size = scalar_size(type);
    if (!in_.read(reinterpret_cast<char*>(bytes), std::streamsize(size))) fail("unexpected end of file");
    if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + size);
    switch (type) {
      case PlyScalar::int8:
        return as<std::int8_t>(bytes);
      case PlyScalar::uint8:
        return as<std::uint8_t>(bytes);
      case PlyScalar::int16:
        return as<std::int16_t>(bytes);
      case PlyScalar::uint16:
        return as<std::uint16_t>(bytes);
      case PlyScalar::int32:
        return as<std::int32_t>(bytes);
      case PlyScalar::uint32:
        return as<std::uint32_t>(bytes);
      case PlyScalar::float32:
        return checked(as<float>(bytes));
      case PlyScalar::float64:
        return checked(as<double>(bytes));
    }
    return 0;
  }
  [[noreturn]] void fail(const std::string& message) const {
    throw Error(source_ + ": " + *element_ + " " + std::to_string(index_) + ": " + message);
  }

 private:
  template <class T>
  static double as(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof value);
    return double(value);
  }
  double checked(double value) const {
    if (!std::isfinite(value)) fail("value is not a finite number");
    return value;
  }

  std::istream& in_;
  const std::string& source_;
  const std::string* element_ = nullptr;
  std::size_t index_ = 0;
};

struct PlyHeader {
  bool binary = false;
  std::vector<PlyElement> elements;
  std::vector<Material> comment_materials;  // from "comment material <i> <name> <r> <g> <b>"
  std::size_t line_count = 0;
};

PlyHeader read_ply_header(std::istream& in, const std::string& source) {
  PlyHeader header;
  std::string line;
  const auto fail = [&](const std::string& message) {
    throw Error(source + ":" + std::to_string(header.line_count) + ": " + message);
  };
  const auto next_line = [&] {
    if (!std::getline(in, line)) fail("unexpected end of file in the PLY header (expected 'end_header')");
    ++header.line_count;
    if (!line.empty() && line.back() == '\r') line.pop_back();
  };
  next_line();
  if (line != "ply") fail("not a PLY file (expected 'ply' on the first line)");
  bool has_format = false;
  while (true) {
    next_line();
    const auto tokens = split_whitespace(line);
    if (tokens.empty()) continue;
    if (tokens[0] == "end_header") break;
    if (tokens[0] == "format") {
      if (tokens.size() < 2) fail("expected a format name");
      if (tokens[1] == "ascii") {
        header.binary = false;
      } else if (tokens[1] == "binary_little_endian") {
        header.binary = true;
      } else {
        fail("unsupported PLY format '" + std::string(tokens[1]) + "' (expected ascii or binary_little_endian)");
      }
      has_format = true;
    } else if (tokens[0] == "element") {
      long long count = 0;
      if (tokens.size() != 3 || !parse_integer(tokens[2], count) || count < 0) {
        fail("expected 'element <name> <count>'");
      }
      header.elements.push_back({std::string(tokens[1]), std::size_t(count), {}});
    } else if (tokens[0] == "property") {
      if (header.elements.empty()) fail("property before any element");
      PlyProperty property;
      if (tokens.size() == 5 && tokens[1] == "list") {
        property.is_list = true;
        if (!parse_scalar(tokens[2], property.count_type) || !parse_scalar(tokens[3], property.type)) {
          fail("unknown type in list property '" + std::string(tokens[4]) + "'");
        }
        if (property.count_type == PlyScalar::float32 || property.count_type == PlyScalar::float64) {
          fail("list count type of '" + std::string(tokens[4]) + "' must be an integer type");
        }
        property.name = std::string(tokens[4]);
      } else if (tokens.size() == 3) {
        if (!parse_scalar(tokens[1], property.type)) fail("unknown property type '" + std::string(tokens[1]) + "'");
        property.name = std::string(tokens[2]);
      } else {
        fail("expected 'property <type> <name>' or 'property list <count type> <item type> <name>'");
      }
      header.elements.back().properties.push_back(property);
    } else if (tokens[0] == "comment" && tokens.size() == 7 && tokens[1] == "material") {
      long long index;
      Material material;
      float rgb[3];
      if (parse_integer(tokens[2], index) && parse_number(tokens[4], rgb[0]) && parse_number(tokens[5], rgb[1]) &&
          parse_number(tokens[6], rgb[2]) && index == (long long)header.comment_materials.size()) {
        material = material_named(std::string(tokens[3]));
        material.base_color = {rgb[0], rgb[1], rgb[2]};
        header.comment_materials.push_back(material);
      }
    } else if (tokens[0] != "comment" && tokens[0] != "obj_info") {
      fail("unexpected header line '" + line + "'");
    }
  }
  if (!has_format) fail("missing 'format' line in the PLY header");
  return header;
}

int property_index(const PlyElement& element, std::string_view name) {
  for (std::size_t i = 0; i < element.properties.size(); ++i) {
    if (element.properties[i].name == name) return int(i);
  }
  return -1;
}

template <class Reader>
Mesh read_ply_body(Reader& reader, const PlyHeader& header, const std::string& source) {
  Mesh mesh;
  mesh.name = std::filesystem::path(source).stem().string();
  bool has_vertices = false, has_faces = false, has_normals = false, has_material = false;
  std::size_t vertex_count = 0;
  // Guards reserve() against absurd counts in a damaged header.
  constexpr std::size_t kReserveLimit = std::size_t(1) << 24;

  for (const PlyElement& element : header.elements) {
    std::vector<double> values(element.properties.size());
    std::vector<std::uint32_t> polygon;
    const bool is_vertex = element.name == "vertex";
    const bool is_face = element.name == "face";
    int xyz[3] = {-1, -1, -1}, nxyz[3] = {-1, -1, -1}, list = -1, material = -1;
    if (is_vertex) {
      static constexpr const char* kAxes[3] = {"x", "y", "z"};
      static constexpr const char* kNormalAxes[3] = {"nx", "ny", "nz"};
      for (int axis = 0; axis < 3; ++axis) {
        xyz[axis] = property_index(element, kAxes[axis]);
        nxyz[axis] = property_index(element, kNormalAxes[axis]);
        if (xyz[axis] < 0 || element.properties[xyz[axis]].is_list) {
          throw Error(source + ": element vertex has no scalar property '" + kAxes[axis] + "'");
        }
      }
      has_vertices = true;
      has_normals = nxyz[0] >= 0 && nxyz[1] >= 0 && nxyz[2] >= 0;
      vertex_count = element.count;
      mesh.positions.reserve(std::min(element.count, kReserveLimit));
      if (has_normals) mesh.normals.reserve(std::min(element.count, kReserveLimit));
    } else if (is_face) {
      list = property_index(element, "vertex_indices");
      if (list < 0) list = property_index(element, "vertex_index");
      if (list < 0 || !element.properties[list].is_list) {
        throw Error(source + ": element face has no list property 'vertex_indices'");
      }
      material = property_index(element, "material");
      has_material = material >= 0 && !element.properties[material].is_list;
      has_faces = true;
      mesh.triangles.reserve(std::min(element.count, kReserveLimit));
    }

    for (std::size_t index = 0; index < element.count; ++index) {
      reader.begin(element.name, index);
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        if (!property.is_list) {
          values[p] = reader.next(property.type);
          continue;
        }
        const double count = reader.next(property.count_type);
        if (count < 0 || count != std::floor(count)) reader.fail("invalid list length for '" + property.name + "'");
        const bool keep = int(p) == list;
        if (keep) polygon.clear();
        for (std::size_t i = 0; i < std::size_t(count); ++i) {
          const double item = reader.next(property.type);
          if (!keep) continue;
          if (item < 0 || item >= double(vertex_count) || item != std::floor(item)) {
            reader.fail("vertex index " + std::to_string(item) + " out of range (" + std::to_string(vertex_count) +
                        " vertices)");
          }
          polygon.push_back(std::uint32_t(item));
        }
      }
      if (is_vertex) {
        mesh.positions.push_back({float(values[xyz[0]]), float(values[xyz[1]]), float(values[xyz[2]])});
        if (has_normals)
          mesh.normals.push_back({float(values[nxyz[0]]), float(values[nxyz[1]]), float(values[nxyz[2]])});
      } else if (is_face) {
        if (polygon.size() < 3) reader.fail("a face needs at least 3 vertices, got " + std::to_string(polygon.size()));
        std::uint16_t material_index = 0;
        if (has_material) {
          const double m = values[material];
          if (m < 0 || m >= double(std::max<std::size_t>(1, header.comment_materials.size()))) {
            reader.fail("material " + std::to_string(m) + " has no 'comment material' line");
          }
          material_index = std::uint16_t(m);
        }
        for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
          mesh.triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
          mesh.triangle_material.push_back(material_index);
        }
      }
    }
  }
  if (!has_vertices) throw Error(source + ": no 'element vertex' in the PLY header");
  if (!has_faces || mesh.triangles.empty()) throw Error(source + ": no faces (expected 'element face')");
  mesh.materials = header.comment_materials;
  if (mesh.materials.empty()) mesh.materials.push_back(material_named("default"));
  if (!has_normals) mesh.normals.clear();
  finish_normals(mesh);
  return mesh;
}

}  // namespace

Mesh read_ply(std::istream& in, const std::string& source_name) {
  const PlyHeader header = read_ply_header(in, source_name);
  if (header.binary) {
    PlyBinaryReader reader(in, source_name);
    return read_ply_body(reader, header, source_name);
  }
  PlyAsciiReader reader(in, source_name, header.line_count);
  return read_ply_body(reader, header, source_name);
}

namespace {

// A PLY file by its name or its first line: read_ply's, never Assimp's.
bool is_ply(const std::string& extension, std::string_view head) {
  const std::string first = lowercase(std::string(head.substr(0, 4)));
  return lowercase(extension) == ".ply" || lowercase(extension) == "ply" || first == "ply\n" || first == "ply\r";
}

// Text formats handed to Assimp must hold no NUL byte: Assimp 5.2's OBJ reader wrote through a
// null pointer on a `usemtl` line with NULs in it (found by fuzz_model_file). Throws an Error
// naming the first one's line; `line` is the line `text` starts on (the file is read in chunks).
bool is_text_format(const std::string& extension) {
  const std::string e = lowercase(extension.starts_with('.') ? extension.substr(1) : extension);
  return e == "obj" || e == "dae" || e == "gltf";
}
void refuse_nul(std::string_view text, std::uint64_t& line, const std::string& source, const std::string& extension) {
  const std::size_t nul = text.find('\0');
  const std::string_view before = text.substr(0, nul);
  line += std::uint64_t(std::count(before.begin(), before.end(), '\n'));
  if (nul == std::string_view::npos) return;
  throw Error(source, std::to_string(line),
              "holds a NUL byte; a " + extension + " file is text (a damaged or binary file under that name?)");
}

// An importer without Assimp's PLY reader: Assimp picks readers by the bytes too (the word "ply"
// in a file's first 200 bytes is enough), so that reader must not be there to pick. The importer
// does not free a reader it no longer holds: freed here.
std::unique_ptr<Assimp::Importer> make_importer() {
  auto importer = std::make_unique<Assimp::Importer>();
  if (Assimp::BaseImporter* ply = importer->GetImporter("ply")) {
    if (importer->UnregisterLoader(ply) == AI_SUCCESS) delete ply;
  }
  return importer;
}

}  // namespace

namespace {

// Whether the file at `path` is PLY (read by read_ply); throws when it is missing or unreadable.
bool is_ply_file(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw Error(path, "", "no such model file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "", "cannot open the file for reading");
  char head[4] = {};
  in.read(head, sizeof head);
  return is_ply(path.extension().string(), std::string_view(head, std::size_t(in.gcount())));
}

Mesh load_ply(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return read_ply(in, path.string());
}

// Assimp's scene of a model file other than PLY (its text checked for NULs first). With
// `keep_objects` the file's node tree stays, each mesh moved into the file's space, so that its
// objects can be told apart; else meshes of one material are joined.
const aiScene& import_file(const std::filesystem::path& path, Assimp::Importer& importer, bool keep_objects) {
  if (is_text_format(path.extension().string())) {
    std::ifstream in(path, std::ios::binary);
    std::string chunk(1 << 16, '\0');
    std::uint64_t line = 1;
    while (in.read(chunk.data(), std::streamsize(chunk.size())) || in.gcount() > 0)
      refuse_nul(std::string_view(chunk.data(), std::size_t(in.gcount())), line, path.string(),
                 path.extension().string());
  }
  importer.SetPropertyBool(AI_CONFIG_PP_PTV_KEEP_HIERARCHY, keep_objects);
  const aiScene* scene = importer.ReadFile(path.string(), kImportSteps);
  if (scene == nullptr) throw Error(path, "", std::string("not a model Assimp reads: ") + importer.GetErrorString());
  return *scene;
}

std::vector<unsigned> every_mesh(const aiScene& scene) {
  std::vector<unsigned> parts(scene.mNumMeshes);
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) parts[m] = m;
  return parts;
}

// The triangle meshes of `node` itself.
void add_own_meshes(const aiScene& scene, const aiNode& node, std::vector<unsigned>& parts) {
  for (unsigned i = 0; i < node.mNumMeshes; ++i)
    if (const unsigned m = node.mMeshes[i];
        m < scene.mNumMeshes && (scene.mMeshes[m]->mPrimitiveTypes & aiPrimitiveType_TRIANGLE))
      parts.push_back(m);
}

// The triangle meshes under `node`, depth first (a stack, not recursion: a file may nest deep).
std::vector<unsigned> meshes_under(const aiScene& scene, const aiNode& node) {
  std::vector<unsigned> parts;
  std::vector<const aiNode*> stack{&node};
  while (!stack.empty()) {
    const aiNode* at = stack.back();
    stack.pop_back();
    add_own_meshes(scene, *at, parts);
    for (unsigned c = at->mNumChildren; c-- > 0;) stack.push_back(at->mChildren[c]);
  }
  return parts;
}

// A file's objects: below the wrappers exporters put around a scene (nodes of no mesh and one
// child), each child node holding triangles is one object, and the node's own triangles one more.
std::vector<std::pair<std::string, std::vector<unsigned>>> scene_objects(const aiScene& scene) {
  std::vector<std::pair<std::string, std::vector<unsigned>>> objects;
  const aiNode* top = scene.mRootNode;
  while (top != nullptr && top->mNumMeshes == 0 && top->mNumChildren == 1) top = top->mChildren[0];
  if (top == nullptr) return objects;
  std::vector<unsigned> own;
  add_own_meshes(scene, *top, own);
  if (!own.empty()) objects.emplace_back(top->mName.C_Str(), own);
  for (unsigned c = 0; c < top->mNumChildren; ++c)
    if (auto parts = meshes_under(scene, *top->mChildren[c]); !parts.empty())
      objects.emplace_back(top->mChildren[c]->mName.C_Str(), std::move(parts));
  return objects;
}

}  // namespace

Mesh load_mesh(const std::filesystem::path& path) {
  if (is_ply_file(path)) return load_ply(path);
  const auto importer = make_importer();
  const aiScene& scene = import_file(path, *importer, false);
  std::error_code error;
  Mesh mesh =
      mesh_from_scene(scene, std::filesystem::absolute(path, error).parent_path(), path.string(), every_mesh(scene));
  mesh.name = path.stem().string();
  return mesh;
}

std::vector<Mesh> load_mesh_objects(const std::filesystem::path& path) {
  if (is_ply_file(path)) return {load_ply(path)};
  const auto importer = make_importer();
  const aiScene& scene = import_file(path, *importer, true);
  std::error_code error;
  const std::filesystem::path folder = std::filesystem::absolute(path, error).parent_path();
  std::vector<Mesh> meshes;
  for (const auto& [name, parts] : scene_objects(scene)) {
    meshes.push_back(mesh_from_scene(scene, folder, path.string(), parts));
    meshes.back().name = name.empty() ? path.stem().string() + "_" + std::to_string(meshes.size() - 1) : name;
  }
  if (meshes.empty()) throw Error(path, "", "no triangles (expected faces, not only points or lines)");
  return meshes;
}

bool is_model_file_name(const std::filesystem::path& path) {
  const std::string extension = lowercase(path.extension().string());
  return extension == ".ply" || (extension.size() > 1 && Assimp::Importer().IsExtensionSupported(extension));
}

Mesh read_model(std::span<const std::uint8_t> bytes, const std::string& extension, const std::string& source_name) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (is_ply(extension, text)) {
    std::istringstream in(std::string(text), std::ios::binary);
    return read_ply(in, source_name);
  }
  if (is_text_format(extension)) {
    std::uint64_t line = 1;
    refuse_nul(text, line, source_name, extension);
  }
  const auto importer = make_importer();
  const std::string hint = lowercase(extension.starts_with('.') ? extension.substr(1) : extension);
  const aiScene* scene = importer->ReadFileFromMemory(bytes.data(), bytes.size(), kImportSteps, hint.c_str());
  if (scene == nullptr)
    throw Error(source_name, "", std::string("not a model Assimp reads: ") + importer->GetErrorString());
  Mesh mesh = mesh_from_scene(*scene, {}, source_name, every_mesh(*scene));
  mesh.name = std::filesystem::path(source_name).stem().string();
  return mesh;
}

Mesh load_user_model(const std::filesystem::path& path, const UserModelOptions& options) {
  if (!(options.scale > 0) || !std::isfinite(options.scale)) {
    throw Error(path.string() + ": model scale " + std::to_string(options.scale) + " is invalid: expected > 0");
  }
  Mesh mesh = load_mesh(path);
  to_model_space(mesh, options);
  return mesh;
}

void to_model_space(Mesh& mesh, const UserModelOptions& options) {
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
}

}  // namespace wangscape
