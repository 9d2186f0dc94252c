#include "templates/mesh_io.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <istream>
#include <ostream>
#include <string_view>
#include <unordered_map>

#include "core/number_text.h"
#include "templates/sunflower.h"

namespace wangscape {
namespace {

// ---- shared helpers ----

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

// A material by name; the sunflower names keep the sunflower colors so a user model can reuse them.
Material material_named(const std::string& name) {
  for (const Material& known : sunflower_materials()) {
    if (known.name == name) return known;
  }
  return Material{name, {0.5f, 0.5f, 0.5f}, 0.5f, 0.0f};
}

// Collects the materials of a file in order of first use.
class MaterialTable {
 public:
  std::uint16_t index_of(const std::string& name) {
    for (std::size_t i = 0; i < materials_.size(); ++i) {
      if (materials_[i].name == name) return std::uint16_t(i);
    }
    materials_.push_back(material_named(name));
    return std::uint16_t(materials_.size() - 1);
  }
  std::vector<Material> take() { return std::move(materials_); }

 private:
  std::vector<Material> materials_;
};

// Normals from the file if it gave one for every vertex, else computed; then zero-length or
// missing ones are recomputed too.
void finish_normals(Mesh& mesh, bool file_has_normals) {
  if (file_has_normals) {
    bool all_valid = true;
    for (auto& n : mesh.normals) {
      const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(length > 1e-12f) || !std::isfinite(length)) {
        all_valid = false;
        break;
      }
      for (float& c : n) c /= length;
    }
    if (all_valid) return;
  }
  compute_vertex_normals(mesh);
}

void require_writable(const std::ostream& out, const char* format) {
  if (!out) throw Error(std::string("writing ") + format + " failed (stream error)");
}

// ---- OBJ ----

struct ObjCorner {
  std::uint32_t position;
  std::int64_t normal;  // -1: none
};

}  // namespace

Mesh read_obj(std::istream& in, const std::string& source_name) {
  std::vector<std::array<float, 3>> positions, normals;
  std::vector<ObjCorner> corners;  // three per triangle
  std::vector<std::uint16_t> triangle_material;
  MaterialTable materials;
  std::string current_material = "default";

  std::string line;
  std::size_t line_number = 0;
  const auto fail = [&](const std::string& message) {
    throw Error(source_name + ":" + std::to_string(line_number) + ": " + message);
  };
  const auto read_vector = [&](const std::vector<std::string_view>& tokens, const char* what) {
    if (tokens.size() < 4) fail(std::string("expected 3 numbers after '") + what + "'");
    std::array<float, 3> v{};
    for (int axis = 0; axis < 3; ++axis) {
      // Parsed straight to float: written floats come back bit for bit.
      if (!parse_number(tokens[axis + 1], v[axis])) {
        fail("'" + std::string(tokens[axis + 1]) + "' is not a finite number in '" + what + "'");
      }
    }
    return v;
  };
  // OBJ indices are 1-based; negative ones count back from the latest element.
  const auto resolve = [&](std::string_view token, std::size_t count, const char* what) -> std::uint32_t {
    long long index;
    if (!parse_integer(token, index) || index == 0) {
      fail(std::string("'") + std::string(token) + "' is not a valid " + what + " index");
    }
    const long long resolved = index > 0 ? index - 1 : (long long)count + index;
    if (resolved < 0 || resolved >= (long long)count) {
      fail(std::string(what) + " index " + std::to_string(index) + " out of range (" + std::to_string(count) + " " +
           what + "s defined so far)");
    }
    return std::uint32_t(resolved);
  };

  while (std::getline(in, line)) {
    ++line_number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    const auto tokens = split_whitespace(line);
    if (tokens.empty()) continue;
    const std::string_view keyword = tokens[0];
    if (keyword == "v") {
      positions.push_back(read_vector(tokens, "v"));
    } else if (keyword == "vn") {
      normals.push_back(read_vector(tokens, "vn"));
    } else if (keyword == "usemtl") {
      if (tokens.size() < 2) fail("expected a material name after 'usemtl'");
      current_material = std::string(tokens[1]);
    } else if (keyword == "f") {
      if (tokens.size() < 4) fail("a face needs at least 3 vertices, got " + std::to_string(tokens.size() - 1));
      std::vector<ObjCorner> polygon;
      for (std::size_t i = 1; i < tokens.size(); ++i) {
        const std::string_view token = tokens[i];
        const std::size_t slash = token.find('/');
        ObjCorner corner{resolve(token.substr(0, slash), positions.size(), "vertex"), -1};
        if (slash != std::string_view::npos) {
          const std::size_t second = token.find('/', slash + 1);
          if (second != std::string_view::npos && second + 1 < token.size()) {
            corner.normal = resolve(token.substr(second + 1), normals.size(), "normal");
          }
        }
        polygon.push_back(corner);
      }
      const std::uint16_t material = materials.index_of(current_material);
      for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
        corners.insert(corners.end(), {polygon[0], polygon[i], polygon[i + 1]});
        triangle_material.push_back(material);
      }
    }
    // Everything else (vt, o, g, s, mtllib, l, ...) does not change the geometry we keep.
  }
  if (in.bad()) throw Error(source_name + ": read error after line " + std::to_string(line_number));
  if (corners.empty()) throw Error(source_name + ": no faces (expected 'f' lines)");

  // One output vertex per distinct (position, normal) pair, or per position without normals.
  const bool file_has_normals =
      std::all_of(corners.begin(), corners.end(), [](const ObjCorner& c) { return c.normal >= 0; });
  Mesh mesh;
  mesh.name = std::filesystem::path(source_name).stem().string();
  std::unordered_map<std::uint64_t, std::uint32_t> vertex_of;
  const auto output_vertex = [&](const ObjCorner& c) {
    const std::uint64_t key =
        file_has_normals ? (std::uint64_t(c.position) << 32 | std::uint64_t(c.normal)) : std::uint64_t(c.position);
    const auto [it, inserted] = vertex_of.try_emplace(key, std::uint32_t(mesh.positions.size()));
    if (inserted) {
      mesh.positions.push_back(positions[c.position]);
      if (file_has_normals) mesh.normals.push_back(normals[std::size_t(c.normal)]);
    }
    return it->second;
  };
  for (std::size_t i = 0; i < corners.size(); i += 3) {
    mesh.triangles.push_back({output_vertex(corners[i]), output_vertex(corners[i + 1]), output_vertex(corners[i + 2])});
  }
  mesh.triangle_material = std::move(triangle_material);
  mesh.materials = materials.take();
  finish_normals(mesh, file_has_normals);
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

// ---- PLY ----

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
  finish_normals(mesh, has_normals);
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

Mesh load_mesh(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (extension != ".obj" && extension != ".ply") {
    throw Error(path.string() + ": unknown mesh format '" + extension + "' (expected .obj or .ply)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string() + ": cannot open the file for reading");
  return extension == ".obj" ? read_obj(in, path.string()) : read_ply(in, path.string());
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
