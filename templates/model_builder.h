// The building blocks every procedural plant (sunflower, grass, wildflower) is made of: double
// vectors, a deterministic random stream, and a mesh builder with grids, thin sheets and tubes.
// Double precision throughout: the meshes are built once, precision is free. Header only (the
// pieces are small templates over the caller's shape functions). Pure: thread safe.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/hash.h"
#include "templates/mesh.h"

namespace wangscape::model_geometry {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kGoldenAngle = kPi * (3.0 - 2.23606797749979);  // radians, ~137.5 degrees

struct Vec3 {
  double x = 0, y = 0, z = 0;
};
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline Vec3 normalize(Vec3 a) {
  const double length = std::sqrt(dot(a, a));
  return length > 0 ? a * (1.0 / length) : Vec3{0, 0, 1};
}
inline constexpr Vec3 kUp{0, 0, 1};

// Any unit vector perpendicular to unit vector `a`.
inline Vec3 perpendicular(Vec3 a) {
  const Vec3 helper = std::abs(a.z) < 0.9 ? kUp : Vec3{1, 0, 0};
  return normalize(cross(helper, a));
}

inline double degrees(double d) { return d * kPi / 180.0; }

// Throws Error unless a `kind` model's triangle budget lies in [low, high].
inline void check_triangle_budget(const char* kind, std::size_t budget, std::size_t low, std::size_t high) {
  if (budget < low || budget > high)
    throw Error(std::string(kind) + " triangle budget " + std::to_string(budget) + " is out of range: expected " +
                std::to_string(low) + " to " + std::to_string(high));
}
inline double lerp(double a, double b, double t) { return a + (b - a) * t; }

// Deterministic random numbers (SplitMix64), identical on every platform.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    state_ += 0x9e3779b97f4a7c15ull;
    return mix64(state_);
  }
  // Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * double(next() >> 11) * 0x1.0p-53; }
  // Uniform integer in [lo, hi].
  int integer(int lo, int hi) { return lo + int(next() % std::uint64_t(hi - lo + 1)); }

 private:
  std::uint64_t state_;
};

// ---- tessellation: one detail factor scales the resolution of every part ----

// A part's resolution at `detail` (0: the coarsest that keeps the part; 1: its full resolution
// `full`), never below `minimum`.
inline int scaled_resolution(double full, int minimum, double detail) {
  return std::max(minimum, int(std::lround(full * detail)));
}

// The largest detail in [0, 64] (to 40 halvings) at which fits(detail) holds, for a fits that holds
// up to some detail and not beyond (a triangle count within a budget); 0 if it never holds.
template <class Fits>
double finest_detail(const Fits& fits) {
  double lo = 0, hi = 64;
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (fits(mid) ? lo : hi) = mid;
  }
  return lo;
}

// Triangles of MeshBuilder::sheet.
inline std::size_t sheet_triangles(int rows, int columns) { return rows == 1 ? 2 : 2ull * rows * columns; }

class MeshBuilder {
 public:
  explicit MeshBuilder(Mesh& mesh) : mesh_(mesh) {}

  std::uint32_t vertex(Vec3 p) {
    mesh_.positions.push_back({float(p.x), float(p.y), float(p.z)});
    return std::uint32_t(mesh_.positions.size() - 1);
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint16_t material) {
    mesh_.triangles.push_back({a, b, c});
    mesh_.triangle_material.push_back(material);
  }

  // A (nu x nv)-quad grid over position(u, v), u in [0, 1] (or [0, 1) when wrap_u: a closed
  // tube), v in [0, 1]. Faces point along dP/du x dP/dv, or the other way when `flip`.
  template <class Position>
  void grid(int nu, int nv, bool wrap_u, bool flip, std::uint16_t material, Position position) {
    const int columns_u = wrap_u ? nu : nu + 1;
    const std::uint32_t first = std::uint32_t(mesh_.positions.size());
    for (int j = 0; j <= nv; ++j) {
      for (int i = 0; i < columns_u; ++i) vertex(position(double(i) / nu, double(j) / nv));
    }
    const auto index = [&](int i, int j) { return first + std::uint32_t(j * columns_u + (i % columns_u)); };
    for (int j = 0; j < nv; ++j) {
      for (int i = 0; i < nu; ++i) {
        const std::uint32_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
        if (flip) {
          triangle(a, c, b, material);
          triangle(a, d, c, material);
        } else {
          triangle(a, b, c, material);
          triangle(a, c, d, material);
        }
      }
    }
  }

  // A thin sheet (petal, leaf, blade) over position(s, q), s in [0, 1] base to tip, q in [0, 1]
  // edge to edge, facing along dP/ds x dP/dq. One row is a diamond (base, widest point, tip: two
  // triangles), which keeps a leaf's fold and a petal's outline at preview budgets.
  template <class Position>
  void sheet(int rows, int columns, std::uint16_t material, Position position) {
    if (rows > 1) {
      grid(rows, columns, false, false, material, position);
      return;
    }
    constexpr double kWidest = 0.4;
    const std::uint32_t base = vertex(position(0.0, 0.5));
    const std::uint32_t side_a = vertex(position(kWidest, 0.0));
    const std::uint32_t tip = vertex(position(1.0, 0.5));
    const std::uint32_t side_b = vertex(position(kWidest, 1.0));
    triangle(base, side_a, tip, material);
    triangle(base, tip, side_b, material);
  }

 private:
  Mesh& mesh_;
};

// A tube of `sides` around the polyline center(t), t in [0, 1], radius(t) meters; open ends.
// Frames are carried along by projection so the tube does not twist.
template <class Center, class Radius>
void add_tube(MeshBuilder& builder, int sides, int segments, std::uint16_t material, Center center, Radius radius) {
  std::vector<Vec3> points(segments + 1), normals(segments + 1), binormals(segments + 1);
  for (int j = 0; j <= segments; ++j) points[j] = center(double(j) / segments);
  for (int j = 0; j <= segments; ++j) {
    const Vec3 tangent = normalize(points[std::min(j + 1, segments)] - points[std::max(j - 1, 0)]);
    const Vec3 previous = j == 0 ? perpendicular(tangent) : normals[j - 1];
    normals[j] = normalize(previous - tangent * dot(previous, tangent));
    binormals[j] = cross(tangent, normals[j]);
  }
  // u around (normal toward binormal), v along: dP/du x dP/dv points outward.
  builder.grid(sides, segments, true, false, material, [&](double u, double v) {
    const int j = int(std::lround(v * segments));
    const double angle = 2 * kPi * u;
    return points[j] + (normals[j] * std::cos(angle) + binormals[j] * std::sin(angle)) * radius(v);
  });
}

// A point on a planar arc starting at `origin` along `out` and bending toward `up`: the
// direction at arc length s*length makes angle start + bend*s with `out`.
inline Vec3 bent_arc(Vec3 origin, Vec3 out, Vec3 up, double length, double start, double bend, double s) {
  if (std::abs(bend) < 1e-6) {
    return origin + (out * std::cos(start) + up * std::sin(start)) * (length * s);
  }
  const double angle = start + bend * s;
  const double along = (std::sin(angle) - std::sin(start)) / bend;
  const double across = (std::cos(start) - std::cos(angle)) / bend;
  return origin + (out * along + up * across) * length;
}

// Lets what hangs below the ground (a drooping leaf's tip, a blade bent over) lie on it: z = 0.
inline void rest_on_ground(Mesh& mesh) {
  for (auto& p : mesh.positions) p[2] = std::max(p[2], 0.0f);
}

// ---- flower heads ----

// A ray petal, ligule or bract of a flower head.
struct PetalShape {
  double angle;   // radians around the head axis
  double length;  // meters
  double width;   // meters
  double lift;    // radians, base angle out of the disk plane (+ toward the facing side)
  double curl;    // radians, added bend toward the back over the petal's length
  double twist;   // relative, tilts one edge forward and the other back
};

// The ranges a ring of bracts (the green sepals folded back under a flower head) is drawn from.
struct BractRanges {
  int count_low, count_high;       // how many
  double length_low, length_high;  // times the reference length (the disk's or the head's radius)
  double width_low, width_high;    // times the length
  double lift_low, lift_high;      // degrees
  double curl_low, curl_high;      // degrees
};
inline std::vector<PetalShape> draw_bracts(Random& random, double reference_length, const BractRanges& r) {
  const int count = random.integer(r.count_low, r.count_high);
  std::vector<PetalShape> bracts;
  for (int i = 0; i < count; ++i) {
    PetalShape bract;
    bract.angle = 2 * kPi * (i + random.uniform(-0.3, 0.3)) / count;
    bract.length = reference_length * random.uniform(r.length_low, r.length_high);
    bract.width = bract.length * random.uniform(r.width_low, r.width_high);
    bract.lift = degrees(random.uniform(r.lift_low, r.lift_high));
    bract.curl = degrees(random.uniform(r.curl_low, r.curl_high));
    bract.twist = random.uniform(-0.2, 0.2);
    bracts.push_back(bract);
  }
  return bracts;
}

// Head frame: `right` x `up_in_disk` = facing.
struct HeadFrame {
  Vec3 center, facing, right, up_in_disk;
  Vec3 radial(double angle) const { return right * std::cos(angle) + up_in_disk * std::sin(angle); }
};

// A ray petal or bract: leaves the head at `base` along radial direction `out`, bends back,
// cupped and twisted; the front side faces `facing`.
inline void add_petal(MeshBuilder& builder, const HeadFrame& head, const PetalShape& petal, Vec3 base, int rows,
                      int columns, std::uint16_t material, double cup) {
  const Vec3 out = head.radial(petal.angle);
  const Vec3 across = cross(head.facing, out);
  builder.sheet(rows, columns, material, [&](double s, double q01) {
    const double q = 2 * q01 - 1;  // -1 .. 1 across the petal
    const Vec3 axis = bent_arc(base, out, head.facing, petal.length, petal.lift, petal.curl, s);
    const double angle = petal.lift + petal.curl * s;
    const Vec3 front = head.facing * std::cos(angle) - out * std::sin(angle);
    // Narrow at the base, widest a third of the way out, pointed (never zero: no slivers).
    const double profile = std::max(0.12, std::pow(std::sin(kPi * std::pow(s, 0.65)), 0.8));
    const double half_width = 0.5 * petal.width * profile;
    return axis + across * (q * half_width) + front * (half_width * (cup * q * q + petal.twist * s * q));
  });
}

}  // namespace wangscape::model_geometry
