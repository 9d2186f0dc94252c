// A user's model read through Assimp (OBJ with its MTL, glTF 2.0 and GLB, FBX, Collada, PLY and
// whatever else Assimp reads), so it can replace the built-in plants; and OBJ and PLY writers for
// Wangscape's own meshes. Readers throw Error naming the file (and the material or mesh at
// fault). Loaded meshes keep the file's coordinates: the caller decides units and axes
// (Wangscape models are meters, z up, ground contact at the origin). Thread-safe: each call has
// its own Assimp importer. Assimp logs nothing unless a logger is made, and none is.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include "templates/mesh.h"

namespace wangscape {

// Loads a model file in any format Assimp reads (chosen by Assimp from the extension and the
// bytes); a .ply file by read_ply instead (Assimp 5.2's PLY reader hangs on damaged headers). Polygons are
// triangulated, points and lines dropped, the file's node transforms applied, smooth normals computed where the file
// has none. One material per material of the file that a triangle uses, in order of first use: its name, base colour
// (glTF baseColorFactor, else the diffuse colour: an MTL's Kd; 0.5 grey when the file gives none), roughness (glTF's),
// the image of its base colour (a file beside the model, which must exist, or one the file holds) and an alpha cutout
// (glTF alphaMode MASK or BLEND at alphaCutoff; an MTL's map_d at 0.5). uvs are the first texture coordinates, kept
// when any triangle has them. The mesh is named by the file's stem. (A .ply file is read by read_ply: no images,
// colours from `comment material` lines.)
Mesh load_mesh(const std::filesystem::path& path);

// One Mesh per object of the file, in the file's order, each as load_mesh makes a whole file
// and named by its object (node) name, else "<stem>_<index>". An object is a child of the
// scene's top node (below wrapper nodes of no mesh and one child) with the triangles of its
// subtree; triangles of the top node itself are one more. A PLY file is one object.
std::vector<Mesh> load_mesh_objects(const std::filesystem::path& path);

// Whether a file's name is one of a model: .ply or an extension Assimp reads (not .mtl, .bin, .png).
bool is_model_file_name(const std::filesystem::path& path);

// The same from bytes in memory, the format named by `extension` (".glb", "obj"); images must be
// held by the bytes. `source_name` is used in error messages and names the mesh.
Mesh read_model(std::span<const std::uint8_t> bytes, const std::string& extension, const std::string& source_name);

// PLY, ascii or binary_little_endian, read by hand: element vertex with x, y, z [nx, ny, nz],
// element face with list vertex_indices (or vertex_index) and optional integer `material` (its
// colour and name from write_ply's `comment material` lines, else one grey "default"); other
// elements and properties are skipped. Errors name the file and the line (ascii) or element
// (binary). `in` must be opened in binary mode.
Mesh read_ply(std::istream& in, const std::string& source_name);

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
// What load_user_model does to a loaded mesh (options.scale must be > 0).
void to_model_space(Mesh& mesh, const UserModelOptions& options);

// OBJ with v, vn, `usemtl` per material run and f v//vn. Numbers round-trip exactly.
void write_obj(std::ostream& out, const Mesh& mesh);

enum class PlyFormat { ascii, binary_little_endian };

// PLY with float x y z nx ny nz, face list uchar uint vertex_indices, ushort material, and one
// `comment material <index> <name> <r> <g> <b>` per material.
void write_ply(std::ostream& out, const Mesh& mesh, PlyFormat format = PlyFormat::binary_little_endian);

}  // namespace wangscape
