// The terrain's shadows on itself, for renderers that light the terrain per vertex (the view).
#pragma once

#include <array>
#include <vector>

#include "templates/mesh.h"

namespace wangscape {

// Per vertex of `mesh`, as the reference's shadow rays see it toward the unit `sun`: 1 where
// the sun is seen past the terrain from just above the vertex, else 0 (interpolated over the
// triangles, so a shadow's edge is as soft as the mesh is coarse).
// Throws Error for Embree's errors.
std::vector<float> terrain_sun_visibility(const Mesh& mesh, const std::array<float, 3>& sun);

}  // namespace wangscape
