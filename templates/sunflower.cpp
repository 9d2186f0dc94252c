#include "templates/sunflower.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "templates/model_builder.h"

namespace wangscape {
namespace {

using namespace model_geometry;

constexpr int kFloretSides = 6;
// Share of the budget for everything but the florets, which take the rest: the seed head is
// where a close-up spends its detail.
constexpr double kNonFloretShare = 0.45;

// ---- the shape of one variant: everything random is drawn here, before any tessellation ----

struct LeafShape {
  double stem_position;   // 0..1 along the stem curve
  double azimuth;         // radians around z
  double length;          // meters, blade
  double width;           // meters, blade
  double petiole_length;  // meters
  double rise;            // radians, blade start above horizontal
  double droop;           // radians, how much the midrib bends down to the tip
  double wave_phase;      // radians
  double roll;            // radians, blade turned about its midrib
};

struct SunflowerShape {
  Vec3 head_center;         // meters
  Vec3 facing;              // unit
  double head_diameter;     // meters, petal tip to tip
  double disk_radius;       // meters
  double dome_height;       // meters, disk bulge
  double receptacle_depth;  // meters, back of the head behind the disk
  double stem_radius;       // meters, at the base
  Vec3 stem_lean;           // meters, horizontal offset of the lower stem's control point
  std::vector<LeafShape> leaves;
  std::vector<PetalShape> petals;  // inner ring first, then outer ring
  int inner_petal_count;
  std::vector<PetalShape> bracts;  // green sepals on the back of the head
};

SunflowerShape draw_shape(std::uint64_t seed, int variant) {
  Random random(mix64(seed ^ mix64(std::uint64_t(variant) + 0x51u)));
  SunflowerShape shape;
  const double center_height = random.uniform(1.55, 2.65);
  shape.head_diameter = random.uniform(0.17, 0.37);
  shape.disk_radius = 0.5 * shape.head_diameter * random.uniform(0.42, 0.56);
  shape.dome_height = shape.disk_radius * random.uniform(0.04, 0.12);
  shape.receptacle_depth = shape.disk_radius * random.uniform(0.25, 0.35);

  // Facing: roughly +x, turned a little, drooping (mature heads nod).
  const double yaw = degrees(random.uniform(-30.0, 30.0));
  const double elevation = degrees(random.uniform(-35.0, 10.0));
  shape.facing = {std::cos(elevation) * std::cos(yaw), std::cos(elevation) * std::sin(yaw), std::sin(elevation)};
  // The neck bends over: the head sits forward of the stem base.
  const double reach = random.uniform(0.08, 0.2);
  shape.head_center = {reach * std::cos(yaw), reach * std::sin(yaw), center_height};

  shape.stem_radius = random.uniform(0.011, 0.017) * (0.75 + 0.15 * center_height);
  const double lean_azimuth = random.uniform(0.0, 2 * kPi);
  const double lean = random.uniform(0.0, 0.06);
  shape.stem_lean = {lean * std::cos(lean_azimuth), lean * std::sin(lean_azimuth), 0};

  const int leaf_count = random.integer(9, 14);
  const double largest_leaf = random.uniform(0.36, 0.5);
  double azimuth = random.uniform(0.0, 2 * kPi);
  for (int i = 0; i < leaf_count; ++i) {
    LeafShape leaf;
    const double t = (i + random.uniform(0.2, 0.8)) / leaf_count;
    leaf.stem_position = lerp(0.1, 0.86, t);
    azimuth += kGoldenAngle + random.uniform(-0.25, 0.25);
    leaf.azimuth = azimuth;
    leaf.length = largest_leaf * (1.0 - 0.5 * t) * random.uniform(0.85, 1.1);
    leaf.width = leaf.length * random.uniform(0.7, 0.9);
    leaf.petiole_length = leaf.length * random.uniform(0.3, 0.45);
    leaf.rise = degrees(random.uniform(10.0, 35.0));
    leaf.droop = degrees(random.uniform(40.0, 75.0));
    leaf.wave_phase = random.uniform(0.0, 2 * kPi);
    leaf.roll = degrees(random.uniform(-50.0, 50.0));
    shape.leaves.push_back(leaf);
  }

  // Two rings of ray petals; real heads carry 34-55 (Fibonacci) of them.
  static constexpr int kRingCounts[] = {13, 17, 21};
  shape.inner_petal_count = kRingCounts[random.integer(0, 2)];
  const int outer_count = shape.inner_petal_count + random.integer(0, 4);
  const double petal_length = 0.5 * shape.head_diameter - 0.92 * shape.disk_radius;
  const double petal_width_ratio = random.uniform(0.3, 0.4);
  for (int ring = 0; ring < 2; ++ring) {
    const int count = ring == 0 ? shape.inner_petal_count : outer_count;
    const double offset = random.uniform(0.0, 2 * kPi);
    for (int i = 0; i < count; ++i) {
      PetalShape petal;
      petal.angle = offset + 2 * kPi * (i + random.uniform(-0.2, 0.2)) / count;
      petal.length = petal_length * random.uniform(0.88, 1.0) * (ring == 0 ? 0.95 : 1.0);
      petal.width = petal.length * petal_width_ratio * random.uniform(0.85, 1.15);
      petal.lift = degrees(ring == 0 ? random.uniform(0.0, 14.0) : random.uniform(-10.0, 4.0));
      petal.curl = degrees(random.uniform(-45.0, -10.0));
      petal.twist = random.uniform(-0.35, 0.35);
      shape.petals.push_back(petal);
    }
  }
  shape.bracts = draw_bracts(random, shape.disk_radius, {16, 24, 0.45, 0.7, 0.35, 0.5, -40.0, -20.0, -50.0, -20.0});
  return shape;
}

// ---- tessellation: resolutions of every part, scaled together by one detail factor ----

struct Tessellation {
  int stem_sides, stem_segments;
  int leaf_rows, leaf_half_columns;
  int petiole_sides, petiole_segments;
  int head_sectors, receptacle_rings, disk_rings;
  int petal_rows, petal_columns;
  int bract_rows, bract_columns;
  int floret_count = 0;
};

// detail 0 is the coarsest that keeps every part; detail 1 is roughly a 20,000-triangle flower.
Tessellation tessellation_for_detail(double detail) {
  const auto scaled = [detail](double full, int minimum) { return scaled_resolution(full, minimum, detail); };
  Tessellation t;
  t.stem_sides = scaled(14, 5);
  t.stem_segments = scaled(36, 3);
  t.leaf_rows = scaled(12, 1);
  t.leaf_half_columns = scaled(4, 1);
  t.petiole_sides = scaled(6, 3);
  t.petiole_segments = scaled(4, 1);
  t.head_sectors = scaled(64, 8);
  t.receptacle_rings = scaled(10, 1);
  t.disk_rings = scaled(16, 1);
  t.petal_rows = scaled(9, 1);
  t.petal_columns = scaled(3, 1);
  t.bract_rows = scaled(4, 1);
  t.bract_columns = scaled(2, 1);
  return t;
}

std::size_t non_floret_triangles(const Tessellation& t, const SunflowerShape& shape) {
  const std::size_t stem = 2ull * t.stem_sides * t.stem_segments;
  const std::size_t leaf =
      sheet_triangles(t.leaf_rows, 2 * t.leaf_half_columns) + 2ull * t.petiole_sides * t.petiole_segments;
  const std::size_t receptacle = 2ull * t.head_sectors * t.receptacle_rings;
  const std::size_t disk = std::size_t(t.head_sectors) * (2 * t.disk_rings - 1);
  const std::size_t petal = sheet_triangles(t.petal_rows, t.petal_columns);
  const std::size_t bract = sheet_triangles(t.bract_rows, t.bract_columns);
  return stem + leaf * shape.leaves.size() + receptacle + disk + petal * shape.petals.size() +
         bract * shape.bracts.size();
}

// The finest tessellation whose non-floret parts fit their share, then florets fill the budget.
Tessellation plan_tessellation(const SunflowerShape& shape, std::size_t budget) {
  const double target = kNonFloretShare * double(budget);
  Tessellation t = tessellation_for_detail(finest_detail(
      [&](double detail) { return double(non_floret_triangles(tessellation_for_detail(detail), shape)) <= target; }));
  const std::size_t rest = budget - std::min(budget, non_floret_triangles(t, shape));
  t.floret_count = int(rest / kFloretSides);
  return t;
}

// ---- the parts ----

// Cubic Bezier stem from the origin into the back of the head.
struct StemCurve {
  Vec3 p0, p1, p2, p3;
  Vec3 at(double t) const {
    const double s = 1 - t;
    return p0 * (s * s * s) + p1 * (3 * s * s * t) + p2 * (3 * s * t * t) + p3 * (t * t * t);
  }
};

StemCurve stem_curve(const SunflowerShape& shape) {
  const Vec3 end = shape.head_center - shape.facing * (0.8 * shape.receptacle_depth);
  // The neck arrives from below and behind, into the back of the head.
  const Vec3 end_tangent = normalize(shape.facing + kUp * 0.9);
  const double height = end.z;
  return {{0, 0, 0}, shape.stem_lean + kUp * (0.45 * height), end - end_tangent * (0.3 * height), end};
}

double stem_radius_at(const SunflowerShape& shape, double t) { return shape.stem_radius * (1.0 - 0.45 * t); }

void add_leaf(MeshBuilder& builder, const Tessellation& tess, const SunflowerShape& shape, const StemCurve& stem,
              const LeafShape& leaf) {
  const Vec3 attach = stem.at(leaf.stem_position);
  const Vec3 out{std::cos(leaf.azimuth), std::sin(leaf.azimuth), 0};
  // Rolled about the midrib, so a field seen from the side shows blades, not edges.
  const Vec3 side = cross(kUp, out) * std::cos(leaf.roll) + kUp * std::sin(leaf.roll);
  // The petiole leaves the stem at 45 degrees and sags to 20 at the blade.
  const double stem_radius = stem_radius_at(shape, leaf.stem_position);
  const Vec3 petiole_start = attach - out * (0.5 * stem_radius);
  const auto petiole = [&](double s) {
    return bent_arc(petiole_start, out, kUp, leaf.petiole_length, degrees(45), degrees(-25), s);
  };
  const double petiole_radius = std::max(0.003, 0.35 * stem_radius);
  add_tube(builder, tess.petiole_sides, tess.petiole_segments, sunflower_stem, petiole,
           [&](double s) { return petiole_radius * (1.0 - 0.3 * s); });

  // Blade: a midrib arc drooping toward the tip, the halves folded up along it, edges curled.
  const Vec3 blade_base = petiole(1.0);
  const int columns = 2 * tess.leaf_half_columns;
  builder.sheet(tess.leaf_rows, columns, sunflower_leaf, [&](double s, double q01) {
    const double q = 2 * q01 - 1;
    const Vec3 midrib = bent_arc(blade_base, out, kUp, leaf.length, leaf.rise, -leaf.droop, s);
    const double angle = leaf.rise - leaf.droop * s;
    const Vec3 normal = normalize(cross(out * std::cos(angle) + kUp * std::sin(angle), side));
    // Heart shaped: broad near the base, pointed at the tip.
    const double profile = std::max(0.06, std::pow(std::sin(kPi * std::pow(s, 0.7)), 0.9));
    const double half_width = 0.5 * leaf.width * profile;
    const double fold = 0.35 * std::abs(q) - 0.3 * q * q;
    const double wave = 0.04 * q * q * std::sin(7 * kPi * s + leaf.wave_phase);
    return midrib + side * (q * half_width) + normal * (half_width * (fold + wave));
  });
}

void add_head(MeshBuilder& builder, const Tessellation& tess, const SunflowerShape& shape, const HeadFrame& head,
              SunflowerModel& model) {
  const int sectors = tess.head_sectors;
  const double radius = shape.disk_radius;
  const auto dome = [&](double rho, double angle) {
    return head.center + head.facing * (shape.dome_height * (1 - rho * rho)) + head.radial(angle) * (rho * radius);
  };

  // Disk: a center fan, then rings each turned half a sector so the facets run in spirals.
  const std::uint32_t center = builder.vertex(dome(0, 0));
  const double twist = kPi / sectors;
  std::vector<std::uint32_t> previous, ring(sectors);
  for (int k = 1; k <= tess.disk_rings; ++k) {
    const double rho = double(k) / tess.disk_rings;
    for (int s = 0; s < sectors; ++s) ring[s] = builder.vertex(dome(rho, 2 * kPi * s / sectors + k * twist));
    for (int s = 0; s < sectors; ++s) {
      const std::uint32_t a = ring[s], b = ring[(s + 1) % sectors];
      if (k == 1) {
        builder.triangle(center, a, b, sunflower_disk);
      } else {
        // Ring k is turned half a sector past ring k-1: previous[s+1] sits between a and b,
        // and a between previous[s] and previous[s+1].
        const std::uint32_t inner_next = previous[(s + 1) % sectors];
        builder.triangle(inner_next, a, b, sunflower_disk);
        builder.triangle(previous[s], a, inner_next, sunflower_disk);
      }
    }
    previous = ring;
  }

  // Receptacle: the green bowl behind the disk, from a rim just outside it to the neck.
  const double neck_radius = 0.9 * stem_radius_at(shape, 1.0);
  builder.grid(sectors, tess.receptacle_rings, true, true, sunflower_stem, [&](double u, double v) {
    const double r = lerp(neck_radius, 1.03 * radius, std::cos(0.5 * kPi * v));
    const double back = shape.receptacle_depth * std::sin(0.5 * kPi * v) + 0.002;
    return head.center + head.radial(2 * kPi * u) * r - head.facing * back;
  });

  // Florets: a Vogel spiral of small cones, smaller toward the young center.
  const int n = tess.floret_count;
  model.floret_count = n;
  const double spiral_radius = 0.97 * radius;
  for (int k = 0; k < n; ++k) {
    const double rho = std::sqrt((k + 0.5) / n) * spiral_radius / radius;
    const double angle = k * kGoldenAngle;
    const Vec3 base = dome(rho, angle);
    const Vec3 normal = normalize(head.facing + head.radial(angle) * (2 * shape.dome_height * rho / radius));
    const double base_radius = 0.95 * spiral_radius / std::sqrt(double(n)) * (0.75 + 0.35 * rho);
    // Capped so that the few big florets of a preview stay low bumps, not spikes.
    const double cone_height = std::min(1.1 * base_radius, 0.03 * radius);
    const Vec3 e1 = perpendicular(normal);
    const Vec3 e2 = cross(normal, e1);
    const std::uint32_t tip = builder.vertex(base + normal * (0.85 * cone_height));
    const std::uint32_t first = tip + 1;
    for (int j = 0; j < kFloretSides; ++j) {
      const double a = angle + 2 * kPi * j / kFloretSides;
      builder.vertex(base + (e1 * std::cos(a) + e2 * std::sin(a)) * base_radius - normal * (0.15 * cone_height));
    }
    for (int j = 0; j < kFloretSides; ++j) {
      builder.triangle(tip, first + j, first + (j + 1) % kFloretSides, sunflower_disk);
    }
  }

  // Two rings of ray petals around the disk, the outer ring a little behind the inner one.
  for (std::size_t i = 0; i < shape.petals.size(); ++i) {
    const bool inner = int(i) < shape.inner_petal_count;
    const PetalShape& petal = shape.petals[i];
    const Vec3 base =
        head.center + head.radial(petal.angle) * (0.92 * radius) - head.facing * (inner ? 0.004 : 0.01 + 0.02 * radius);
    add_petal(builder, head, petal, base, tess.petal_rows, tess.petal_columns, sunflower_petal, 0.25);
  }
  // Bracts: pointed green sepals on the back of the bowl, bent backward.
  for (const PetalShape& bract : shape.bracts) {
    const Vec3 base =
        head.center + head.radial(bract.angle) * (0.85 * radius) - head.facing * (0.35 * shape.receptacle_depth);
    add_petal(builder, head, bract, base, tess.bract_rows, tess.bract_columns, sunflower_leaf, 0.15);
  }
}

HeadFrame head_frame(const SunflowerShape& shape) {
  HeadFrame head;
  head.center = shape.head_center;
  head.facing = shape.facing;
  head.right = normalize(cross(kUp, shape.facing));
  head.up_in_disk = cross(head.facing, head.right);
  return head;
}

std::array<float, 3> to_floats(Vec3 v) { return {float(v.x), float(v.y), float(v.z)}; }

}  // namespace

std::vector<Material> sunflower_materials() {
  return {
      {"petal", {0.85f, 0.55f, 0.02f}, 0.6f, 0.35f},
      {"disk", {0.09f, 0.045f, 0.015f}, 0.9f, 0.0f},
      {"stem", {0.16f, 0.32f, 0.05f}, 0.7f, 0.1f},
      {"leaf", {0.09f, 0.26f, 0.03f}, 0.6f, 0.3f},
  };
}

SunflowerModel make_sunflower(std::uint64_t seed, int variant, std::size_t triangle_budget) {
  check_triangle_budget("sunflower", triangle_budget, kSunflowerMinimumTriangleBudget, kSunflowerMaximumTriangleBudget);
  const SunflowerShape shape = draw_shape(seed, variant);
  const Tessellation tess = plan_tessellation(shape, triangle_budget);

  SunflowerModel model;
  Mesh& mesh = model.mesh;
  mesh.name = "sunflower_" + std::to_string(variant);
  mesh.materials = sunflower_materials();
  mesh.positions.reserve(triangle_budget);
  mesh.triangles.reserve(triangle_budget);
  mesh.triangle_material.reserve(triangle_budget);
  MeshBuilder builder(mesh);

  const StemCurve stem = stem_curve(shape);
  add_tube(
      builder, tess.stem_sides, tess.stem_segments, sunflower_stem, [&](double t) { return stem.at(t); },
      [&](double t) { return stem_radius_at(shape, t); });
  for (const LeafShape& leaf : shape.leaves) add_leaf(builder, tess, shape, stem, leaf);
  const HeadFrame head = head_frame(shape);
  add_head(builder, tess, shape, head, model);
  compute_vertex_normals(mesh);

  model.extent = measure_extent(mesh);
  float crown_squared = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (mesh.triangle_material[t] != sunflower_petal && mesh.triangle_material[t] != sunflower_disk) continue;
    for (std::uint32_t v : mesh.triangles[t]) {
      const auto& p = mesh.positions[v];
      crown_squared = std::max(crown_squared, p[0] * p[0] + p[1] * p[1]);
    }
  }
  model.crown_radius = std::sqrt(crown_squared);
  model.head_diameter = float(shape.head_diameter);
  model.disk_diameter = float(2 * shape.disk_radius);
  model.head_center = to_floats(shape.head_center);
  model.head_facing = to_floats(shape.facing);
  return model;
}

std::vector<SunflowerModel> make_sunflower_variants(const SunflowerOptions& options) {
  if (options.variant_count < 1) {
    throw Error("sunflower variant count " + std::to_string(options.variant_count) + " is invalid: expected >= 1");
  }
  std::vector<SunflowerModel> models;
  models.reserve(options.variant_count);
  for (int variant = 0; variant < options.variant_count; ++variant) {
    models.push_back(make_sunflower(options.seed, variant, options.triangle_budget));
  }
  return models;
}

}  // namespace wangscape
