// A batch's output folder (renders/batch/batch_folder.h): plan.json, the tasks' records and states.
#include "renders/batch/batch_folder.h"

#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/json_text.h"
#include "core/printable.h"
#include "core/text_file.h"
#include "core/vecmath.h"

namespace wangscape {

namespace fs = std::filesystem;

namespace batch_detail {

namespace {

// ---- plan.json ----------------------------------------------------------------------------------

// A path of the plan: its text under `key` (U+FFFD where it is not UTF-8, as JSON output writes
// it) and, when it is not UTF-8 (a DEM folder's Latin-1 file name), its bytes in hex under
// `key`_bytes, which the workers read instead: they open the file the plan found.
void put_path(json& j, const std::string& key, const fs::path& path) {
  static constexpr char kHex[] = "0123456789abcdef";
  const std::string& bytes = path.native();
  j[key] = bytes;
  if (valid_utf8(bytes) == bytes) return;
  std::string hex;
  for (const char c : bytes) {
    hex += kHex[static_cast<unsigned char>(c) >> 4];
    hex += kHex[static_cast<unsigned char>(c) & 15];
  }
  j[key + "_bytes"] = hex;
}

// The path put_path wrote; a `key`_bytes that is not hex throws as a field of the wrong type.
fs::path get_path(const json& j, const std::string& key) {
  const auto bytes = j.find(key + "_bytes");
  if (bytes == j.end()) return j.at(key).get<std::string>();
  const std::string hex = bytes->get<std::string>();
  const auto digit = [&](char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    throw json::type_error::create(302, "not hex", &*bytes);
  };
  if (hex.size() % 2 != 0) throw json::type_error::create(302, "not hex", &*bytes);
  std::string native;
  for (std::size_t k = 0; k < hex.size(); k += 2) native += static_cast<char>(digit(hex[k]) * 16 + digit(hex[k + 1]));
  return native;
}

// An integer field of at most 2^31 - 1 (a float or a larger number throws, as a missing field does).
int int_field(const json& j, const char* key) {
  const json& v = j.at(key);
  if (!v.is_number_integer() || v.get<std::int64_t>() < 0 || v.get<std::int64_t>() > 0x7fffffff)
    throw json::type_error::create(302, "not an integer", &v);
  return static_cast<int>(v.get<std::int64_t>());
}

BatchTask task_from_json(const json& j) {
  BatchTask t;
  t.index = int_field(j, "index");
  t.id = j.at("id");
  t.dem = get_path(j, "dem");
  t.viewpoint = j.at("viewpoint");
  const auto& c = j.at("camera");
  t.camera.position = c.at("position_enu");
  t.camera.target = c.at("target_enu");
  t.camera.fov_degrees = c.at("fov");
  t.camera_latlon = {c.at("latitude"), c.at("longitude")};
  const auto& s = j.at("sun");
  t.sun.label = s.at("label");
  t.sun.azimuth = s.at("azimuth");
  t.sun.elevation = s.at("elevation");
  if (const json& when = s.at("time_unix"); !when.is_null()) {
    if (!when.is_number_integer()) throw json::type_error::create(302, "not an integer", &when);
    t.sun.time_unix = when.get<std::int64_t>();
  }
  t.engine = parse_render_engine(j.at("engine").get<std::string>());
  t.width = int_field(j, "width");
  t.height = int_field(j, "height");
  t.scene_key = j.at("scene_key");
  t.input_hash = j.at("input_hash");
  if (const auto frames = j.find("frames"); frames != j.end()) {
    BatchFrames f;
    f.file = get_path(*frames, "file");
    f.fps = frames->at("fps");
    f.first = int_field(*frames, "first");
    f.count = int_field(*frames, "count");
    f.total = int_field(*frames, "total");
    f.folder = frames->at("folder");
    t.frames = f;
  }
  return t;
}

}  // namespace

json task_json(const BatchTask& t) {
  json j = {{"index", t.index},
            {"id", t.id},
            {"viewpoint", t.viewpoint},
            {"camera",
             {{"position_enu", t.camera.position},
              {"target_enu", t.camera.target},
              {"fov", t.camera.fov_degrees},
              {"latitude", t.camera_latlon[0]},
              {"longitude", t.camera_latlon[1]}}},
            {"sun",
             {{"label", t.sun.label},
              {"azimuth", t.sun.azimuth},
              {"elevation", t.sun.elevation},
              {"time_unix", t.sun.time_unix ? json(*t.sun.time_unix) : json(nullptr)}}},
            {"engine", to_string(t.engine)},
            {"width", t.width},
            {"height", t.height},
            {"scene_key", t.scene_key},
            {"input_hash", t.input_hash}};
  put_path(j, "dem", t.dem);
  if (t.frames) {
    const BatchFrames& f = *t.frames;
    j["frames"] = {{"fps", f.fps}, {"first", f.first}, {"count", f.count}, {"total", f.total}, {"folder", f.folder}};
    put_path(j["frames"], "file", f.file);
  }
  return j;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return {};
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A task record (tasks/ID.json, .failed): small files of this run; anything else (a torn write,
// a folder, a FIFO, a foreign or deep file) counts as absent.
json read_json(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec) || fs::file_size(file, ec) > (1u << 20) || ec) return json();
  const std::string text = read_text(file);
  if (text.empty()) return json();
  try {
    check_nesting(text, file, kMaxNesting);
    return json::parse(text);
  } catch (const std::exception&) {
    return json();
  }
}

Plan load_plan(const fs::path& dir) {
  const fs::path file = dir / "plan.json";
  std::error_code ec;
  if (!fs::exists(file, ec))
    throw Error(file, "", "is missing: not a batch output folder (run `wangscape batch run BATCH --out DIR` first)");
  return parse_batch_plan(read_text_file(file, kMaxPlanBytes, "batch plan"), file);
}

void write_plan(const fs::path& dir, const BatchConfig& config, const std::vector<BatchTask>& tasks) {
  json j;
  j["batch_file"] = config.source.string();
  j["scene"] = {{"text", config.scene.text}};
  put_path(j["scene"], "source", config.scene.source);
  put_path(j["scene"], "base_dir", config.scene.base_dir);
  put_path(j["scene"], "dem", config.scene.terrain.dem);
  j["tasks"] = json::array();
  for (const auto& t : tasks) j["tasks"].push_back(task_json(t));
  write_file_atomically(dir / "plan.json", json_text(j, 1) + "\n");
}

fs::path still_of(const fs::path& dir, const BatchTask& t) { return dir / "stills" / (t.id + ".png"); }
fs::path record_of(const fs::path& dir, const BatchTask& t, const char* ext) { return dir / "tasks" / (t.id + ext); }

bool task_done(const fs::path& dir, const BatchTask& t) {
  const json r = read_json(record_of(dir, t, ".json"));
  return r.is_object() && r.value("input_hash", "") == t.input_hash && fs::exists(still_of(dir, t));
}

const char* state_name(State s) {
  return s == State::done ? "done" : s == State::running ? "running" : s == State::failed ? "failed" : "pending";
}

State task_state(const fs::path& dir, const BatchTask& t) {
  if (task_done(dir, t)) return State::done;
  const std::string running = read_text(record_of(dir, t, ".running"));
  if (!running.empty()) {
    // A worker of this machine that is gone (killed) left its marker: the task is pending.
    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    std::istringstream in(running);
    long pid = 0;
    std::string on;
    in >> pid >> on;
    if (on != host || (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) == 0)) return State::running;
  }
  return fs::exists(record_of(dir, t, ".failed")) ? State::failed : State::pending;
}

}  // namespace batch_detail

using namespace batch_detail;

BatchPlan parse_batch_plan(std::string_view text, const fs::path& file) {
  check_nesting(text, file, kMaxNesting);  // nlohmann's parser recurses
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw Error(file, "", "is not a batch plan: not JSON (at byte " + std::to_string(e.byte) + ")");
  } catch (const json::exception&) {  // out_of_range.406: a number beyond a double
    throw Error(file, "", "is not a batch plan: it holds a number too large for a double");
  }
  const auto bad = [&](const std::string& place, const std::string& what) {
    return Error(file, place, what + " (the plan is written by `wangscape batch run`; run it again)");
  };
  if (!j.is_object() || !j.contains("scene") || !j.contains("tasks") || !j["tasks"].is_array())
    throw bad("", "is not a batch plan: expected an object with 'scene' and 'tasks'");
  BatchPlan plan;
  try {
    const auto& s = j.at("scene");
    plan.scene = parse_scene_config(s.at("text").get<std::string>(), get_path(s, "source"), get_path(s, "base_dir"));
    plan.scene.terrain.dem = get_path(s, "dem");
  } catch (const json::exception&) {
    throw bad("scene", "is not a batch plan's scene: expected 'text', 'source', 'base_dir' and 'dem' strings");
  }
  if (j["tasks"].size() > static_cast<std::size_t>(kMaxBatchTasks))
    throw bad("tasks", "holds " + std::to_string(j["tasks"].size()) + " tasks; at most " +
                           std::to_string(kMaxBatchTasks) + " are planned");
  for (const auto& item : j["tasks"]) {
    const std::string place = "task " + std::to_string(plan.tasks.size());
    BatchTask t;
    try {
      t = task_from_json(item);
    } catch (const json::exception&) {
      throw bad(place, "a field is missing or of the wrong type");
    } catch (const Error& e) {
      throw bad(place, e.message());
    }
    // Every path a worker derives from a task (stills/ID.png, tasks/ID.json, work/ID/, logs/ID.log,
    // scenes/KEY/) stays inside the output folder: ids and keys are checked, never trusted.
    if (t.index != static_cast<int>(plan.tasks.size()) || t.id != batch_task_id(t.index))
      throw bad(place, "has index " + std::to_string(t.index) + " and id '" + printable(t.id) + "'; expected " +
                           std::to_string(plan.tasks.size()) + " and '" +
                           batch_task_id(static_cast<int>(plan.tasks.size())) + "'");
    if (t.scene_key.size() != 16 || t.scene_key.find_first_not_of("0123456789abcdef") != std::string::npos)
      throw bad(place, "has scene key '" + printable(t.scene_key) + "'; expected 16 hex digits");
    const auto& c = t.camera;
    for (double v : {c.position[0], c.position[1], c.position[2], c.target[0], c.target[1], c.target[2], t.sun.azimuth,
                     t.camera_latlon[0], t.camera_latlon[1]})
      if (!std::isfinite(v)) throw bad(place, "holds a number that is not finite");
    if (!valid_field_of_view(c.fov_degrees) || !(t.sun.elevation >= -90 && t.sun.elevation <= 90) || t.width < 1 ||
        t.width > 32768 || t.height < 1 || t.height > 32768)
      throw bad(place, "has a field of view, a sun elevation or an image size out of range");
    if (const auto& f = t.frames) {  // paths/FOLDER/ stays inside the output folder too
      if (f->folder.empty() || f->folder.size() > 255 ||
          f->folder.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_") !=
              std::string::npos)
        throw bad(place, "has frames folder '" + printable(f->folder) + "'; expected letters, digits, '-' and '_'");
      if (!(f->fps >= kMinBatchPathFps && f->fps <= kMaxBatchPathFps) || f->count < 1 || f->first + f->count > f->total)
        throw bad(place, "has a path part out of range (frames " + std::to_string(f->first) + " + " +
                             std::to_string(f->count) + " of " + std::to_string(f->total) + ")");
    }
    plan.tasks.push_back(t);
  }
  return plan;
}

BatchCounts batch_status(const fs::path& dir, std::string* report) {
  const Plan plan = load_plan(dir);
  BatchCounts counts;
  for (const auto& t : plan.tasks) {
    const State s = task_state(dir, t);
    (s == State::done      ? counts.done
     : s == State::running ? counts.running
     : s == State::failed  ? counts.failed
                           : counts.pending)++;
    if (report)
      *report += t.id + "  " + state_name(s) + "  " + t.viewpoint + ", sun " + t.sun.label + ", " +
                 std::string(to_string(t.engine)) + "\n";
  }
  if (report)
    *report += "done " + std::to_string(counts.done) + ", running " + std::to_string(counts.running) + ", failed " +
               std::to_string(counts.failed) + ", pending " + std::to_string(counts.pending) + "\n";
  return counts;
}

}  // namespace wangscape
