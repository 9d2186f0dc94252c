// Stand-ins: coarser copies of a user's model for where it is drawn small (the camera-aware
// export's proxies, between `near` and `far`), made by meshoptimizer's simplifier. A stand-in
// keeps the model's materials, and its vertices are a subset of the model's, so every texture
// coordinate is one the model had.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "templates/mesh.h"

namespace wangscape {

struct StandInOptions {
  std::size_t max_triangles = 400;  // at most this many
  // The error the simplifier may make, as a fraction of the model's largest extent: it stops
  // there unless max_triangles needs more. 1/16: half a pixel where a model the size of a
  // sunflower head spans 8 (the camera-aware `near`).
  double target_error = 1.0 / 16;
};

struct StandIn {
  Mesh mesh;            // named as the model
  double error = 0;     // meters in model space: meshoptimizer's result error times the model's largest extent
  bool sloppy = false;  // the borders held the simplifier above max_triangles: meshopt_simplifySloppy made it
};

// A stand-in of `model`: its corners welded by position, texture coordinate and material (uv
// seams and materials' edges are kept whole, so no triangle changes material), simplified to the
// fewest triangles within options.target_error with open borders held in place (a leaf card
// keeps its outline), or to options.max_triangles when that needs more error (borders then
// free, at last meshopt_simplifySloppy).
// A model of no triangles gives an empty stand-in; one the simplifier would empty, itself.
StandIn make_stand_in(const Mesh& model, const StandInOptions& options = {});

// What a build reports of one stand-in.
struct StandInFigures {
  std::string name;                 // the stand-in's model name ("tulip_2 proxy")
  std::size_t triangles = 0;        // the stand-in's
  std::size_t model_triangles = 0;  // the full model's
  double error = 0;                 // meters, StandIn::error
};

// The stand-ins of `models` in order, each named "<model> proxy" (as the procedural proxies are),
// with their figures appended to `figures`.
std::vector<Mesh> make_stand_ins(std::span<const Mesh> models, const StandInOptions& options,
                                 std::vector<StandInFigures>& figures);

}  // namespace wangscape
