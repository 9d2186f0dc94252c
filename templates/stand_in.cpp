#include "templates/stand_in.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cstdint>
#include <vector>

namespace wangscape {

namespace {

// The model's triangles over its distinct vertices: corners equal in position, texture
// coordinate and material made one. A file's triangles often hold their own copies of a shared
// corner, which the simplifier would take for separate pieces (and copies left in its vertex
// buffer, unused, for locked corners). Corners at a uv seam or a material's edge stay apart: the
// simplifier keeps such seams whole, so every triangle keeps one material and no crack opens.
struct Welded {
  std::vector<std::uint32_t> corners;           // 3 per triangle, into `positions`
  std::vector<std::array<float, 3>> positions;  // the distinct vertices
  std::vector<std::uint32_t> model_vertex;      // of each distinct vertex: a model vertex of its kind
  std::vector<std::uint16_t> material;          // of each distinct vertex
};

Welded weld(const Mesh& model) {
  const std::size_t count = model.triangles.size() * 3;
  const bool uvs = model.uvs.size() == model.positions.size();
  std::vector<std::array<float, 3>> positions(count);
  std::vector<std::array<float, 2>> uv(count);
  std::vector<std::uint32_t> material(count);
  for (std::size_t c = 0; c < count; ++c) {
    const std::uint32_t v = model.triangles[c / 3][c % 3];
    positions[c] = model.positions[v];
    if (uvs) uv[c] = model.uvs[v];
    material[c] = c / 3 < model.triangle_material.size() ? model.triangle_material[c / 3] : 0;
  }
  const meshopt_Stream streams[] = {{positions.data(), sizeof(float) * 3, sizeof(float) * 3},
                                    {uv.data(), sizeof(float) * 2, sizeof(float) * 2},
                                    {material.data(), sizeof(std::uint32_t), sizeof(std::uint32_t)}};
  Welded welded;
  welded.corners.resize(count);
  const std::size_t distinct =
      meshopt_generateVertexRemapMulti(welded.corners.data(), nullptr, count, count, streams, std::size(streams));
  welded.positions.resize(distinct);
  welded.model_vertex.resize(distinct);
  welded.material.resize(distinct);
  for (std::size_t c = 0; c < count; ++c) {
    const std::uint32_t d = welded.corners[c];
    welded.positions[d] = positions[c];
    welded.model_vertex[d] = model.triangles[c / 3][c % 3];
    welded.material[d] = std::uint16_t(material[c]);
  }
  return welded;
}

struct Simplified {
  std::vector<std::uint32_t> corners;
  float relative_error = 0;
  bool sloppy = false;
};

// The fewest triangles within `target_error`, open borders held (a leaf card keeps its outline,
// a stem tube its ends); else `max_triangles` with whatever error it takes: borders held, then
// free, at last sloppily.
Simplified simplify(const Welded& welded, std::size_t max_triangles, float target_error) {
  Simplified out;
  const std::vector<std::uint32_t>& corners = welded.corners;
  out.corners.resize(corners.size());
  const float* positions = welded.positions.front().data();
  const std::size_t vertices = welded.positions.size(), stride = sizeof(float) * 3;
  const auto run = [&](std::size_t target, float error, unsigned options) {
    return meshopt_simplify(out.corners.data(), corners.data(), corners.size(), positions, vertices, stride, target,
                            error, options, &out.relative_error);
  };
  const std::size_t most = max_triangles * 3;
  std::size_t kept = run(0, target_error, meshopt_SimplifyLockBorder);
  if (kept > most) kept = run(most, FLT_MAX, meshopt_SimplifyLockBorder);
  if (kept > most) kept = run(most, FLT_MAX, 0);
  if (kept > most) {
    kept = meshopt_simplifySloppy(out.corners.data(), corners.data(), corners.size(), positions, vertices, stride, most,
                                  FLT_MAX, &out.relative_error);
    out.sloppy = true;
  }
  out.corners.resize(kept);
  return out;
}

// The stand-in's own vertex list: the model's vertices its triangles use, in order of first use.
void keep_used_vertices(const Mesh& model, Mesh& stand_in) {
  std::vector<std::uint32_t> new_index(model.positions.size(), ~0u);
  const bool uvs = model.uvs.size() == model.positions.size();
  const bool normals = model.normals.size() == model.positions.size();
  for (auto& triangle : stand_in.triangles)
    for (auto& v : triangle) {
      if (new_index[v] == ~0u) {
        new_index[v] = std::uint32_t(stand_in.positions.size());
        stand_in.positions.push_back(model.positions[v]);
        if (normals) stand_in.normals.push_back(model.normals[v]);
        if (uvs) stand_in.uvs.push_back(model.uvs[v]);
      }
      v = new_index[v];
    }
}

}  // namespace

StandIn make_stand_in(const Mesh& model, const StandInOptions& options) {
  StandIn result;
  result.mesh.name = model.name;
  result.mesh.materials = model.materials;
  if (model.triangles.empty() || model.positions.empty()) return result;
  const Welded welded = weld(model);
  const float scale =
      meshopt_simplifyScale(welded.positions.front().data(), welded.positions.size(), sizeof(float) * 3);
  const Simplified simplified = simplify(welded, options.max_triangles, float(options.target_error));
  result.error = double(simplified.relative_error) * scale;
  result.sloppy = simplified.sloppy;
  for (std::size_t c = 0; c + 2 < simplified.corners.size(); c += 3) {
    const std::uint32_t a = simplified.corners[c], b = simplified.corners[c + 1], d = simplified.corners[c + 2];
    result.mesh.triangles.push_back({welded.model_vertex[a], welded.model_vertex[b], welded.model_vertex[d]});
    // (A sloppy stand-in may join corners of two materials: the first one's.)
    result.mesh.triangle_material.push_back(welded.material[a]);
  }
  if (result.mesh.triangles.empty()) {
    // Simplified to nothing (a sloppy pass on a tiny budget): the model stands in for itself, as
    // an empty mesh is no model to an exporter (POV-Ray refuses a mesh2 of no face).
    result.mesh = model;
    result.error = 0;
    return result;
  }
  keep_used_vertices(model, result.mesh);
  return result;
}

std::vector<Mesh> make_stand_ins(std::span<const Mesh> models, const StandInOptions& options,
                                 std::vector<StandInFigures>& figures) {
  std::vector<Mesh> stand_ins;
  for (const Mesh& model : models) {
    StandIn stand_in = make_stand_in(model, options);
    stand_in.mesh.name += " proxy";
    figures.push_back({stand_in.mesh.name, stand_in.mesh.triangle_count(), model.triangle_count(), stand_in.error});
    stand_ins.push_back(std::move(stand_in.mesh));
  }
  return stand_ins;
}

}  // namespace wangscape
