// Parsing a batch file and expanding it into tasks (see batch_file.h, docs/batch-file.md).
#include "renders/batch/batch_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include "core/number_text.h"
#include "core/text_file.h"
#include "core/vecmath.h"
#include "scene/scene.h"
#include "scene/scene_ground.h"
#include "scene/sun.h"
#include "terrain/georef.h"

namespace wangscape {

extern const char* const kExampleBatchToml;  // generated from templates/batches/example.toml

namespace {

int line_of(const toml::node& node) { return static_cast<int>(node.source().begin.line); }

// Reads one TOML table; finish() fails on the keys nothing read (naming the file and the line).
class Table {
 public:
  Table(const toml::table& table, const std::filesystem::path& file, std::string name)
      : table_(table), file_(file), name_(std::move(name)) {}
  void finish() const {
    for (const auto& [key, node] : table_)
      if (!used_.count(std::string(key.str())))
        throw Error(file_, std::to_string(line_of(node)), "unknown key '" + name_ + std::string(key.str()) + "'");
  }
  const toml::node* node(const std::string& key) {
    used_.insert(key);
    return table_.get(key);
  }
  [[noreturn]] void fail(const toml::node& node, const std::string& key, const std::string& what) const {
    throw Error(file_, std::to_string(line_of(node)), "'" + name_ + key + "' " + what);
  }
  double number(const std::string& key, double fallback) {
    const auto* n = node(key);
    if (!n) return fallback;
    if (auto v = n->value<double>(); v && std::isfinite(*v)) return *v;
    fail(*n, key, "must be a finite number");
  }
  // A number in [lo, hi] (units in `unit`), or the fallback when the key is absent.
  double number(const std::string& key, double fallback, double lo, double hi, const std::string& unit) {
    const double v = number(key, fallback);
    if (node(key) && !(v >= lo && v <= hi))
      fail(*node(key), key,
           "is " + number_text(v) + "; expected " + unit + " from " + number_text(lo) + " to " + number_text(hi));
    return v;
  }
  int integer(const std::string& key, int fallback, int min, int max) {
    const auto* n = node(key);
    if (!n) return fallback;
    const auto v = n->value_exact<std::int64_t>();
    if (!v || *v < min || *v > max)
      fail(*n, key, "must be an integer from " + std::to_string(min) + " to " + std::to_string(max));
    return static_cast<int>(*v);
  }
  std::vector<std::string> strings(const std::string& key) {
    std::vector<std::string> out;
    const auto* n = node(key);
    if (!n) return out;
    const auto* array = n->as_array();
    if (!array) fail(*n, key, "must be a list of strings");
    for (const auto& item : *array) {
      const auto v = item.value<std::string>();
      if (!v) fail(item, key, "must be a list of strings");
      out.push_back(*v);
    }
    return out;
  }
  std::vector<std::array<double, 2>> pairs(const std::string& key) {
    std::vector<std::array<double, 2>> out;
    const auto* n = node(key);
    if (!n) return out;
    const auto* array = n->as_array();
    if (!array) fail(*n, key, "must be a list of [a, b] number pairs");
    for (const auto& item : *array) {
      const auto* pair = item.as_array();
      const auto a = pair && pair->size() == 2 ? (*pair)[0].value<double>() : std::nullopt;
      const auto b = pair && pair->size() == 2 ? (*pair)[1].value<double>() : std::nullopt;
      if (!a || !b) fail(item, key, "must be a list of [a, b] number pairs");
      if (!std::isfinite(*a) || !std::isfinite(*b)) fail(item, key, "must hold finite numbers");
      out.push_back({*a, *b});
    }
    return out;
  }
  const std::filesystem::path& file() const { return file_; }

 private:
  const toml::table& table_;
  std::filesystem::path file_;
  std::string name_;
  std::set<std::string> used_;
};

std::int64_t unix_seconds(const toml::node& node, Table& sun, const std::string& key) {
  const auto* dt = node.as_date_time();
  if (!dt || !dt->get().offset)
    sun.fail(node, key, "must be TOML date-times with a UTC offset, e.g. 2024-07-15T09:00:00-07:00");
  const auto& v = dt->get();
  return unix_seconds_utc(v.date.year, v.date.month, v.date.day, v.time.hour, v.time.minute, v.time.second,
                          v.offset->minutes);
}

// A date-time as written (its TOML form), for labels.
std::string text_of(const toml::node& node) {
  std::ostringstream out;
  if (const auto* dt = node.as_date_time()) out << dt->get();
  return out.str();
}

// "2024-07-15T11:00:00-07:00": a moment as local time at a UTC offset (labels of from-to-step suns).
std::string local_time_text(std::int64_t unix, int offset_minutes) {
  using namespace std::chrono;
  const sys_seconds local{seconds{unix + std::int64_t{offset_minutes} * 60}};
  const auto day = floor<days>(local);
  const year_month_day ymd{day};
  const hh_mm_ss hms{local - day};
  toml::date_time dt{};  // value-initialized: no stray nanoseconds
  dt.date.year = static_cast<std::uint16_t>(static_cast<int>(ymd.year()));
  dt.date.month = static_cast<std::uint8_t>(static_cast<unsigned>(ymd.month()));
  dt.date.day = static_cast<std::uint8_t>(static_cast<unsigned>(ymd.day()));
  dt.time.hour = static_cast<std::uint8_t>(hms.hours().count());
  dt.time.minute = static_cast<std::uint8_t>(hms.minutes().count());
  dt.time.second = static_cast<std::uint8_t>(hms.seconds().count());
  dt.offset = toml::time_offset{};
  dt.offset->minutes = static_cast<std::int16_t>(offset_minutes);
  std::ostringstream out;
  out << dt;
  return out.str();
}

void read_suns(Table& sun, BatchConfig& config) {
  if (const auto* n = sun.node("times")) {
    const auto* array = n->as_array();
    if (!array) sun.fail(*n, "times", "must be a list of date-times");
    for (const auto& item : *array) config.suns.push_back({unix_seconds(item, sun, "times"), text_of(item)});
  }
  const auto* from = sun.node("from");
  const auto* to = sun.node("to");
  if ((from != nullptr) != (to != nullptr))
    sun.fail(from ? *from : *to, from ? "from" : "to", "needs both from and to");
  if (from) {
    // Bounded above too: a step of 1e18 minutes overflowed the seconds of the second sun, which
    // then came before 'to' again and again until memory ran out.
    const double step = sun.number("step_minutes", 60, 1, kMaxSunStepMinutes, "minutes");
    const auto t0 = unix_seconds(*from, sun, "from"), t1 = unix_seconds(*to, sun, "to");
    if (t1 < t0) sun.fail(*to, "to", "is before 'from'");
    const int offset = from->as_date_time()->get().offset->minutes;
    const double count = std::floor(static_cast<double>(t1 - t0) / (step * 60)) + 1;
    if (count > kMaxBatchSuns)
      sun.fail(*from, "from",
               "to 'to' every " + number_text(step) + " minutes is " + number_text(count) + " suns; at most " +
                   std::to_string(kMaxBatchSuns) + " are planned: raise step_minutes or shorten the span");
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(count); ++k) {
      const std::int64_t t = t0 + static_cast<std::int64_t>(static_cast<double>(k) * step * 60);
      if (t > t1) break;
      config.suns.push_back({t, local_time_text(t, offset)});
    }
  }
  const auto* angles = sun.node("angles");
  for (const auto& [az, el] : sun.pairs("angles")) {
    if (!(el > 0 && el <= 90))
      sun.fail(*angles, "angles", "elevation " + number_text(el) + ": expected degrees in (0, 90]");
    BatchSun s;
    s.azimuth = az;  // any finite value; the label gives it in [0, 360)
    const double compass = std::fmod(std::fmod(az, 360.0) + 360.0, 360.0);
    s.elevation = el;
    s.label = "az " + std::to_string(static_cast<int>(std::lround(compass))) + " el " +
              std::to_string(static_cast<int>(std::lround(el)));
    config.suns.push_back(s);
  }
}

ViewpointRule read_viewpoint(Table& v, int line) {
  ViewpointRule rule;
  rule.line = line;
  if (const auto* n = v.node("kind")) {
    const auto kind = find_viewpoint_kind(n->value_or(std::string()));
    if (!kind) v.fail(*n, "kind", "must be flowers, summits, grid or path");
    rule.kind = *kind;
  }
  rule.count = v.integer("count", rule.count, 1, 10000);
  rule.eye_height = v.number("eye_height", rule.eye_height, 0, kMaxEyeHeight, "meters above the ground");
  rule.min_height = v.number("min_height", rule.min_height, -kMaxGroundHeight, kMaxGroundHeight, "meters");
  rule.fov = v.number("fov", 0);
  if (const auto* n = v.node("fov"); n && !valid_field_of_view(rule.fov))
    v.fail(*n, "fov",
           "is " + number_text(rule.fov) + "; expected degrees in (0, " + number_text(kMaxFieldOfViewDegrees) + "]");
  if (const auto* n = v.node("grid")) {
    const auto* a = n->as_array();
    const auto c = a && a->size() == 2 ? (*a)[0].value_exact<std::int64_t>() : std::nullopt;
    const auto r = a && a->size() == 2 ? (*a)[1].value_exact<std::int64_t>() : std::nullopt;
    if (!c || !r || *c < 1 || *r < 1 || *c > 10000 || *r > 10000 || *c * *r > 10000)
      v.fail(*n, "grid", "must be [columns, rows], each >= 1");
    rule.grid = {static_cast<int>(*c), static_cast<int>(*r)};
  }
  rule.path_enu = v.pairs("enu");
  rule.path_latlon = v.pairs("latlon");
  if (rule.kind == ViewpointKind::path && rule.path_enu.size() + rule.path_latlon.size() < 2)
    throw Error(v.file(), std::to_string(line), "a path viewpoint needs 'enu' or 'latlon' with at least 2 points");
  return rule;
}

// One [[paths]] table: the path file read now, so that a bad file fails before anything runs.
BatchPath read_path(Table& p, int line, const std::filesystem::path& base_dir) {
  BatchPath path;
  path.line = line;
  const auto* file = p.node("file");
  const auto name = file ? file->value<std::string>() : std::nullopt;
  if (!name || name->empty())
    throw Error(p.file(), std::to_string(line), "[[paths]] needs 'file', the path file (the view's, docs/viewer.md)");
  std::error_code ignored;  // absolute: Slurm's workers run in the output folder
  path.file = std::filesystem::absolute(base_dir / *name, ignored);
  path.fps = p.number("fps", path.fps, kMinBatchPathFps, kMaxBatchPathFps, "frames a second");
  path.frames_per_task = p.integer("frames_per_task", path.frames_per_task, 1, 100000);
  try {
    path.path = read_view_path(path.file);
    path.frames = path_frame_count(path.path, path.fps, path.file, "'paths.fps'");
  } catch (const Error& e) {
    throw Error(p.file(), std::to_string(line), "[[paths]] file: " + std::string(e.what()));
  }
  return path;
}

// ---- numbers and hashes -------------------------------------------------------------------------

// What the scene folder depends on: the scene text, the DEM and its size and time.
std::string scene_key(const SceneConfig& scene, const std::filesystem::path& dem) {
  std::string key = std::string("wangscape ") + scene.text + "\n" + scene.source.string() + "\n" + dem.string();
  std::error_code ec;
  if (!dem.empty()) {
    key += " " + std::to_string(std::filesystem::file_size(dem, ec));
    key += " " + std::to_string(std::filesystem::last_write_time(dem, ec).time_since_epoch().count());
  }
  return hash_hex(key);
}

// ---- viewpoints ---------------------------------------------------------------------------------

// A head-height eye among plants is moved to the nearest place clear of them within this many
// meters (on rings kClearStep apart), or else lifted above them. Clear: this far beyond any plant's
// reach, and farther from the plants in front (within the field of view): at 0.1 m beyond one a
// leaf in front still filled a third of a 60-degree still.
constexpr double kClearSearch = 5.0, kClearStep = 0.25, kClearLift = 0.3;
constexpr double kClearMargin = 0.1, kClearFrontMargin = 0.6;

// The plants of a ground as a viewpoint meets them: the scene's field laid without a camera's view
// (every tile, camera-aware or not) and each model's reach and height.
struct Plants {
  std::shared_ptr<SceneField> field;
  std::vector<MeshExtent> extents;  // per model (InstanceBatch::variant)

  // The scene over `ground` with a camera 100 m above `at` (the base scene's own camera may not fit
  // this DEM; tasks get their own).
  Plants(const SceneConfig& base, const SceneGround& ground, const std::array<double, 2>& at) {
    SceneConfig scene = base;
    const double up = ground.height(at[0], at[1]).value_or(0) + 100;
    scene.camera = {};
    scene.camera.position.enu = {at[0], at[1], up};
    scene.camera.target.enu = {at[0] + 10, at[1], up};
    scene.ground.reset();  // the plants alone: no ground bake, no far field painted into it
    scene.camera_aware.far_texture = false;
    const Scene made = make_scene(scene);
    field = std::make_shared<SceneField>(*made.field);
    field->view.reset();
    for (const Mesh& model : made.models) extents.push_back(measure_extent(model));
  }
  // The plants whose tiles meet the square of half side `reach` around (x, y): where each stands,
  // how far its leaves reach and how high it grows.
  struct Plant {
    double x, y, reach, top;
  };
  std::vector<Plant> around(double x, double y, double reach) const {
    std::vector<Plant> plants;
    field->place_in(Extent{x - reach, y - reach, x + reach, y + reach}, [&](const InstanceBatch& batch) {
      for (std::size_t i = 0; i < batch.size(); ++i) {
        const MeshExtent& e = extents[std::min<std::size_t>(batch.variant[i], extents.size() - 1)];
        plants.push_back({batch.x[i], batch.y[i], e.radius * batch.scale[i], batch.z[i] + e.height * batch.scale[i]});
      }
    });
    return plants;
  }
};

// The ground of one DEM with what viewpoints need of it.
struct Site {
  const SceneConfig& scene;
  const SceneGround& ground;
  Extent field;
  mutable std::optional<Plants> plants;  // made on the first head-height eye

  // Flowers may grow here: inside the field, over the ground, within the height/slope masks.
  bool has_flowers(double x, double y) const {
    if (!field.contains(x, y)) return false;
    const auto h = ground.height(x, y);
    if (!h) return false;
    const auto& m = scene.masks;
    if ((m.max_height && *h > *m.max_height) || (m.min_height && *h < *m.min_height)) return false;
    const auto slope = ground.slope_degrees(x, y);
    return !m.max_slope || (slope && *slope <= *m.max_slope);
  }
  // Samples of the ground on a regular n x n grid (x, y, height), off-ground ones dropped.
  std::vector<std::array<double, 3>> samples(int n) const {
    std::vector<std::array<double, 3>> out;
    const Extent e = ground.extent();
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = e.min_x + (i + 0.5) * e.width() / n, y = e.min_y + (j + 0.5) * e.height() / n;
        if (const auto h = ground.height(x, y)) out.push_back({x, y, *h});
      }
    return out;
  }
  // True when the straight line from `eye` to `p` stays above the ground, tested at 24 points, or
  // every `step` meters when that is finer (a summit's own shoulder lies within the first of 24).
  bool visible(const std::array<double, 3>& eye, const std::array<double, 3>& p, double step = 0) const {
    const double length = std::hypot(p[0] - eye[0], p[1] - eye[1]);
    const int steps = step > 0 ? std::clamp(static_cast<int>(std::ceil(length / step)), 24, 100000) : 24;
    for (int s = 1; s < steps; ++s) {
      const double t = static_cast<double>(s) / steps;
      const double x = eye[0] + (p[0] - eye[0]) * t, y = eye[1] + (p[1] - eye[1]) * t;
      const auto h = ground.height(x, y);
      if (h && *h > eye[2] + (p[2] - eye[2]) * t + 0.01) return false;
    }
    return true;
  }
  // The highest ground point visible from `eye` (ties: the one nearest the field's center).
  std::array<double, 3> highest_in_view(const std::array<double, 3>& eye) const {
    const double cx = (field.min_x + field.max_x) / 2, cy = (field.min_y + field.max_y) / 2;
    std::optional<std::array<double, 3>> best;
    double best_center = 0;
    for (const auto& p : samples(48)) {
      if (std::hypot(p[0] - eye[0], p[1] - eye[1]) < 5.0 || !visible(eye, p)) continue;
      const double center = std::hypot(p[0] - cx, p[1] - cy);
      if (!best || p[2] > (*best)[2] + 1e-9 || (std::abs(p[2] - (*best)[2]) <= 1e-9 && center < best_center)) {
        best = p;
        best_center = center;
      }
    }
    if (!best) return {cx, cy, ground.height(cx, cy).value_or(eye[2] - 1.0)};
    return *best;
  }
  std::array<double, 3> eye_at(double x, double y, double eye_height) const {
    return {x, y, ground.height(x, y).value_or(0) + eye_height};
  }
  // An eye eye_height above the ground at (x, y) looking toward `toward` (ENU) with a horizontal
  // field of view of fov_degrees, out of the plants: there when no plant's reach (its widest leaf,
  // scaled) plus a margin holds it below that plant's top, else the nearest clear place within
  // kClearSearch, else kClearLift above the tops around it. A head-height still taken from inside
  // a sunflower had a leaf filling a corner (issue 40).
  std::array<double, 3> clear_eye_at(double x, double y, double eye_height, const std::array<double, 3>& toward,
                                     double fov_degrees) const {
    if (!plants) plants.emplace(scene, ground, std::array<double, 2>{x, y});
    double reach = 0;
    for (const MeshExtent& e : plants->extents) reach = std::max<double>(reach, e.radius);
    const auto around = plants->around(x, y, kClearSearch + 2 * reach + kClearFrontMargin);
    const double ahead = std::atan2(toward[1] - y, toward[0] - x);
    const double half_view = (fov_degrees / 2 + 10) * std::numbers::pi / 180;  // with a leaf's width to spare
    const auto inside = [&](const std::array<double, 3>& eye) {
      return std::any_of(around.begin(), around.end(), [&](const Plants::Plant& p) {
        const double dx = p.x - eye[0], dy = p.y - eye[1];
        const double off = std::abs(std::remainder(std::atan2(dy, dx) - ahead, 2 * std::numbers::pi));
        return eye[2] < p.top && std::hypot(dx, dy) < p.reach + (off < half_view ? kClearFrontMargin : kClearMargin);
      });
    };
    if (const auto eye = eye_at(x, y, eye_height); !inside(eye)) return eye;
    for (double r = kClearStep; r <= kClearSearch + 1e-9; r += kClearStep) {
      const int steps = std::max(8, static_cast<int>(std::ceil(2 * std::numbers::pi * r / kClearStep)));
      for (int k = 0; k < steps; ++k) {
        const double a = 2 * std::numbers::pi * k / steps, px = x + r * std::cos(a), py = y + r * std::sin(a);
        if (!ground.height(px, py)) continue;
        if (const auto eye = eye_at(px, py, eye_height); !inside(eye)) return eye;
      }
    }
    auto eye = eye_at(x, y, eye_height);
    for (const Plants::Plant& p : around)
      if (std::hypot(x - p.x, y - p.y) < p.reach) eye[2] = std::max(eye[2], p.top + kClearLift);
    return eye;
  }
};

double halton(int index, int base) {
  double f = 1, r = 0;
  for (int i = index; i > 0; i /= base) {
    f /= base;
    r += f * (i % base);
  }
  return r;
}

struct View {
  std::string name;
  Camera camera;
};

std::vector<View> expand_viewpoint(const ViewpointRule& rule, const Site& site, const std::filesystem::path& file) {
  std::vector<View> views;
  auto add = [&](const std::string& name, const std::array<double, 3>& eye, const std::array<double, 3>& target) {
    View v{name, {}};
    v.camera.position = eye;
    v.camera.target = target;
    v.camera.fov_degrees = rule.fov > 0 ? rule.fov : site.scene.camera.fov;
    views.push_back(v);
  };
  const double fov = rule.fov > 0 ? rule.fov : site.scene.camera.fov;
  // A head-height eye at (x, y), out of the plants, looking toward the highest ground it sees
  // (looked for again only when the eye had to move).
  const auto add_toward_highest = [&](const std::string& name, double x, double y) {
    const auto at = site.eye_at(x, y, rule.eye_height);
    const auto toward = site.highest_in_view(at);
    const auto eye = site.clear_eye_at(x, y, rule.eye_height, toward, fov);
    add(name, eye, eye == at ? toward : site.highest_in_view(eye));
  };
  const Extent& f = site.field;
  if (rule.kind == ViewpointKind::flowers) {
    for (int k = 1; k < 20000 && static_cast<int>(views.size()) < rule.count; ++k) {
      const double x = f.min_x + halton(k, 2) * f.width(), y = f.min_y + halton(k, 3) * f.height();
      if (!site.has_flowers(x, y)) continue;
      add_toward_highest("flowers " + std::to_string(views.size() + 1), x, y);
    }
  } else if (rule.kind == ViewpointKind::summits) {
    const int n = 48;
    const auto s = site.samples(n);
    std::vector<std::array<double, 3>> peaks;
    for (const auto& p : s) {
      if (p[2] < rule.min_height) continue;
      bool top = true;
      const Extent e = site.ground.extent();
      const double dx = e.width() / n, dy = e.height() / n;
      for (int j = -1; j <= 1 && top; ++j)
        for (int i = -1; i <= 1 && top; ++i)
          if (i || j) top = site.ground.height(p[0] + i * dx, p[1] + j * dy).value_or(-1e300) < p[2];
      if (top) peaks.push_back(p);
    }
    std::stable_sort(peaks.begin(), peaks.end(), [](const auto& a, const auto& b) { return a[2] > b[2]; });
    const std::array<double, 3> center = site.eye_at((f.min_x + f.max_x) / 2, (f.min_y + f.max_y) / 2, 0);
    // A summit whose own shoulder hides the field's centre gave a still of near ground and sky
    // (issue 40): only summits that see it (at the flowers' height, 1 m) look at it.
    const std::array<double, 3> flowers{center[0], center[1], center[2] + 1.0};
    for (const auto& p : peaks) {
      if (static_cast<int>(views.size()) >= rule.count) break;
      const std::array<double, 3> eye{p[0], p[1], p[2] + rule.eye_height};
      if (site.visible(eye, flowers, 5.0)) add("summit " + std::to_string(views.size() + 1), eye, center);
    }
  } else if (rule.kind == ViewpointKind::grid) {
    for (int j = 0; j < rule.grid[1]; ++j)
      for (int i = 0; i < rule.grid[0]; ++i) {
        const double x = f.min_x + (i + 0.5) * f.width() / rule.grid[0];
        const double y = f.min_y + (j + 0.5) * f.height() / rule.grid[1];
        if (!site.ground.height(x, y)) continue;
        add_toward_highest("grid " + std::to_string(i) + "," + std::to_string(j), x, y);
      }
  } else {
    auto points = rule.path_enu;
    for (const auto& [lat, lon] : rule.path_latlon) points.push_back(site.ground.to_enu(lat, lon));
    for (std::size_t k = 0; k < points.size(); ++k) {
      const auto& [x, y] = points[k];
      if (!site.ground.height(x, y))
        throw Error(file, std::to_string(rule.line),
                    "path point " + std::to_string(k + 1) + " (east " + number_text(x) + " m, north " + number_text(y) +
                        " m) is not over the ground (" + site.ground.description() + ")");
      // Look along the path: towards the next point, the last one onwards from the one before.
      const auto& a = points[k + 1 < points.size() ? k : k - 1];
      const auto& b = points[k + 1 < points.size() ? k + 1 : k];
      if (std::hypot(b[0] - a[0], b[1] - a[1]) < 1e-3)
        throw Error(file, std::to_string(rule.line),
                    "path points " + std::to_string(k + 1 < points.size() ? k + 1 : k) + " and " +
                        std::to_string(k + 1 < points.size() ? k + 2 : k + 1) +
                        " are the same place (less than 1 mm apart), so the camera there has no direction; " +
                        "give points that move along the path");
      const auto eye = site.clear_eye_at(x, y, rule.eye_height, {x + b[0] - a[0], y + b[1] - a[1], 0}, fov);
      add("path " + std::to_string(k + 1), eye, {eye[0] + b[0] - a[0], eye[1] + b[1] - a[1], eye[2]});
    }
  }
  if (views.empty())
    throw Error(file, std::to_string(rule.line),
                "no " + std::string(to_string(rule.kind)) + " viewpoint fits the ground " + site.ground.description());
  return views;
}

// `name` as a folder name: letters, digits, '-' and '_' kept, anything else '_'.
std::string safe_name(const std::string& name) {
  std::string out;
  for (const char c : name) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
  return out.empty() ? "path" : out;
}

// The tasks of one [[paths]] entry (the `number`th) over one ground: each engine's frames in parts
// of frames_per_task, each part's camera its first frame's, its frames folder shared by the parts.
template <class AddTask>
void add_path_tasks(const BatchPath& path, int number, const std::string& dem_name, const BatchConfig& config,
                    const SceneGround& ground, const BatchSun& sun, const AddTask& add_task) {
  const GroundHeightAt height = [&](double e, double n) { return ground.height(e, n); };
  const std::string stem = safe_name(path.file.stem().string());
  const std::string canonical = view_path_json(path.path);  // what the frames depend on, not the file's spacing
  for (const RenderEngine engine : config.engines) {
    const std::string folder = std::to_string(number) + "-" + stem +
                               (dem_name.empty() ? "" : "-" + safe_name(dem_name)) + "-" +
                               std::string(to_string(engine));
    for (long long first = 0; first < path.frames; first += path.frames_per_task) {
      const long long count = std::min<long long>(path.frames_per_task, path.frames - first);
      const Camera camera = camera_at_frame(path.path, first, path.fps, config.scene.camera.fov, height, path.file);
      BatchTask& t =
          add_task("path " + stem + " frames " + std::to_string(first) + "-" + std::to_string(first + count - 1),
                   camera, sun, engine);
      t.frames = BatchFrames{path.file, path.fps, first, count, path.frames, folder};
      t.input_hash = hash_hex(t.input_hash + ' ' + canonical + ' ' + number_text(path.fps) + ' ' +
                              std::to_string(first) + ' ' + std::to_string(count));
    }
  }
}

// The tasks a batch will make, counted from the file before any ground is loaded: the viewpoints
// a rule asks for (fewer may fit the ground) times the suns, engines and DEMs.
double planned_tasks(const BatchConfig& config, double* viewpoints = nullptr) {
  double views = 0;
  for (const auto& rule : config.viewpoints)
    views += rule.kind == ViewpointKind::grid   ? double(rule.grid[0]) * rule.grid[1]
             : rule.kind == ViewpointKind::path ? double(rule.path_enu.size() + rule.path_latlon.size())
                                                : double(rule.count);
  if (viewpoints) *viewpoints = views;
  double parts = 0;  // a path's tasks take the scene's sun alone
  for (const auto& path : config.paths) parts += std::ceil(double(path.frames) / double(path.frames_per_task));
  return (views * double(std::max<std::size_t>(config.suns.size(), 1)) + parts) * double(config.engines.size()) *
         double(std::max<std::size_t>(config.dems.size(), 1));
}

void check_batch_size(const BatchConfig& config) {
  double views = 0;
  const double tasks = planned_tasks(config, &views);
  if (tasks <= kMaxBatchTasks) return;
  throw Error(config.source, "",
              "the batch asks for up to " + fixed_text(tasks, 0) + " stills (" +
                  std::to_string(std::max<std::size_t>(config.dems.size(), 1)) + " DEMs x " + fixed_text(views, 0) +
                  " viewpoints x " + std::to_string(std::max<std::size_t>(config.suns.size(), 1)) + " suns x " +
                  std::to_string(config.engines.size()) + " engines, and the paths' parts); at most " +
                  std::to_string(kMaxBatchTasks) +
                  " are planned: split it into several batch files, each with its own --out");
}

}  // namespace

std::string batch_task_id(int index) {
  std::string s = std::to_string(index);
  return std::string(s.size() < 4 ? 4 - s.size() : 0, '0') + s;
}

std::string hash_hex(std::string_view text) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  static const char* digits = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i, h >>= 4) out[i] = digits[h & 15];
  return out;
}

BatchConfig parse_batch_config(std::string_view toml_text, const std::filesystem::path& source,
                               const std::filesystem::path& base_dir) {
  check_nesting(toml_text, source, kMaxNesting);  // toml++ recurses: refuse deep input first
  toml::table root;
  try {
    root = toml::parse(toml_text, source.string());
  } catch (const toml::parse_error& e) {
    throw Error(source, std::to_string(e.source().begin.line), std::string(e.description()));
  }
  BatchConfig config;
  config.source = source;
  Table top(root, source, "");
  const auto resolve = [&](const std::string& p) {
    return std::filesystem::path(p).is_absolute() ? std::filesystem::path(p) : base_dir / p;
  };
  const auto* scene = top.node("scene");
  if (!scene || !scene->is_string())
    throw Error(source, scene ? std::to_string(line_of(*scene)) : "",
                "'scene' must name the base scene file (or \"default\" for the embedded one)");
  const std::string scene_name = scene->value_or(std::string());
  config.scene = scene_name == "default" ? default_scene_config() : load_scene_config(resolve(scene_name));
  for (const auto& dem : top.strings("dems")) config.dems.push_back(resolve(dem));
  if (const auto* dems = root.get("dems")) config.dems_line = line_of(*dems);
  if (const auto* folder = top.node("dem_folder")) {
    const auto dir = resolve(folder->value_or(std::string()));
    std::error_code ec;
    std::vector<std::filesystem::path> found;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
      const auto ext = entry.path().extension().string();
      if (ext == ".dem" || ext == ".tif" || ext == ".asc" || ext == ".DEM") found.push_back(entry.path());
    }
    if (ec || found.empty())
      top.fail(*folder, "dem_folder", "'" + dir.string() + "' has no DEM (.dem, .tif, .asc) or cannot be read");
    std::sort(found.begin(), found.end());
    config.dems.insert(config.dems.end(), found.begin(), found.end());
  }
  if (const auto* n = top.node("engines")) {
    config.engines.clear();
    for (const auto& name : top.strings("engines")) {
      const auto e = find_render_engine(name);
      if (!e)
        top.fail(*n, "engines", "'" + name + "' is not an engine of this wangscape (known: povray, blender, embree)");
      config.engines.push_back(*e);
    }
    if (config.engines.empty()) top.fail(*n, "engines", "must name at least one engine");
  }
  config.width = top.integer("width", 0, 1, 32768);
  config.height = top.integer("height", 0, 1, 32768);
  if (const auto* n = top.node("viewpoints")) {
    const auto* array = n->as_array();
    if (!array || !array->is_array_of_tables()) top.fail(*n, "viewpoints", "must be [[viewpoints]] tables");
    for (const auto& item : *array) {
      Table v(*item.as_table(), source, "viewpoints.");
      config.viewpoints.push_back(read_viewpoint(v, line_of(item)));
      v.finish();
    }
  }
  if (const auto* n = top.node("paths")) {
    const auto* array = n->as_array();
    if (!array || !array->is_array_of_tables()) top.fail(*n, "paths", "must be [[paths]] tables");
    for (const auto& item : *array) {
      Table p(*item.as_table(), source, "paths.");
      config.paths.push_back(read_path(p, line_of(item), base_dir));
      p.finish();
    }
  }
  if (const auto* n = top.node("sun")) {
    if (!n->as_table()) top.fail(*n, "sun", "must be a [sun] table");
    Table sun(*n->as_table(), source, "sun.");
    read_suns(sun, config);
    sun.finish();
  }
  top.finish();
  if (config.viewpoints.empty()) config.viewpoints.push_back({});
  return config;
}

BatchConfig load_batch_config(const std::filesystem::path& file) {
  return parse_batch_config(read_text_file(file, kMaxBatchFileBytes, "batch file"), file, file.parent_path());
}

std::string_view example_batch_text() { return kExampleBatchToml; }

SceneConfig task_scene_config(const SceneConfig& base, const BatchTask& task) {
  SceneConfig scene = base;
  if (!task.dem.empty()) scene.terrain.dem = task.dem;
  scene.camera = {};
  scene.camera.position.enu = task.camera.position;
  scene.camera.target.enu = task.camera.target;
  scene.camera.fov = task.camera.fov_degrees;
  scene.sun.time_unix.reset();
  scene.sun.azimuth = task.sun.azimuth;
  scene.sun.elevation = task.sun.elevation;
  scene.image.width = task.width;
  scene.image.height = task.height;
  scene.image.threads = 1;  // parallelism comes from running tasks side by side
  return scene;
}

std::vector<BatchTask> expand_batch(const BatchConfig& config) {
  check_batch_size(config);
  // Every DEM is checked before anything is loaded, so a typo fails at once.
  for (const auto& dem : config.dems)
    if (!std::filesystem::is_regular_file(dem))
      throw Error(config.source, config.dems_line ? std::to_string(config.dems_line) : "",
                  "DEM '" + dem.string() + "' does not exist (or is not a file)");
  std::vector<std::filesystem::path> dems = config.dems;
  if (dems.empty()) dems.push_back(config.scene.terrain.dem);
  std::vector<BatchTask> tasks;
  for (const auto& dem : dems) {
    SceneConfig scene = config.scene;
    scene.terrain.dem = dem;
    const auto ground = SceneGround::load(scene.terrain, scene.masks, scene.tiles.area_latlon);
    Site site{scene, ground, field_area(scene, ground), {}};
    const EnuFrame frame(LatLon{ground.origin()[0], ground.origin()[1]});
    // A sun given by its time takes its angles at the ground's origin.
    const auto placed = [&](BatchSun s) {
      if (!s.time_unix) return s;
      const auto p = solar_position(ground.origin()[0], ground.origin()[1], *s.time_unix);
      if (p.elevation_degrees <= 0)
        throw Error(config.source, "", "sun time " + s.label + " is night at the origin of " + ground.description());
      s.azimuth = p.azimuth_degrees;
      s.elevation = p.elevation_degrees;
      return s;
    };
    // The scene's own sun (a path's frames take it alone), and the batch's suns (default: it).
    BatchSun scene_sun;
    scene_sun.time_unix = config.scene.sun.time_unix;
    scene_sun.azimuth = config.scene.sun.azimuth;
    scene_sun.elevation = config.scene.sun.elevation;
    scene_sun.label = scene_sun.time_unix ? config.scene.sun.time_text : "the scene's sun";
    const BatchSun own = placed(scene_sun);
    std::vector<BatchSun> suns;
    for (const BatchSun& s : config.suns) suns.push_back(placed(s));
    if (suns.empty()) suns.push_back(own);
    const std::string key = scene_key(scene, dem);
    const auto add_task = [&](const std::string& viewpoint, const Camera& camera, const BatchSun& sun,
                              RenderEngine engine) -> BatchTask& {
      BatchTask t;
      t.index = static_cast<int>(tasks.size());
      t.id = batch_task_id(t.index);
      t.dem = dem;
      t.scene_key = key;
      t.viewpoint = viewpoint;
      t.camera = camera;
      const auto ll = frame.to_lat_lon(camera.position[0], camera.position[1]);
      t.camera_latlon = {ll.lat, ll.lon};
      t.sun = sun;
      t.engine = engine;
      t.width = config.width ? config.width : config.scene.image.width;
      t.height = config.height ? config.height : config.scene.image.height;
      // The input hash: the scene, then every number of the still, shortest round-trip form.
      std::string h =
          key + ' ' + std::string(to_string(engine)) + ' ' + std::to_string(t.width) + 'x' + std::to_string(t.height);
      const auto& c = camera;
      for (double v : {c.position[0], c.position[1], c.position[2], c.target[0], c.target[1], c.target[2],
                       c.fov_degrees, sun.azimuth, sun.elevation, config.scene.sun.strength}) {
        h += ' ';
        h += number_text(v);
      }
      t.input_hash = hash_hex(h);
      tasks.push_back(t);
      return tasks.back();
    };
    for (const auto& rule : config.viewpoints)
      for (const auto& view : expand_viewpoint(rule, site, config.source))
        for (const auto& sun : suns)
          for (const auto& engine : config.engines) add_task(view.name, view.camera, sun, engine);
    for (std::size_t k = 0; k < config.paths.size(); ++k)
      add_path_tasks(config.paths[k], int(k) + 1, dems.size() > 1 ? dem.stem().string() : "", config, ground, own,
                     add_task);
  }
  return tasks;
}

std::string_view to_string(ViewpointKind kind) {
  switch (kind) {
    case ViewpointKind::flowers:
      return "flowers";
    case ViewpointKind::summits:
      return "summits";
    case ViewpointKind::grid:
      return "grid";
    case ViewpointKind::path:
      return "path";
  }
  return "?";
}

std::optional<ViewpointKind> find_viewpoint_kind(std::string_view name) {
  for (const ViewpointKind k :
       {ViewpointKind::flowers, ViewpointKind::summits, ViewpointKind::grid, ViewpointKind::path})
    if (name == to_string(k)) return k;
  return std::nullopt;
}

}  // namespace wangscape
