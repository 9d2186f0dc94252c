// [wind]: plants that sway. Each plant leans about its base, by an angle that a field of gusts
// gives at its place and time. The field is a few plane waves travelling with the wind, so
// neighbours lean together and gusts cross the field at the wind's speed; it is a sum of sines
// with constants fixed here, so POV-Ray (functions of the clock), Blender (geometry nodes of the
// scene time) and the Embree reference evaluate the very same lean (docs/scene-file.md).
#pragma once

#include <array>

namespace wangscape {

// [wind] as the scene file gives it.
struct WindConfig {
  double direction = 90;   // compass degrees the wind blows toward (0 north, 90 east)
  double strength = 10;    // degrees: the lean of a plant in the strongest gust; 0 is calm
  double gust_scale = 15;  // meters: the size of a gust (the longest wave of the field)
  double speed = 3;        // meters a second the gusts travel
};

// How far a plant leans: the top moves toward east by `east` degrees and toward north by `north`.
struct WindLean {
  double east = 0, north = 0;
};

// lean = base + sum over waves of amplitude * sin(k_east * E + k_north * N + k_time * t + phase),
// E and N in ENU meters, t in seconds.
struct WindWave {
  double k_east = 0, k_north = 0, k_time = 0, phase = 0;  // radians per meter, per second; radians
  double amplitude_east = 0, amplitude_north = 0;         // degrees
};

struct WindField {
  WindLean base;
  std::array<WindWave, 4> waves{};

  WindLean lean(double east, double north, double seconds) const;
};

// The field of a [wind] section with a strength above 0.
WindField wind_field(const WindConfig& config);

// The rotation (row-major 3 x 3 over ENU) that leans a plant standing at the origin by `lean`:
// first about the east axis, its top toward north by lean.north, then about the north axis, its
// top toward east by lean.east (in POV-Ray `rotate <north, 0, -east>`, in Blender the Euler XYZ
// (-north, east, 0), both in radians or degrees as each takes them).
std::array<double, 9> lean_rotation(const WindLean& lean);

}  // namespace wangscape
