// The OBJ and PLY writers of templates/mesh_io.h (the readers are in mesh_io.cpp).
#include <algorithm>
#include <bit>
#include <cstring>
#include <ostream>
#include <string>

#include "core/number_text.h"
#include "templates/mesh_io.h"

namespace wangscape {

namespace {

void require_writable(const std::ostream& out, const char* format) {
  if (!out) throw Error(std::string("writing ") + format + " failed (stream error)");
}

}  // namespace

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

}  // namespace wangscape
