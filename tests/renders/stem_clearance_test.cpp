// The eye kept out of the stems (renders/view/stem_clearance.h, issue 40): checked against the
// stems' own triangles, placed as the field places them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "renders/view/stem_clearance.h"
#include "tests/renders/view_test_world.h"

namespace wangscape {
namespace {

using view_test::field;

using P = std::array<double, 3>;
P sub(const P& a, const P& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot3(const P& a, const P& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
P along(const P& a, const P& d, double t) { return {a[0] + d[0] * t, a[1] + d[1] * t, a[2] + d[2] * t}; }

// The closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
P closest_on_triangle(const P& p, const P& a, const P& b, const P& c) {
  const P ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const P bp = sub(p, b);
  const double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return along(a, ab, d1 / (d1 - d3));
  const P cp = sub(p, c);
  const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return along(a, ac, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return along(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1 / (va + vb + vc);
  return along(along(a, ab, vb * denom), ac, vc * denom);
}

// Every stem triangle of the field's plants around `area`, in world space.
std::vector<std::array<P, 3>> stem_triangles(const ViewWorld& world, const Extent& area) {
  std::vector<std::array<P, 3>> out;
  world.scene().field->place_in(area, [&](const InstanceBatch& batch) {
    for (std::size_t i = 0; i < batch.size(); ++i) {
      const Mesh& mesh = world.scene().models[batch.variant[i]];
      const double c = std::cos(double(batch.yaw[i])), s = std::sin(double(batch.yaw[i])), k = batch.scale[i];
      const auto to_world = [&](std::uint32_t v) -> P {
        const auto& q = mesh.positions[v];
        return {batch.x[i] + k * (c * q[0] - s * q[1]), batch.y[i] + k * (s * q[0] + c * q[1]), batch.z[i] + k * q[2]};
      };
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        if (mesh.materials[mesh.triangle_material[t]].name == "stem")
          out.push_back(
              {to_world(mesh.triangles[t][0]), to_world(mesh.triangles[t][1]), to_world(mesh.triangles[t][2])});
    }
  });
  return out;
}

double distance_to_stems(const P& eye, const std::vector<std::array<P, 3>>& stems) {
  double best = 1e9;
  for (const auto& t : stems) {
    const P q = closest_on_triangle(eye, t[0], t[1], t[2]);
    best = std::min(best, std::sqrt(dot3(sub(eye, q), sub(eye, q))));
  }
  return best;
}

// Eyes on a 2 cm grid over a patch of the field at three heights: those that started inside a
// stem or within the clearance of one end at least 4 cm from every stem triangle (the clearance
// less the tube's chords).
TEST(StemClearance, EyesOnAGridEndClearOfEveryStem) {
  const ViewWorld& world = *field();
  const std::vector<std::array<P, 3>> stems = stem_triangles(world, {-2.5, -2.5, 2.5, 2.5});
  ASSERT_GT(stems.size(), 100u);
  int started_close = 0, checked = 0;
  for (const double height : {0.4, 0.9, 1.4})
    for (double y = -1.5; y <= 1.5; y += 0.02)
      for (double x = -1.5; x <= 1.5; x += 0.02) {
        const P eye{x, y, world.ground_height(x, y, 0) + height};
        const double before = distance_to_stems(eye, stems);
        if (before > 0.1) continue;  // far from any stem: nothing to see
        started_close += before < 0.04;
        const P kept = world.clear_of_stems(eye);
        EXPECT_EQ(kept[2], eye[2]);
        EXPECT_GE(distance_to_stems(kept, stems), 0.04) << x << ", " << y << " at " << height << " m";
        ++checked;
      }
  EXPECT_GT(started_close, 20) << checked;  // the grid met stems: the check above could fail
}

// A walk straight at a stem slides past it: every step clear, and the walk gets through.
TEST(StemClearance, AWalkIntoAStemSlidesAlongIt) {
  const ViewWorld& world = *field();
  float bx = 0, by = 0;
  bool found = false;
  world.scene().field->place_in({-0.5, -0.5, 0.5, 0.5}, [&](const InstanceBatch& batch) {
    if (!found && !batch.empty()) bx = batch.x[0], by = batch.y[0], found = true;
  });
  ASSERT_TRUE(found);
  const std::vector<std::array<P, 3>> stems = stem_triangles(world, {bx - 3.0, by - 1.5, bx + 3.0, by + 1.5});
  P eye{bx - 2.0, by, 0};
  for (int step = 0; step < 200; ++step) {  // 2 cm a step, along +x through the plant's base
    eye[0] += 0.02;
    eye[2] = world.ground_height(eye[0], eye[1], 0) + 0.8;
    eye = world.clear_of_stems(eye);
    ASSERT_GE(distance_to_stems(eye, stems), 0.04) << "step " << step;
  }
  EXPECT_GT(eye[0], bx + 1.5);            // not stopped at the stem (sliding costs a little)
  EXPECT_LT(std::abs(eye[1] - by), 0.5);  // slid aside, not thrown off
}

}  // namespace
}  // namespace wangscape
