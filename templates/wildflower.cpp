#include "templates/wildflower.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "templates/model_builder.h"

namespace wangscape {
namespace {

using namespace model_geometry;

struct BasalLeaf {
  double azimuth;  // radians around z
  double length;   // meters
  double width;    // meters
  double rise;     // radians above the ground at the base
  double droop;    // radians the midrib bends down toward the tip
  int teeth;       // lobes along each edge (runcinate, like a dandelion's)
};

struct WildflowerShape {
  Vec3 head_center;    // meters
  Vec3 facing;         // unit, up and tilted
  double disk_radius;  // meters, the head's yellow centre
  double stem_radius;  // meters
  Vec3 stem_bend;      // meters, horizontal offset of the stem's middle control point
  std::vector<BasalLeaf> leaves;
  std::vector<PetalShape> ligules;  // inner ring first
  std::vector<PetalShape> bracts;   // green, folded back under the head
};

WildflowerShape draw_shape(std::uint64_t seed, int variant) {
  Random random(mix64(seed ^ mix64(std::uint64_t(variant) + 0x77u)));
  WildflowerShape shape;
  const double height = random.uniform(0.12, 0.32);
  const double tilt = degrees(random.uniform(0.0, 35.0));
  const double tilt_azimuth = random.uniform(0.0, 2 * kPi);
  const Vec3 tilt_direction{std::cos(tilt_azimuth), std::sin(tilt_azimuth), 0};
  shape.facing = normalize(kUp * std::cos(tilt) + tilt_direction * std::sin(tilt));
  // The stem bends toward where the head leans.
  shape.head_center = tilt_direction * (0.25 * height * std::sin(tilt)) + kUp * height;
  shape.stem_bend = tilt_direction * random.uniform(0.0, 0.04);
  shape.stem_radius = random.uniform(0.0018, 0.0028);
  const double head_radius = random.uniform(0.018, 0.028);  // a little large: it must read in a meadow
  shape.disk_radius = 0.3 * head_radius;

  const int leaf_count = random.integer(5, 9);
  double azimuth = random.uniform(0.0, 2 * kPi);
  for (int i = 0; i < leaf_count; ++i) {
    BasalLeaf leaf;
    azimuth += kGoldenAngle + random.uniform(-0.2, 0.2);
    leaf.azimuth = azimuth;
    leaf.length = random.uniform(0.08, 0.18);
    leaf.width = leaf.length * random.uniform(0.18, 0.28);
    leaf.rise = degrees(random.uniform(10.0, 35.0));
    leaf.droop = degrees(random.uniform(15.0, 45.0));
    leaf.teeth = random.integer(3, 5);
    shape.leaves.push_back(leaf);
  }

  // Three rings of ligules, each longer and flatter than the one inside (a dandelion's pompom).
  static constexpr int kRingCounts[2][3] = {{8, 13, 21}, {13, 21, 34}};
  const int* counts = kRingCounts[random.integer(0, 1)];
  for (int ring = 0; ring < 3; ++ring) {
    const double offset = random.uniform(0.0, 2 * kPi);
    for (int i = 0; i < counts[ring]; ++i) {
      PetalShape ligule;
      ligule.angle = offset + 2 * kPi * (i + random.uniform(-0.25, 0.25)) / counts[ring];
      ligule.length = (head_radius - shape.disk_radius) * (0.55 + 0.225 * ring) * random.uniform(0.9, 1.1);
      ligule.width = ligule.length * random.uniform(0.22, 0.3);
      ligule.lift = degrees((ring == 0 ? 60.0 : ring == 1 ? 35.0 : 10.0) + random.uniform(-8.0, 8.0));
      ligule.curl = degrees(random.uniform(-15.0, 5.0));
      ligule.twist = random.uniform(-0.3, 0.3);
      shape.ligules.push_back(ligule);
    }
  }
  shape.bracts = draw_bracts(random, head_radius, {8, 12, 0.5, 0.7, 0.2, 0.3, -80.0, -50.0, -30.0, -10.0});
  return shape;
}

struct Tessellation {
  int stem_sides, stem_segments;
  int leaf_rows, leaf_half_columns;
  int disk_sectors, disk_rings;
  int ligule_rows, ligule_columns;
  int bract_rows;
};

// detail 0 is the coarsest that keeps every part; detail 1 is roughly a 2,800-triangle flower.
Tessellation tessellation_for_detail(double detail) {
  const auto scaled = [detail](double full, int minimum) { return scaled_resolution(full, minimum, detail); };
  Tessellation t;
  t.stem_sides = scaled(10, 4);
  t.stem_segments = scaled(16, 3);
  t.leaf_rows = scaled(14, 1);
  t.leaf_half_columns = scaled(3, 1);
  t.disk_sectors = scaled(24, 8);
  t.disk_rings = scaled(4, 1);
  t.ligule_rows = scaled(4, 1);
  t.ligule_columns = scaled(2, 1);
  t.bract_rows = scaled(3, 1);
  return t;
}

std::size_t triangle_count(const Tessellation& t, const WildflowerShape& shape) {
  const std::size_t stem = 2ull * t.stem_sides * t.stem_segments;
  const std::size_t leaf = sheet_triangles(t.leaf_rows, 2 * t.leaf_half_columns);
  const std::size_t disk = std::size_t(t.disk_sectors) * (2 * t.disk_rings - 1);
  const std::size_t ligule = sheet_triangles(t.ligule_rows, t.ligule_columns);
  const std::size_t bract = sheet_triangles(t.bract_rows, 1);
  return stem + leaf * shape.leaves.size() + disk + ligule * shape.ligules.size() + bract * shape.bracts.size();
}

// The finest tessellation that fits the budget (detail 0 always does above the minimum budget).
Tessellation plan_tessellation(const WildflowerShape& shape, std::size_t budget) {
  return tessellation_for_detail(
      finest_detail([&](double detail) { return triangle_count(tessellation_for_detail(detail), shape) <= budget; }));
}

Vec3 stem_at(const WildflowerShape& shape, double t) {
  // A quadratic Bezier from the ground into the back of the head.
  const Vec3 end = shape.head_center - shape.facing * 0.003;
  const Vec3 middle = kUp * (0.5 * end.z) + shape.stem_bend;
  const double s = 1 - t;
  return middle * (2 * s * t) + end * (t * t);
}

void add_leaf(MeshBuilder& builder, const Tessellation& tess, const BasalLeaf& leaf) {
  const Vec3 out{std::cos(leaf.azimuth), std::sin(leaf.azimuth), 0};
  const Vec3 side = cross(kUp, out);
  const Vec3 base = out * 0.004 + kUp * 0.002;
  builder.sheet(tess.leaf_rows, 2 * tess.leaf_half_columns, wildflower_leaf, [&](double s, double q01) {
    const double q = 2 * q01 - 1;
    const Vec3 midrib = bent_arc(base, out, kUp, leaf.length, leaf.rise, -leaf.droop, s);
    // Lanceolate, widest past the middle, cut into lobes pointing back toward the rosette.
    const double outline = std::pow(std::sin(kPi * std::pow(s, 0.75)), 0.8);
    const double lobe = std::fmod(s * leaf.teeth, 1.0);
    const double half_width = 0.5 * leaf.width * std::max(0.06, outline * (0.55 + 0.45 * lobe));
    return midrib + side * (q * half_width) + kUp * (0.15 * half_width * q * q);
  });
}

void add_head(MeshBuilder& builder, const Tessellation& tess, const WildflowerShape& shape) {
  HeadFrame head;
  head.center = shape.head_center;
  head.facing = shape.facing;
  head.right = perpendicular(shape.facing);
  head.up_in_disk = cross(head.facing, head.right);
  // The yellow centre: a low dome, a fan and then rings.
  const auto dome = [&](double rho, double angle) {
    return head.center + head.facing * (0.4 * shape.disk_radius * (1 - rho * rho)) +
           head.radial(angle) * (rho * shape.disk_radius);
  };
  const int sectors = tess.disk_sectors;
  const std::uint32_t centre = builder.vertex(dome(0, 0));
  std::vector<std::uint32_t> previous, ring(sectors);
  for (int k = 1; k <= tess.disk_rings; ++k) {
    for (int s = 0; s < sectors; ++s)
      ring[s] = builder.vertex(dome(double(k) / tess.disk_rings, 2 * kPi * s / sectors));
    for (int s = 0; s < sectors; ++s) {
      const std::uint32_t a = ring[s], b = ring[(s + 1) % sectors];
      if (k == 1) {
        builder.triangle(centre, a, b, wildflower_petal);
      } else {
        builder.triangle(previous[s], a, b, wildflower_petal);
        builder.triangle(previous[s], b, previous[(s + 1) % sectors], wildflower_petal);
      }
    }
    previous = ring;
  }
  for (const PetalShape& ligule : shape.ligules) {
    const Vec3 base = head.center + head.radial(ligule.angle) * (0.8 * shape.disk_radius);
    add_petal(builder, head, ligule, base, tess.ligule_rows, tess.ligule_columns, wildflower_petal, 0.2);
  }
  for (const PetalShape& bract : shape.bracts) {
    const Vec3 base = head.center + head.radial(bract.angle) * (0.7 * shape.disk_radius) - head.facing * 0.002;
    add_petal(builder, head, bract, base, tess.bract_rows, 1, wildflower_leaf, 0.1);
  }
}

}  // namespace

std::vector<Material> wildflower_materials() {
  return {
      {"petal", {0.9f, 0.62f, 0.01f}, 0.6f, 0.35f},
      {"stem", {0.18f, 0.34f, 0.08f}, 0.7f, 0.15f},
      {"leaf", {0.08f, 0.25f, 0.04f}, 0.6f, 0.3f},
  };
}

PlantModel make_wildflower(std::uint64_t seed, int variant, std::size_t triangle_budget) {
  check_triangle_budget("wildflower", triangle_budget, kWildflowerMinimumTriangleBudget,
                        kWildflowerMaximumTriangleBudget);
  const WildflowerShape shape = draw_shape(seed, variant);
  const Tessellation tess = plan_tessellation(shape, triangle_budget);
  PlantModel model;
  Mesh& mesh = model.mesh;
  mesh.name = "wildflower_" + std::to_string(variant);
  mesh.materials = wildflower_materials();
  MeshBuilder builder(mesh);
  add_tube(
      builder, tess.stem_sides, tess.stem_segments, wildflower_stem, [&](double t) { return stem_at(shape, t); },
      [&](double t) { return shape.stem_radius * (1.0 - 0.25 * t); });
  for (const BasalLeaf& leaf : shape.leaves) add_leaf(builder, tess, leaf);
  add_head(builder, tess, shape);
  rest_on_ground(mesh);
  compute_vertex_normals(mesh);
  model.extent = measure_extent(mesh);
  return model;
}

}  // namespace wangscape
