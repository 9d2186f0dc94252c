// Keeps a walking eye out of the plants' stems (issue 40): inside a stem the picture is black, in
// the view and in the truth alike. Each model's stem (its triangles of the material named "stem")
// is measured once as a stack of slices, each a centre and a radius in model space; an eye within
// a stem's radius plus a clearance, at a height the stem reaches, is pushed out across the ground
// from the stem's centre at that height, so that a walk into a stem slides along it. Leaves, petals
// and grass blades may brush the eye.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/vecmath.h"
#include "scene/scene.h"
#include "templates/mesh.h"

namespace wangscape {

class StemClearance {
 public:
  // Meters kept between the eye and a stem's surface by default: a few centimetres, as a
  // walk-through keeps its camera off walls.
  static constexpr double kClearance = 0.05;

  // The stems of `models` (Scene::models; a model without a "stem" material has none).
  explicit StemClearance(std::span<const Mesh> models);

  // Where `eye` stands, kept at least `clearance` meters from every stem of the field's plants
  // around it (across the ground; its height is kept). Deterministic; thread-safe.
  Vector3d keep_out(const SceneField& field, const Vector3d& eye, double clearance = kClearance) const;

  // The widest stem's largest radius (model space, meters), for the window of plants searched.
  float widest() const { return widest_; }

 private:
  struct Slice {
    float x = 0, y = 0, radius = 0;  // model space, meters; radius -1: no stem at these heights
  };
  struct Stem {
    float bottom = 0, top = 0;  // model-space heights the slices span
    std::vector<Slice> slices;  // bottom to top, evenly
  };
  std::vector<Stem> stems_;  // per model (empty slices: no stem)
  float widest_ = 0;
  float tallest_offset_ = 0;  // the largest horizontal distance of a stem slice's centre from the base
};

}  // namespace wangscape
