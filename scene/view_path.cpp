#include "scene/view_path.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "core/error.h"
#include "core/number_text.h"
#include "core/text_file.h"
#include "core/vecmath.h"

namespace wangscape {

namespace fs = std::filesystem;

namespace {

using PathJson = nlohmann::json;  // not tileset_file.h's ordered Json: a path file is only read

// "LINE:COLUMN" of a byte offset (nlohmann counts from 1, past the byte at fault).
std::string line_and_column(std::string_view text, std::size_t byte) {
  byte = std::min(byte > 0 ? byte - 1 : 0, text.size());
  const std::size_t line = 1 + std::size_t(std::count(text.begin(), text.begin() + std::ptrdiff_t(byte), '\n'));
  const std::size_t line_start = text.rfind('\n', byte == 0 ? 0 : byte - 1);
  const std::size_t column = line_start == std::string_view::npos || byte == 0 ? byte + 1 : byte - line_start;
  return std::to_string(line) + ":" + std::to_string(column);
}

PathJson parse_json(std::string_view text, const fs::path& file) {
  check_nesting(text, file, kMaxNesting);
  try {
    return PathJson::parse(text.begin(), text.end(), nullptr, true, false);
  } catch (const PathJson::parse_error& e) {
    throw Error(file, line_and_column(text, e.byte), "not valid JSON here (expected a path file, docs/viewer.md)");
  } catch (const PathJson::exception&) {
    throw Error(file, "", "a number too large for a path file (expected meters and seconds)");
  }
}

double number_in(const PathJson& j, const fs::path& file, const std::string& where, double lo, double hi,
                 const char* unit) {
  if (!j.is_number()) throw Error(file, where, std::string("expected a number of ") + unit);
  const double v = j.get<double>();
  if (!std::isfinite(v) || v < lo || v > hi)
    throw Error(
        file, where,
        "is " + number_text(v) + "; expected " + unit + " in " + fixed_text(lo, 0) + " .. " + fixed_text(hi, 0));
  return v;
}

// [E, N, H] (absolute height) or [E, N] with a height above the ground in `height_key`.
std::array<double, 3> read_point(const PathJson& key, const char* point_key, const char* height_key, bool above_ground,
                                 const fs::path& file, const std::string& where) {
  const std::string at = where + "." + point_key;
  if (!key.contains(point_key)) throw Error(file, where, std::string("expected \"") + point_key + "\"");
  const PathJson& j = key[point_key];
  const std::size_t size = above_ground ? 2 : 3;
  if (!j.is_array() || j.size() != size)
    throw Error(file, at,
                above_ground
                    ? std::string("expected [E, N] in meters (with \"") + height_key + "\" as in keyframe 0)"
                    : std::string("expected [E, N, H] in meters (no \"") + height_key + "\", as in keyframe 0)");
  std::array<double, 3> p{};
  for (std::size_t c = 0; c < 2; ++c)
    p[c] = number_in(j[c], file, at + "[" + std::to_string(c) + "]", -kMaxPathCoordinate, kMaxPathCoordinate, "meters");
  if (above_ground)
    p[2] = number_in(key[height_key], file, where + "." + height_key,
                     std::string_view(point_key) == "position" ? 0.0 : kMinPathHeight, kMaxPathHeight,
                     "meters above the ground");
  else
    p[2] = number_in(j[2], file, at + "[2]", kMinPathHeight, kMaxPathHeight, "meters");
  return p;
}

// Catmull-Rom through the keys (a smooth walk, no kinks at the keys).
std::array<double, 3> spline(const std::vector<PathKeyframe>& keys, double time, bool look) {
  std::size_t i = 0;
  while (i + 2 < keys.size() && time > keys[i + 1].time) ++i;
  const double f = std::clamp((time - keys[i].time) / (keys[i + 1].time - keys[i].time), 0.0, 1.0);
  auto at = [&](std::size_t k) { return look ? keys[k].look_at : keys[k].position; };
  const auto p1 = at(i), p2 = at(i + 1);
  if (p1 == p2) return p1;  // a still segment stays still (the neighbours' tangents would move it)
  const auto p0 = i > 0 ? at(i - 1) : p1, p3 = i + 2 < keys.size() ? at(i + 2) : p2;
  std::array<double, 3> out{};
  for (std::size_t c = 0; c < 3; ++c)
    out[c] = 0.5 * (2 * p1[c] + (p2[c] - p0[c]) * f + (2 * p0[c] - 5 * p1[c] + 4 * p2[c] - p3[c]) * f * f +
                    (3 * p1[c] - p0[c] - 3 * p2[c] + p3[c]) * f * f * f);
  return out;
}

}  // namespace

long long ViewPath::frame_count(double fps) const { return (long long)(std::floor(duration() * fps)) + 1; }

ViewPath parse_view_path(std::string_view text, const fs::path& file) {
  const PathJson doc = parse_json(text, file);
  const char* shape =
      "expected {\"keyframes\": [{\"time\": s, \"position\": [E, N, H], \"look_at\": [E, N, H]}, ...]} "
      "with at least two keyframes";
  if (!doc.is_object() || !doc.contains("keyframes") || !doc["keyframes"].is_array()) throw Error(file, "", shape);
  const PathJson& keys = doc["keyframes"];
  if (keys.size() < 2) throw Error(file, "keyframes", shape);
  if (keys.size() > kMaxPathKeyframes)
    throw Error(file, "keyframes",
                "holds " + std::to_string(keys.size()) + " keyframes; at most " + std::to_string(kMaxPathKeyframes) +
                    " are read (a keyframe every few seconds is enough: the spline is smooth between them)");
  ViewPath path;
  // Keyframe 0 says how heights are given; the others must say the same (one spline per channel).
  path.position_above_ground = keys[0].is_object() && keys[0].contains("height_above_ground");
  path.look_at_above_ground = keys[0].is_object() && keys[0].contains("look_at_height_above_ground");
  path.keys.reserve(keys.size());
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const PathJson& j = keys[k];
    const std::string where = "keyframes[" + std::to_string(k) + "]";
    if (!j.is_object() || !j.contains("time"))
      throw Error(file, where,
                  "expected {\"time\": seconds, \"position\": [E, N, H], \"look_at\": [E, N, H]} (or [E, N] with "
                  "\"height_above_ground\" / \"look_at_height_above_ground\")");
    if (j.contains("height_above_ground") != path.position_above_ground ||
        j.contains("look_at_height_above_ground") != path.look_at_above_ground)
      throw Error(file, where, "gives its heights another way than keyframe 0 (every keyframe the same way)");
    PathKeyframe key;
    key.time = number_in(j["time"], file, where + ".time", -kMaxPathSeconds * 1000, kMaxPathSeconds * 1000, "seconds");
    key.position = read_point(j, "position", "height_above_ground", path.position_above_ground, file, where);
    key.look_at = read_point(j, "look_at", "look_at_height_above_ground", path.look_at_above_ground, file, where);
    // The camera must see a horizon (camera_basis): the point looked at at least 1 mm sideways.
    if (!(std::hypot(key.look_at[0] - key.position[0], key.look_at[1] - key.position[1]) >= kMinPathLookSideways))
      throw Error(file, where + ".look_at",
                  "is straight above, below or at the position (E, N less than 1 mm apart); expected a point "
                  "sideways of the eye");
    if (!path.keys.empty() && !(key.time > path.keys.back().time))
      throw Error(file, where + ".time", "is " + number_text(key.time) + "; times must be ascending");
    path.keys.push_back(key);
  }
  if (path.duration() > kMaxPathSeconds)
    throw Error(file, "", "the path lasts " + number_text(path.duration()) + " s; at most an hour (3600 s)");
  return path;
}

ViewPath read_view_path(const fs::path& file) {
  return parse_view_path(read_text_file(file, kMaxPathFileBytes, "path file"), file);
}

std::string view_path_json(const ViewPath& path) {
  const auto point = [](const std::array<double, 3>& p, bool above) {
    // Appended, not "[" + string: GCC 12 warns (-Wrestrict) on that operator+ where it is inlined.
    std::string text = "[";
    text += number_text(p[0]);
    text += ", ";
    text += number_text(p[1]);
    if (!above) {
      text += ", ";
      text += number_text(p[2]);
    }
    text += "]";
    return text;
  };
  std::string out = "{\"keyframes\": [\n";
  for (std::size_t k = 0; k < path.keys.size(); ++k) {
    const PathKeyframe& key = path.keys[k];
    out +=
        "  {\"time\": " + number_text(key.time) + ", \"position\": " + point(key.position, path.position_above_ground);
    if (path.position_above_ground) out += ", \"height_above_ground\": " + number_text(key.position[2]);
    out += ", \"look_at\": " + point(key.look_at, path.look_at_above_ground);
    if (path.look_at_above_ground) out += ", \"look_at_height_above_ground\": " + number_text(key.look_at[2]);
    out += k + 1 < path.keys.size() ? "},\n" : "}\n";
  }
  return out + "]}\n";
}

Camera camera_along(const ViewPath& path, double time, double fov_degrees, const GroundHeightAt& ground,
                    const fs::path& file) {
  Camera camera{spline(path.keys, time, false), spline(path.keys, time, true), fov_degrees};
  const auto over_ground = [&](std::array<double, 3>& p, const char* what) {
    const std::optional<double> h = ground(p[0], p[1]);
    if (!h)
      throw Error(file, "",
                  std::string("at ") + fixed_text(time, 3) + " s the " + what + " (" + number_text(p[0]) + ", " +
                      number_text(p[1]) + ") is not over the ground, so a height above the ground has no meaning");
    p[2] += *h;
  };
  if (path.position_above_ground) over_ground(camera.position, "eye");
  if (path.look_at_above_ground) over_ground(camera.target, "look-at point");
  // Keyframes that look sideways can still meet between them, where the spline bends.
  if (!camera_basis(camera.position, camera.target))
    throw Error(file, "",
                "at " + fixed_text(time, 3) + " s the look-at point (" + number_text(camera.target[0]) + ", " +
                    number_text(camera.target[1]) + ") is straight above, below or at the eye (" +
                    number_text(camera.position[0]) + ", " + number_text(camera.position[1]) +
                    "); move the keyframes' look_at points sideways of their positions");
  return camera;
}

long long path_frame_count(const ViewPath& path, double fps, const fs::path& file, std::string_view rate) {
  const long long frames = path.frame_count(fps);
  if (frames > kMaxPathFrames)
    throw Error(file, "",
                "lasts " + number_text(path.duration()) + " s: " + std::to_string(frames) + " frames at " +
                    number_text(fps) + " frames/s; at most " + std::to_string(kMaxPathFrames) +
                    " are rendered (lower " + std::string(rate) + " or cut the path in parts)");
  return frames;
}

Camera camera_at_frame(const ViewPath& path, long long frame, double fps, double fov_degrees,
                       const GroundHeightAt& ground, const fs::path& file) {
  return camera_along(path, path.keys.front().time + double(frame) / fps, fov_degrees, ground, file);
}

std::string path_frame_name(long long frame) {
  std::string digits = std::to_string(frame);
  if (digits.size() < 5) digits.insert(0, 5 - digits.size(), '0');
  return "frame-" + digits + ".png";
}

}  // namespace wangscape
