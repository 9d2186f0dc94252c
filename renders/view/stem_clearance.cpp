#include "renders/view/stem_clearance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wangscape {

namespace {
// Slices per stem: a sunflower's stem bends a little and tapers, so one cylinder would either
// leave the eye inside its top or hold it far from its foot.
constexpr int kSlices = 24;
// Passes over the plants around the eye: pushed out of one stem into a neighbour's, it is pushed
// again (stems stand tens of centimetres apart, so two passes settle it; the rest are a margin).
constexpr int kPasses = 4;
}  // namespace

StemClearance::StemClearance(std::span<const Mesh> models) {
  stems_.resize(models.size());
  for (std::size_t m = 0; m < models.size(); ++m) {
    const Mesh& mesh = models[m];
    std::vector<std::uint32_t> corners;       // the stem triangles' vertices, three a triangle
    std::vector<std::size_t> stem_triangles;  // their indices in the mesh
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const std::uint16_t material = mesh.triangle_material[t];
      if (material < mesh.materials.size() && mesh.materials[material].name == "stem") {
        corners.insert(corners.end(), mesh.triangles[t].begin(), mesh.triangles[t].end());
        stem_triangles.push_back(t);
      }
    }
    if (corners.empty()) continue;
    Stem& stem = stems_[m];
    stem.bottom = std::numeric_limits<float>::infinity();
    stem.top = -stem.bottom;
    for (const std::uint32_t v : corners) {
      stem.bottom = std::min(stem.bottom, mesh.positions[v][2]);
      stem.top = std::max(stem.top, mesh.positions[v][2]);
    }
    if (!(stem.top > stem.bottom)) continue;
    // Per slice, the box across the ground of every stem triangle that reaches its heights (all
    // three corners: a triangle between two rings of the tube lies in no slice by its vertices
    // alone): its centre is the stem's axis there, and no such triangle lies beyond its radius.
    const float span = stem.top - stem.bottom;
    const auto slice_of = [&](float z) { return std::clamp(int((z - stem.bottom) / span * kSlices), 0, kSlices - 1); };
    struct Box {
      float x0 = std::numeric_limits<float>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    };
    std::vector<Box> boxes(kSlices);
    const auto for_each_slice = [&](std::size_t triangle, const auto& f) {  // the slices it reaches
      const auto& t = mesh.triangles[triangle];
      const float z0 = std::min({mesh.positions[t[0]][2], mesh.positions[t[1]][2], mesh.positions[t[2]][2]});
      const float z1 = std::max({mesh.positions[t[0]][2], mesh.positions[t[1]][2], mesh.positions[t[2]][2]});
      for (int k = slice_of(z0); k <= slice_of(z1); ++k) f(std::size_t(k));
    };
    for (std::size_t i = 0; i < corners.size(); ++i) {
      const auto& p = mesh.positions[corners[i]];
      for_each_slice(stem_triangles[i / 3], [&](std::size_t k) {
        Box& b = boxes[k];
        b.x0 = std::min(b.x0, p[0]), b.x1 = std::max(b.x1, p[0]);
        b.y0 = std::min(b.y0, p[1]), b.y1 = std::max(b.y1, p[1]);
      });
    }
    stem.slices.assign(kSlices, {});
    for (int k = 0; k < kSlices; ++k) {
      const Box& b = boxes[std::size_t(k)];
      if (b.x1 >= b.x0)
        stem.slices[std::size_t(k)] = {(b.x0 + b.x1) / 2, (b.y0 + b.y1) / 2, 0};
      else
        stem.slices[std::size_t(k)].radius = -1;  // a gap in the stem: nothing to keep out of
    }
    for (std::size_t i = 0; i < corners.size(); ++i) {
      const auto& p = mesh.positions[corners[i]];
      for_each_slice(stem_triangles[i / 3], [&](std::size_t k) {
        Slice& s = stem.slices[k];
        s.radius = std::max(s.radius, std::hypot(p[0] - s.x, p[1] - s.y));
      });
    }
    for (const Slice& s : stem.slices) {
      widest_ = std::max(widest_, s.radius);
      tallest_offset_ = std::max(tallest_offset_, std::hypot(s.x, s.y));
    }
  }
}

Vector3d StemClearance::keep_out(const SceneField& field, const Vector3d& eye, double clearance) const {
  if (widest_ <= 0) return eye;
  // The plants whose stems may reach the eye: a scale of 2 at most, as placement draws them.
  const double reach = 2.0 * double(widest_ + tallest_offset_) + clearance + 0.05;
  const Extent window{eye[0] - reach, eye[1] - reach, eye[0] + reach, eye[1] + reach};
  InstanceBatch plants;
  field.place_in(window, [&](const InstanceBatch& batch) {
    for (std::size_t i = 0; i < batch.size(); ++i)
      if (batch.variant[i] < stems_.size() && !stems_[batch.variant[i]].slices.empty())
        plants.push_back(batch.x[i], batch.y[i], batch.z[i], batch.yaw[i], batch.scale[i], batch.variant[i],
                         batch.tile[i]);
  });
  Vector3d at = eye;
  for (int pass = 0; pass < kPasses; ++pass) {
    bool pushed = false;
    for (std::size_t i = 0; i < plants.size(); ++i) {
      const Stem& stem = stems_[plants.variant[i]];
      const double k = plants.scale[i];
      // Every slice within the clearance above or below the eye (a wider one just below would
      // otherwise come nearer than the clearance).
      const double height = (at[2] - double(plants.z[i])) / k, margin = clearance / k;  // model space
      if (height < stem.bottom - margin || height > stem.top + margin) continue;
      const double slice_height = (stem.top - stem.bottom) / kSlices;
      const int first = std::clamp(int(std::floor((height - margin - stem.bottom) / slice_height)), 0, kSlices - 1);
      const int last = std::clamp(int(std::floor((height + margin - stem.bottom) / slice_height)), 0, kSlices - 1);
      const double c = std::cos(double(plants.yaw[i])), sn = std::sin(double(plants.yaw[i]));
      for (int slice = first; slice <= last; ++slice) {
        const Slice& s = stem.slices[std::size_t(slice)];
        if (s.radius < 0) continue;
        const double cx = plants.x[i] + k * (c * s.x - sn * s.y), cy = plants.y[i] + k * (sn * s.x + c * s.y);
        const double keep = k * s.radius + clearance;
        const double dx = at[0] - cx, dy = at[1] - cy, d = std::hypot(dx, dy);
        if (d >= keep) continue;
        // Out across the ground, away from the stem's axis (due east from the axis itself).
        const double ux = d > 1e-9 ? dx / d : 1.0, uy = d > 1e-9 ? dy / d : 0.0;
        at[0] = cx + ux * keep * (1 + 1e-9);
        at[1] = cy + uy * keep * (1 + 1e-9);
        pushed = true;
      }
    }
    if (!pushed) break;
  }
  return at;
}

}  // namespace wangscape
