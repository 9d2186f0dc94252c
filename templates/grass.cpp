#include "templates/grass.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "templates/model_builder.h"

namespace wangscape {
namespace {

using namespace model_geometry;

// Rows of a blade at full detail: enough for its arch to read as a curve up close.
constexpr int kMaxBladeRows = 10;
constexpr int kMaxBlades = int(kGrassMaximumTriangleBudget / (2 * kMaxBladeRows));

// What one clump shares: its size, its tuft, its lean, how much of it has dried.
struct ClumpShape {
  std::uint64_t blade_seed;
  double height;       // meters, the tallest blades reach about this
  double tuft_radius;  // meters, where the blades leave the ground
  int blade_count;     // at full detail
  double dry_share, straw_share;
  Vec3 lean;  // horizontal, the clump's wind-blown direction times its strength
};

ClumpShape draw_clump(std::uint64_t seed, int variant) {
  Random random(mix64(seed ^ mix64(std::uint64_t(variant) + 0x67u)));
  ClumpShape clump;
  clump.blade_seed = random.next();
  clump.height = random.uniform(0.28, 0.6);
  clump.tuft_radius = random.uniform(0.02, 0.05);
  clump.blade_count = random.integer(36, 64);
  clump.dry_share = random.uniform(0.08, 0.3);
  clump.straw_share = random.uniform(0.04, 0.2);
  const double lean_azimuth = random.uniform(0.0, 2 * kPi);
  const double lean = random.uniform(0.0, 0.35);
  clump.lean = {lean * std::cos(lean_azimuth), lean * std::sin(lean_azimuth), 0};
  return clump;
}

// Blade k of a clump: the same at every budget (its own random stream).
void add_blade(MeshBuilder& builder, const ClumpShape& clump, int k, int rows) {
  Random random(mix64(clump.blade_seed + std::uint64_t(k) * 0x9e3779b97f4a7c15ull));
  const double base_angle = random.uniform(0.0, 2 * kPi);
  const double base_radius = clump.tuft_radius * std::sqrt(random.uniform(0.0, 1.0));
  const Vec3 base{base_radius * std::cos(base_angle), base_radius * std::sin(base_angle), 0};
  // Blades splay out from the tuft's centre, turned by the clump's lean.
  const double azimuth = base_angle + random.uniform(-0.6, 0.6);
  const Vec3 out = normalize(Vec3{std::cos(azimuth), std::sin(azimuth), 0} + clump.lean);
  const Vec3 side = normalize(cross(kUp, out));
  // Green, yellowed or straw in the clump's shares (the golden ratio spreads them evenly).
  const double which = std::fmod(k * 0.6180339887498949, 1.0);
  const std::uint16_t material = which < clump.straw_share                     ? grass_straw
                                 : which < clump.straw_share + clump.dry_share ? grass_dry
                                                                               : grass_blade;
  const bool dead = material == grass_straw;
  // Dead blades are shorter and fall further over.
  const double length = clump.height * random.uniform(0.55, 1.15) * (dead ? 0.75 : 1.0);
  const double rise = degrees(random.uniform(62.0, 88.0));
  const double bend = degrees(random.uniform(20.0, 70.0) + (dead ? 40.0 : 0.0));
  const double width = random.uniform(0.003, 0.007);
  builder.sheet(rows, 1, material, [&](double s, double q01) {
    const double q = 2 * q01 - 1;
    const Vec3 axis = bent_arc(base, out, kUp, length, rise, -bend, s);
    const double angle = rise - bend * s;
    const Vec3 tangent = out * std::cos(angle) + kUp * std::sin(angle);
    const Vec3 normal = cross(side, tangent);
    // Parallel sides tapering to a point (never zero: no slivers), folded along the midrib
    // above the ground (flat where it leaves the ground, so no edge dips below it).
    const double half_width = 0.5 * width * std::max(0.08, 1.0 - std::pow(s, 2.5));
    const double fold = 0.3 * half_width * std::abs(q) * std::min(1.0, 4 * s);
    return axis + side * (q * half_width) + normal * fold;
  });
}

}  // namespace

std::vector<Material> grass_materials() {
  return {
      {"grass", {0.07f, 0.24f, 0.03f}, 0.6f, 0.3f},
      {"grass_dry", {0.24f, 0.28f, 0.07f}, 0.7f, 0.2f},
      {"straw", {0.52f, 0.44f, 0.2f}, 0.8f, 0.1f},
  };
}

PlantModel make_grass_clump(std::uint64_t seed, int variant, std::size_t triangle_budget) {
  check_triangle_budget("grass", triangle_budget, kGrassMinimumTriangleBudget, kGrassMaximumTriangleBudget);
  const ClumpShape clump = draw_clump(seed, variant);
  // Rows first (the clump's own blade count at as many rows as fit), then as many blades of
  // those rows as the budget holds: within one blade of the budget.
  const int budget = int(triangle_budget);
  const int rows = std::clamp(budget / (2 * clump.blade_count), 1, kMaxBladeRows);
  const int blades = std::min(kMaxBlades, budget / (2 * rows));

  PlantModel model;
  Mesh& mesh = model.mesh;
  mesh.name = "grass_" + std::to_string(variant);
  mesh.materials = grass_materials();
  MeshBuilder builder(mesh);
  for (int k = 0; k < blades; ++k) add_blade(builder, clump, k, rows);
  rest_on_ground(mesh);
  compute_vertex_normals(mesh);
  model.extent = measure_extent(mesh);
  return model;
}

}  // namespace wangscape
