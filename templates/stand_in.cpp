#include "templates/stand_in.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cfloat>
#include <cstdint>
#include <vector>

namespace wangscape {

namespace {

// One index per corner, vertices equal in position and texture coordinate made one: a file's
// triangles often hold their own copies of a shared corner, which the simplifier would take for
// separate pieces and could not collapse. Corners at a uv seam stay apart (the simplifier keeps
// seams whole).
std::vector<std::uint32_t> welded_corners(const Mesh& model) {
  std::vector<std::uint32_t> corners;
  corners.reserve(model.triangles.size() * 3);
  for (const auto& triangle : model.triangles) corners.insert(corners.end(), triangle.begin(), triangle.end());
  std::vector<meshopt_Stream> streams{{model.positions.data(), sizeof(float) * 3, sizeof(float) * 3}};
  if (model.uvs.size() == model.positions.size())
    streams.push_back({model.uvs.data(), sizeof(float) * 2, sizeof(float) * 2});
  std::vector<std::uint32_t> remap(model.positions.size());
  meshopt_generateVertexRemapMulti(remap.data(), corners.data(), corners.size(), model.positions.size(), streams.data(),
                                   streams.size());
  // The remap numbers the distinct vertices anew; pointing each corner at the first vertex of its
  // kind keeps the model's own vertices (and their uvs) as they are.
  std::vector<std::uint32_t> first_of(model.positions.size(), ~0u);
  for (std::uint32_t v = 0; v < remap.size(); ++v)
    if (remap[v] != ~0u && first_of[remap[v]] == ~0u) first_of[remap[v]] = v;
  for (auto& corner : corners) corner = first_of[remap[corner]];
  return corners;
}

struct Simplified {
  std::vector<std::uint32_t> corners;
  float relative_error = 0;
  bool sloppy = false;
};

// The fewest triangles of `corners` within `target_error`, or `max_triangles` when that takes
// more error (sloppily where the borders stop the simplifier above it).
Simplified simplify(const std::vector<std::uint32_t>& corners, const Mesh& model, std::size_t max_triangles,
                    float target_error) {
  const float* positions = model.positions.front().data();
  const std::size_t vertices = model.positions.size(), stride = sizeof(float) * 3;
  Simplified out;
  out.corners.resize(corners.size());
  std::size_t kept = meshopt_simplify(out.corners.data(), corners.data(), corners.size(), positions, vertices, stride,
                                      0, target_error, 0, &out.relative_error);
  if (kept > max_triangles * 3)
    kept = meshopt_simplify(out.corners.data(), corners.data(), corners.size(), positions, vertices, stride,
                            max_triangles * 3, FLT_MAX, 0, &out.relative_error);
  if (kept > max_triangles * 3) {
    kept = meshopt_simplifySloppy(out.corners.data(), corners.data(), corners.size(), positions, vertices, stride,
                                  max_triangles * 3, FLT_MAX, &out.relative_error);
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
  const std::vector<std::uint32_t> corners = welded_corners(model);
  const float scale = meshopt_simplifyScale(model.positions.front().data(), model.positions.size(), sizeof(float) * 3);
  // Each material alone, with its share of the triangles (at least one).
  std::uint16_t materials = 1;
  for (const std::uint16_t m : model.triangle_material) materials = std::max<std::uint16_t>(materials, m + 1);
  for (std::uint16_t m = 0; m < materials; ++m) {
    std::vector<std::uint32_t> own;
    for (std::size_t t = 0; t < model.triangles.size(); ++t)
      if ((t < model.triangle_material.size() ? model.triangle_material[t] : 0) == m)
        own.insert(own.end(), corners.begin() + std::ptrdiff_t(3 * t), corners.begin() + std::ptrdiff_t(3 * t + 3));
    if (own.empty()) continue;
    const std::size_t share =
        std::max<std::size_t>(1, options.max_triangles * (own.size() / 3) / model.triangles.size());
    const Simplified simplified = simplify(own, model, share, float(options.target_error));
    result.error = std::max(result.error, double(simplified.relative_error) * scale);
    result.sloppy = result.sloppy || simplified.sloppy;
    for (std::size_t c = 0; c + 2 < simplified.corners.size(); c += 3) {
      result.mesh.triangles.push_back({simplified.corners[c], simplified.corners[c + 1], simplified.corners[c + 2]});
      result.mesh.triangle_material.push_back(m);
    }
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
