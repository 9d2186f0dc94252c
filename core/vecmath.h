// Three-vectors as std::array<T, 3> (float or double, ENU meters or unit directions), in the
// manner of pbrt-v4's util/vecmath.h: dot, cross, length, normalized, and one camera basis.
// Templates, so float stays float and double stays double with the same operation order.
// Pure functions: thread safe.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "core/error.h"
#include "core/number_text.h"

namespace wangscape {

template <typename T>
using Vector3 = std::array<T, 3>;
using Vector3d = Vector3<double>;
using Vector3f = Vector3<float>;

template <typename T>
constexpr T dot(const Vector3<T>& a, const Vector3<T>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

template <typename T>
constexpr Vector3<T> cross(const Vector3<T>& a, const Vector3<T>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

template <typename T>
T length(const Vector3<T>& a) {
  return std::sqrt(dot(a, a));
}

// a / |a| (each component divided by the length); not finite for a zero vector.
template <typename T>
Vector3<T> normalized(const Vector3<T>& a) {
  const T n = length(a);
  return {a[0] / n, a[1] / n, a[2] / n};
}

template <typename T>
constexpr Vector3<T> operator+(const Vector3<T>& a, const Vector3<T>& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}

template <typename T>
constexpr Vector3<T> operator-(const Vector3<T>& a, const Vector3<T>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

template <typename T>
constexpr Vector3<T> operator*(T s, const Vector3<T>& a) {
  return {s * a[0], s * a[1], s * a[2]};
}

// ---- the camera ------------------------------------------------------------------------------

// The widest horizontal field of view any camera takes (the scene file, the reference renderer,
// the view), degrees, itself allowed; the narrowest is above 0. A pinhole's image plane grows as
// tan(fov / 2), unbounded at 180.
// 0 below lo, 1 above hi, the smooth cubic 3t^2 - 2t^3 between (a step at lo when hi <= lo).
inline float smoothstep(double lo, double hi, double v) {
  if (hi <= lo) return v >= lo ? 1.f : 0.f;
  const double t = std::clamp((v - lo) / (hi - lo), 0.0, 1.0);
  return static_cast<float>(t * t * (3 - 2 * t));
}

inline constexpr double kMaxFieldOfViewDegrees = 179;

// Whether `degrees` is a horizontal field of view a camera takes: in (0, kMaxFieldOfViewDegrees].
inline bool valid_field_of_view(double degrees) { return degrees > 0 && degrees <= kMaxFieldOfViewDegrees; }

// Throws Error("<what> <degrees>: expected degrees in (0, 179]") unless valid_field_of_view; `what`
// names the value for the user ("--fov", "reference render: camera field of view").
inline void check_field_of_view(double degrees, std::string_view what) {
  if (!valid_field_of_view(degrees))
    throw Error(std::string(what) + " " + number_text(degrees) + ": expected degrees in (0, " +
                number_text(kMaxFieldOfViewDegrees) + "]");
}

// Unit vectors of a camera looking from a position at a target: forward (to the target), right
// (forward x world up, normalized) and up (right x forward). Right-handed; with world up +z
// (ENU), right is horizontal.
struct CameraBasis {
  Vector3<double> forward, right, up;
};

// The basis, or nothing when the camera cannot frame a horizon: a position or target that is not
// finite, the target at the position, or the target straight above or below it along `world_up`
// (the horizontal part of the unit forward vector under 1e-9).
inline std::optional<CameraBasis> camera_basis(const Vector3<double>& position, const Vector3<double>& target,
                                               const Vector3<double>& world_up = {0, 0, 1}) {
  const Vector3<double> look = target - position;
  const double look_length = length(look);
  if (!(look_length > 0) || !std::isfinite(look_length)) return std::nullopt;
  CameraBasis b;
  b.forward = {look[0] / look_length, look[1] / look_length, look[2] / look_length};
  const Vector3<double> r = cross(b.forward, world_up);
  const double r_length = length(r);
  if (!(r_length > 1e-9)) return std::nullopt;
  b.right = {r[0] / r_length, r[1] / r_length, r[2] / r_length};
  b.up = cross(b.right, b.forward);
  return b;
}

}  // namespace wangscape
