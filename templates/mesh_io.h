// Reading and writing meshes as Wavefront OBJ and PLY, so a user model can replace the built-in
// sunflower. Readers throw Error whose message names the file and the line (OBJ, ASCII PLY)
// or element (binary PLY) at fault. Loaded meshes keep the file's coordinates: the caller decides
// units and axes (Wangscape models are meters, z up, ground contact at the origin).
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>

#include "templates/mesh.h"

namespace wangscape {

// Loads an .obj or .ply file (chosen by extension, case-insensitive). Triangulates polygons as
// fans; computes smooth normals when the file has none (or not for every face corner).
// Materials: OBJ `usemtl` names, PLY `comment material` lines as written by write_ply, else one
// material "default"; the names petal, disk, stem and leaf take the sunflower colors.
Mesh load_mesh(const std::filesystem::path& path);

// How to bring a user's model into Wangscape model space.
struct UserModelOptions {
  float scale = 1.0f;            // multiplies file units to get meters
  bool y_up = false;             // the file is y-up (common for OBJ): rotate so that its +y becomes +z
  bool ground_at_origin = true;  // move the model so its lowest point is at z = 0 and its
                                 // footprint (x-y box) is centered on the origin
};

// load_mesh, then scale, turn to z up and move to the origin as `options` say; normals follow.
// The result can replace the built-in sunflower (its extent gives height and placement radius).
Mesh load_user_model(const std::filesystem::path& path, const UserModelOptions& options = {});

// OBJ with v, vn and f (v, v/vt, v//vn, v/vt/vn; negative indices count back from the last
// vertex); other statements are ignored. `source_name` is used in error messages.
Mesh read_obj(std::istream& in, const std::string& source_name);

// PLY, ascii or binary_little_endian: element vertex with x, y, z [nx, ny, nz], element face with
// list vertex_indices (or vertex_index) and optional integer `material`; other elements and
// properties are skipped. `in` must be opened in binary mode.
Mesh read_ply(std::istream& in, const std::string& source_name);

// OBJ with v, vn, `usemtl` per material run and f v//vn. Numbers round-trip exactly.
void write_obj(std::ostream& out, const Mesh& mesh);

enum class PlyFormat { ascii, binary_little_endian };

// PLY with float x y z nx ny nz, face list uchar uint vertex_indices, ushort material, and one
// `comment material <index> <name> <r> <g> <b>` per material.
void write_ply(std::ostream& out, const Mesh& mesh, PlyFormat format = PlyFormat::binary_little_endian);

}  // namespace wangscape
