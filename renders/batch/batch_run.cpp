// Batch runs: tasks that can be run twice, the local and Slurm executors, status from the
// files and the gallery (see batch_run.h).
#include "renders/batch/batch_run.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "core/atomic_file.h"
#include "core/durable_file.h"
#include "core/json_text.h"
#include "core/number_text.h"
#include "core/printable.h"
#include "core/text_file.h"
#include "core/vecmath.h"
#include "exporters/povray_writer.h"
#include "exporters/scene_folder.h"
#include "renders/external/blender_render.h"
#include "renders/external/child_process.h"
#include "renders/external/movie.h"
#include "renders/external/povray_render.h"

namespace wangscape {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using Messages = std::function<void(const std::string& line)>;

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

using Plan = BatchPlan;

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

// ---- one task -----------------------------------------------------------------------------------

fs::path still_of(const fs::path& dir, const BatchTask& t) { return dir / "stills" / (t.id + ".png"); }
fs::path record_of(const fs::path& dir, const BatchTask& t, const char* ext) { return dir / "tasks" / (t.id + ext); }

bool task_done(const fs::path& dir, const BatchTask& t) {
  const json r = read_json(record_of(dir, t, ".json"));
  return r.is_object() && r.value("input_hash", "") == t.input_hash && fs::exists(still_of(dir, t));
}

// The first task of `t`'s scene: it alone decides the shared folder, whichever worker builds it.
const BatchTask& scene_owner(const Plan& plan, const BatchTask& t) {
  return *std::find_if(plan.tasks.begin(), plan.tasks.end(),
                       [&](const BatchTask& o) { return o.scene_key == t.scene_key; });
}

// An exclusive lock on a file, released when it goes out of scope (workers of other processes
// and other Slurm nodes over a shared folder wait here).
class FileLock {
 public:
  explicit FileLock(const fs::path& file) : fd_(::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644)) {
    if (fd_ < 0 || ::flock(fd_, LOCK_EX) != 0) throw Error(file, "", "cannot be locked");
  }
  ~FileLock() { ::close(fd_); }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_;
};

// Builds the shared scene folder of `t` unless it is there (write_scene_folder publishes it
// whole, so a folder with scene.toml is complete).
fs::path shared_scene(const fs::path& dir, const Plan& plan, const BatchTask& t) {
  const fs::path folder = fs::absolute(dir / "scenes" / t.scene_key);
  FileLock lock(dir / "scenes" / (t.scene_key + ".lock"));
  if (!fs::exists(folder / "scene.toml")) {
    SceneConfig scene = task_scene_config(plan.scene, scene_owner(plan, t));
    scene.exports = {};
    scene.exports.povray = true;
    build_scene_folder(scene, folder);
  }
  return folder;
}

// This program: workers, Slurm's array tasks and the Embree stills run it again.
fs::path self_program() { return fs::read_symlink("/proc/self/exe"); }

// The log of task t's engine (work/ID/ENGINE.log).
fs::path engine_log(const fs::path& dir, const BatchTask& t) {
  return dir / "work" / t.id / (std::string(to_string(t.engine)) + ".log");
}

// POV-Ray over the shared folder: scene.pov with this task's camera and sun, includes and
// Library_Path pointing at the shared folder.
fs::path render_povray_task(const fs::path& dir, const Plan& plan, const BatchTask& t) {
  const fs::path scene = shared_scene(dir, plan, t);
  const fs::path work = dir / "work" / t.id;
  fs::create_directories(work);
  std::string pov = read_text(scene / "scene.pov");
  const auto begin = pov.find("camera {\n"), end = pov.find("sky_sphere {");
  if (begin == std::string::npos || end == std::string::npos || end < begin)
    throw Error(scene / "scene.pov", "", "has no camera and sky_sphere blocks to replace");
  Sun sun;
  sun.azimuth_degrees = t.sun.azimuth;
  sun.elevation_degrees = t.sun.elevation;
  sun.strength = plan.scene.sun.strength;
  pov.replace(begin, end - begin, povray_camera_and_sun(t.camera, sun) + "\n");
  write_file_atomically(work / "scene.pov", pov);
  std::string ini;
  std::istringstream lines(read_text(scene / "scene.ini"));
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("Library_Path=", 0) != 0 && line.rfind("Work_Threads=", 0) != 0) ini += line + "\n";
  ini += "Work_Threads=1\nLibrary_Path=" + povray_quoted_path(scene) + "\n";
  write_file_atomically(work / "scene.ini", ini);
  PovrayRenderOptions options;
  options.width = t.width;
  options.height = t.height;
  return render_povray(work, options).image;
}

// Blender reads the camera from the folder's manifest, so each Blender still builds its own.
fs::path render_blender_task(const fs::path& dir, const Plan& plan, const BatchTask& t) {
  SceneConfig scene = task_scene_config(plan.scene, t);
  scene.exports = {};
  scene.exports.blender = true;
  const fs::path work = fs::absolute(dir / "work" / t.id);
  build_scene_folder(scene, work);
  BlenderRenderOptions options;
  options.width = t.width;
  options.height = t.height;
  return render_blender(work, options).image;
}

// Runs argv (this program again) with its output in `log`, which starts with the command so that the
// gallery's link shows what was run. Throws Error naming `what` and the log's last lines.
void run_child(const std::vector<std::string>& argv, const fs::path& log, const std::string& what) {
  std::string command;
  for (const std::string& arg : argv) command += (command.empty() ? "" : " ") + arg;
  write_file_atomically(log, command + "\n");
  const ChildExit ended = run_logged(argv, log);
  if (!ended.exited || ended.status != 0) throw Error(log, "", what + " " + ended.describe() + last_log_lines(log, 3));
}

// The Embree reference over the shared folder: `wangscape render` in a child process with this
// task's camera, lens and sun (batch starts programs on a folder; the Embree scene is the render
// command's to make).
fs::path render_embree_task(const fs::path& dir, const Plan& plan, const BatchTask& t) {
  const fs::path scene = shared_scene(dir, plan, t);
  const fs::path work = fs::absolute(dir / "work" / t.id);
  fs::create_directories(work);
  const auto triple = [](const std::array<double, 3>& p) {
    return number_text(p[0]) + "," + number_text(p[1]) + "," + number_text(p[2]);
  };
  const fs::path image = work / "render_embree.png";
  // (--option=value: a value may start with a minus sign)
  std::vector<std::string> argv{self_program().string(),
                                "--quiet",
                                "render",
                                scene.string(),
                                "--engine=embree",
                                "--camera=" + triple(t.camera.position),
                                "--look-at=" + triple(t.camera.target),
                                "--fov=" + number_text(t.camera.fov_degrees),
                                "--sun=" + number_text(t.sun.azimuth) + "," + number_text(t.sun.elevation),
                                "--out=" + image.string()};
  if (t.width > 0) argv.push_back("--width=" + std::to_string(t.width));
  if (t.height > 0) argv.push_back("--height=" + std::to_string(t.height));
  run_child(argv, engine_log(dir, t), "the Embree render");
  return image;
}

// A part of a path: `wangscape render --path` over the scene folder (the shared one; Blender's its
// own, with its export) into work/ID/frames, where an earlier run's frames are kept and not
// rendered again; each frame is then linked into the path's folder paths/FOLDER/ (under a
// temporary name, then renamed: a frame there is whole), and the part's first frame is the still.
fs::path render_frames_task(const fs::path& dir, const Plan& plan, const BatchTask& t) {
  const BatchFrames& f = *t.frames;
  const fs::path work = fs::absolute(dir / "work" / t.id), frames = work / "frames";
  const fs::path shared = fs::absolute(dir / "paths" / f.folder);
  fs::create_directories(frames);
  fs::create_directories(shared);
  const auto missing = [&] {
    for (long long k = f.first; k < f.first + f.count; ++k)
      if (!fs::exists(shared / path_frame_name(k))) return true;
    return false;
  };
  if (missing()) {
    fs::path scene;
    if (t.engine == RenderEngine::blender) {
      SceneConfig config = task_scene_config(plan.scene, t);
      config.exports = {};
      config.exports.blender = true;
      scene = work / "scene";
      if (!fs::exists(scene / "scene.toml")) build_scene_folder(config, scene);
    } else {
      scene = shared_scene(dir, plan, t);
    }
    std::vector<std::string> argv{self_program().string(),
                                  "--quiet",
                                  "render",
                                  scene.string(),
                                  "--engine=" + std::string(to_string(t.engine)),
                                  "--path=" + f.file.string(),
                                  "--frames=" + frames.string(),
                                  "--fps=" + number_text(f.fps),
                                  "--first-frame=" + std::to_string(f.first),
                                  "--frame-count=" + std::to_string(f.count),
                                  "--width=" + std::to_string(t.width),
                                  "--height=" + std::to_string(t.height)};
    run_child(argv, engine_log(dir, t), "the " + std::string(to_string(t.engine)) + " render of frames");
    for (long long k = f.first; k < f.first + f.count; ++k) {
      const fs::path from = frames / path_frame_name(k), to = shared / path_frame_name(k);
      if (fs::exists(to)) continue;
      AtomicPath linked(to);
      std::error_code failed;
      fs::create_hard_link(from, linked.temp_path(), failed);
      if (failed) fs::copy_file(from, linked.temp_path());  // (another filesystem)
      linked.commit();
    }
  }
  const fs::path first = work / "first-frame.png";
  fs::copy_file(shared / path_frame_name(f.first), first, fs::copy_options::overwrite_existing);
  return first;
}

// The still of task t, rendered by its engine.
fs::path render_task(const fs::path& dir, const Plan& plan, const BatchTask& t) {
  if (t.frames) return render_frames_task(dir, plan, t);
  switch (t.engine) {
    case RenderEngine::blender:
      return render_blender_task(dir, plan, t);
    case RenderEngine::embree:
      return render_embree_task(dir, plan, t);
    case RenderEngine::povray:
      break;
  }
  return render_povray_task(dir, plan, t);
}

// Publishes a rendered PNG as the task's still without the chunks that record when it was
// rendered (POV-Ray writes tIME and a "Render Date" comment), so a still is a function of its
// inputs: reruns and executors give the same bytes.
void publish_still(const fs::path& image, const fs::path& still) {
  const std::string png = read_text(image);
  static constexpr std::string_view kSignature = "\x89PNG\r\n\x1a\n";
  if (png.compare(0, kSignature.size(), kSignature) != 0) throw Error(image, "", "is not a PNG image");
  std::string out(kSignature);
  for (std::size_t at = kSignature.size(); at + 12 <= png.size();) {
    const auto byte = [&](std::size_t k) {
      return static_cast<std::uint32_t>(static_cast<unsigned char>(png[at + k]));
    };
    const std::size_t length = (byte(0) << 24) | (byte(1) << 16) | (byte(2) << 8) | byte(3);
    const std::string_view type(png.data() + at + 4, 4);
    if (at + 12 + length > png.size()) throw Error(image, "", "is a truncated PNG image");
    const bool dated = type == "tIME" || (type == "tEXt" && png.compare(at + 8, 8, "Comment\0", 8) == 0);
    if (!dated) out.append(png, at, 12 + length);
    at += 12 + length;
  }
  write_file_atomically(still, out);
  fs::remove(image);
}

// Runs one task unless it is done. Returns true when its still is done.
bool run_task(const fs::path& dir, const Plan& plan, const BatchTask& t, const Messages& say) {
  if (task_done(dir, t)) {
    say("task " + t.id + ": done already, skipped");
    return true;
  }
  const json previous = read_json(record_of(dir, t, ".json"));
  fs::create_directories(dir / "stills");
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  write_file_atomically(record_of(dir, t, ".running"), std::to_string(::getpid()) + " " + host + "\n");
  const auto start = std::chrono::steady_clock::now();
  try {
    const fs::path image = render_task(dir, plan, t);
    publish_still(image, still_of(dir, t));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const json record = {{"input_hash", t.input_hash},
                         {"seconds", std::round(seconds * 1000) / 1000},
                         {"renders", (previous.is_object() ? previous.value("renders", 0) : 0) + 1},
                         {"finished_unix", static_cast<std::int64_t>(std::time(nullptr))},
                         {"host", host}};
    write_file_atomically(record_of(dir, t, ".json"), json_text(record, 1) + "\n");
    fs::remove(record_of(dir, t, ".failed"));
    fs::remove(record_of(dir, t, ".running"));
    say("task " + t.id + ": rendered in " + fixed_text(seconds, 2) + " s");
    return true;
  } catch (const std::exception& e) {
    const fs::path log = engine_log(dir, t);
    write_file_atomically(record_of(dir, t, ".failed"), json_text(json{{"error", e.what()}, {"log", log.string()}}, 1));
    fs::remove(record_of(dir, t, ".running"));
    say("task " + t.id + " failed: " + e.what());
    return false;
  }
}

// ---- status -------------------------------------------------------------------------------------

enum class State { done, running, failed, pending };
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

// ---- executors ----------------------------------------------------------------------------------

int default_workers() { return std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }

// A line per failed task: its viewpoint, sun and engine, its error and its log.
std::string failure_lines(const fs::path& dir, const Plan& plan) {
  std::string lines;
  for (const auto& t : plan.tasks)
    if (task_state(dir, t) == State::failed) {
      const json f = read_json(record_of(dir, t, ".failed"));
      lines += "\n  task " + t.id + " (" + t.viewpoint + ", " + t.sun.label + ", " + std::string(to_string(t.engine)) +
               ") failed: " + (f.is_object() ? f.value("error", "?") : "?") +
               " (log: " + (f.is_object() ? f.value("log", "?") : "?") + ")";
    }
  return lines;
}

// Local: N worker processes (`wangscape batch run-task`), each task its own process.
void run_local(const BatchRunSettings& s, const Plan& plan) {
  const fs::path program = self_program();
  const int workers = s.workers > 0 ? s.workers : default_workers();
  std::atomic<int> next{0}, finished{0};
  std::mutex report;
  const int total = static_cast<int>(plan.tasks.size());
  auto worker = [&] {
    for (int k = next++; k < total; k = next++) {
      const auto& t = plan.tasks[k];
      if (!task_done(s.out_dir, t)) {
        const std::vector<std::string> argv{program.string(), "--quiet",          "batch",
                                            "run-task",       s.out_dir.string(), std::to_string(k)};
        run_logged(argv, s.out_dir / "logs" / (t.id + ".log"));
      }
      const int f = ++finished;
      std::lock_guard lock(report);
      if (s.on_progress) s.on_progress(f, total);
    }
  };
  std::vector<std::thread> pool;
  try {
    for (int i = 0; i < std::min(workers, std::max(total, 1)); ++i) pool.emplace_back(worker);
  } catch (const std::system_error&) {  // no thread left: run with the workers that started
    if (pool.empty()) throw Error("batch run: cannot start a worker thread (too many threads or processes)");
  }
  for (auto& th : pool) th.join();
}

// Runs a Slurm tool and returns its stdout (Error naming the command when it fails).
std::string slurm(const fs::path& dir, std::vector<std::string> argv) {
  const std::string tool = argv[0];
  const fs::path program = find_program(tool);
  if (program.empty()) throw Error("slurm executor: '" + tool + "' is not installed (apt install slurm-client)");
  argv[0] = program.string();
  const fs::path out = dir / "logs" / ("." + tool + "-" + std::to_string(::getpid()) + ".out");
  fs::remove(out);
  const auto exit = run_logged(argv, out);
  std::string text = read_text(out);
  fs::remove(out);
  if (!exit.exited || exit.status != 0) {
    if (tool == "squeue") return {};  // jobs that left the queue are unknown to it
    throw Error("slurm executor: " + tool + " " + exit.describe() + ": " + text);
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text.substr(0, text.find(';'));  // sbatch --parsable: "job[;cluster]"
}

bool in_queue(const fs::path& dir, const std::string& job) {
  return !slurm(dir, {"squeue", "-h", "-j", job, "-o", "%i"}).empty();
}

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Slurm: one job array (chunks of tasks per element, throttled with %), failed elements
// resubmitted up to `retries` times, and a final job (afterok) that assembles the results.
void run_slurm(const BatchRunSettings& s, const Plan& plan) {
  const fs::path dir = fs::absolute(s.out_dir);
  const int total = static_cast<int>(plan.tasks.size());
  const int chunk = s.chunk > 0 ? s.chunk : std::max(1, (total + 255) / 256);
  const fs::path script = dir / "logs" / "element.sh";
  write_file_atomically(script, "#!/bin/sh\n# One Slurm array element: tasks [id * chunk, id * chunk + chunk).\nexec " +
                                    quoted(self_program().string()) + " --quiet batch run-task " +
                                    quoted(dir.string()) + " $((SLURM_ARRAY_TASK_ID * " + std::to_string(chunk) +
                                    ")) " + std::to_string(chunk) + "\n");
  fs::permissions(script, fs::perms::owner_all | fs::perms::group_read | fs::perms::others_read);
  for (int attempt = 0;; ++attempt) {
    std::string elements;
    for (int e = 0; e * chunk < total; ++e) {
      bool done = true;
      for (int k = e * chunk; k < std::min(total, (e + 1) * chunk); ++k) done = done && task_done(dir, plan.tasks[k]);
      if (done) continue;
      if (!elements.empty()) elements += ',';
      elements += std::to_string(e);
    }
    std::vector<std::string> sbatch{"sbatch", "--parsable", "--requeue", "--job-name=wangscape-batch",
                                    "--chdir=" + dir.string()};
    std::string after;
    if (!elements.empty()) {
      auto array = sbatch;
      array.push_back("--array=" + elements + (s.throttle > 0 ? "%" + std::to_string(s.throttle) : ""));
      array.push_back("--output=" + (dir / "logs" / "slurm-%A_%a.log").string());
      array.push_back(script.string());
      after = slurm(dir, array);
      if (s.on_message) s.on_message("submitted job array " + after + " (elements " + elements + ")");
    }
    auto final_job = sbatch;
    if (!after.empty()) final_job.push_back("--dependency=afterok:" + after);
    final_job.push_back("--output=" + (dir / "logs" / "slurm-assemble-%j.log").string());
    final_job.push_back("--wrap=" + quoted(self_program().string()) + " --quiet batch run-task " +
                        quoted(dir.string()));
    const std::string assemble = slurm(dir, final_job);
    while (!after.empty() && in_queue(dir, after)) {
      if (s.on_progress) s.on_progress(batch_status(dir).done, total);
      std::this_thread::sleep_for(std::chrono::milliseconds(250));
    }
    const auto counts = batch_status(dir);
    if (counts.done == total || attempt >= s.retries) {
      if (counts.done != total) slurm(dir, {"scancel", assemble});  // afterok never fires
      while (in_queue(dir, assemble)) std::this_thread::sleep_for(std::chrono::milliseconds(100));
      return;
    }
    slurm(dir, {"scancel", assemble});
    if (s.on_message) s.on_message(std::to_string(total - counts.done) + " tasks failed; resubmitting them");
  }
}

// ---- results ------------------------------------------------------------------------------------

std::string html_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

// Where the gallery links a still to, relative to the output folder: the scene folder it was
// rendered from (POV-Ray: the shared scenes/KEY/; Blender: the task's own work/ID/; a path's part:
// its inputs are the path's frames folder), the
// engine's log and what the engine ran (POV-Ray: work/ID/scene.pov with the task's camera and
// sun; Blender: the manifest of the task's folder, which holds them; Embree: the shared scene file,
// its log starting with the command that holds the task's camera and sun).
struct TaskLinks {
  std::string scene, log, inputs;
};
TaskLinks task_links(const BatchTask& t) {
  const std::string work = "work/" + t.id + "/";
  if (t.frames) {  // a path's part: its frames folder (with path.mp4 once every part is done)
    const std::string scene = t.engine == RenderEngine::blender ? work + "scene/" : "scenes/" + t.scene_key + "/";
    return {scene, work + std::string(to_string(t.engine)) + ".log", "paths/" + t.frames->folder + "/"};
  }
  if (t.engine == RenderEngine::blender) return {work, work + "blender.log", work + "blender/manifest.json"};
  if (t.engine == RenderEngine::embree)
    return {"scenes/" + t.scene_key + "/", work + "embree.log", "scenes/" + t.scene_key + "/scene.toml"};
  return {"scenes/" + t.scene_key + "/", work + "povray.log", work + "scene.pov"};
}

// The labels' font: Debian's DejaVu Sans (fonts-dejavu-core); without it the sheet has no labels
// (index.html still names every still's viewpoint, sun and engine).
constexpr char kLabelFont[] = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
constexpr int kLabelSize = 11, kLabelLines = 2;  // pixels per line; viewpoint and engine, then sun

// A sun's label as short as a thumbnail's width wants it: a time "2024-07-15T10:00:00-07:00" as
// "2024-07-15 10:00 -07:00" (with its seconds unless they are 0); other labels as they are. The
// full label with the engine ran 40 pixels into the next column.
std::string sheet_sun_label(const std::string& label) {
  const bool time = label.size() == 25 && label[10] == 'T' && label[13] == ':' && label[16] == ':';
  if (!time) return label;
  const std::string clock = label.compare(16, 3, ":00") == 0 ? label.substr(11, 5) : label.substr(11, 8);
  return label.substr(0, 10) + " " + clock + " " + label.substr(19);
}

void write_contact_sheet(const fs::path& dir, const Plan& plan) {
  constexpr int kThumb = 160;
  const int n = static_cast<int>(plan.tasks.size());
  const int columns = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)))));
  const int rows = std::max(1, (n + columns - 1) / columns);
  int thumb_h = kThumb * 9 / 16;
  if (!plan.tasks.empty() && plan.tasks[0].width > 0)
    thumb_h = std::max(1, kThumb * plan.tasks[0].height / plan.tasks[0].width);
  std::error_code ec;
  const bool labelled = fs::is_regular_file(kLabelFont, ec);
  const int label_h = labelled ? kLabelLines * (kLabelSize + 2) + 2 : 0;
  const int cell_h = thumb_h + label_h + 4;
  const float grey[3] = {0.2f, 0.2f, 0.2f}, white[3] = {0.92f, 0.92f, 0.92f};
  OIIO::ImageBuf sheet(OIIO::ImageSpec(columns * (kThumb + 4) + 4, rows * cell_h + 4, 3, OIIO::TypeDesc::UINT8));
  OIIO::ImageBufAlgo::fill(sheet, grey);
  for (int k = 0; k < n; ++k) {
    const BatchTask& task = plan.tasks[std::size_t(k)];
    const int x = 4 + (k % columns) * (kThumb + 4), y = 4 + (k / columns) * cell_h;
    if (task_done(dir, task)) {
      OIIO::ImageBuf image(still_of(dir, task).string());
      OIIO::ImageBuf thumb = OIIO::ImageBufAlgo::resize(image, "", 0, OIIO::ROI(0, kThumb, 0, thumb_h, 0, 1, 0, 3));
      OIIO::ImageBufAlgo::paste(sheet, x, y, 0, 0, thumb);
    }
    if (!labelled) continue;
    // Under each still (or its empty place): what it shows, as the batch file names it.
    const std::string lines[kLabelLines] = {
        task.id + "  " + task.viewpoint + "  " + std::string(to_string(task.engine)), sheet_sun_label(task.sun.label)};
    for (int line = 0; line < kLabelLines; ++line)
      OIIO::ImageBufAlgo::render_text(sheet, x + 1, y + thumb_h + (line + 1) * (kLabelSize + 2), lines[line],
                                      kLabelSize, kLabelFont, white);
  }
  AtomicPath out(dir / "contact-sheet.png");
  if (!sheet.write(out.temp_path().string(), OIIO::TypeDesc::UINT8, "png"))
    throw Error(dir / "contact-sheet.png", "", "cannot be written: " + sheet.geterror());
  out.commit();
}

}  // namespace

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

std::string batch_plan_text(const fs::path& batch_file, bool as_json) {
  const auto config = load_batch_config(batch_file);
  const auto tasks = expand_batch(config);
  if (as_json) {
    json j = json::array();
    for (const auto& t : tasks) j.push_back(task_json(t));
    return json_text(j, 2) + "\n";
  }
  std::string out;
  for (const auto& t : tasks) {
    const auto& p = t.camera.position;
    out += t.id + "  " + (t.dem.empty() ? std::string("flat ground") : t.dem.filename().string()) + "  " + t.viewpoint +
           " at ENU (" + fixed_text(p[0], 1) + ", " + fixed_text(p[1], 1) + ", " + fixed_text(p[2], 1) + ")  sun " +
           t.sun.label + "  " + std::string(to_string(t.engine)) + " " + std::to_string(t.width) + "x" +
           std::to_string(t.height) + "\n";
  }
  return out + std::to_string(tasks.size()) + " tasks\n";
}

void run_batch_tasks(const fs::path& dir, int first, int count, const Messages& on_message) {
  const Messages say = on_message ? on_message : [](const std::string&) {};
  const Plan plan = load_plan(dir);
  const int total = static_cast<int>(plan.tasks.size());
  if (first < 0 || first >= total) throw Error(dir / "plan.json", "", "has no task " + std::to_string(first));
  std::string failed;
  for (int k = first; k < std::min(total, first + count); ++k)
    if (!run_task(dir, plan, plan.tasks[k], say)) failed += " " + plan.tasks[k].id;
  if (!failed.empty()) throw Error(dir / "tasks", "", "task(s)" + failed + " failed (see the .failed files)");
}

void run_batch_tasks(const BatchRunSettings& settings) {
  if (settings.task_range.empty()) return assemble_batch(settings.out_dir);
  run_batch_tasks(settings.out_dir, settings.task_range[0], settings.task_range.size() > 1 ? settings.task_range[1] : 1,
                  settings.on_message);
}

std::string batch_status_text(const BatchRunSettings& settings) {
  std::string report;
  for (auto counts = batch_status(settings.out_dir); settings.watch && settings.on_progress;
       counts = batch_status(settings.out_dir)) {
    const int total = counts.done + counts.running + counts.failed + counts.pending;
    settings.on_progress(counts.running > 0 ? counts.done + counts.failed : total, total);
    if (counts.running == 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  batch_status(settings.out_dir, &report);
  return report;
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

namespace {

// Each path whose parts are all done made into paths/FOLDER/path.mp4 (once; when ffmpeg is on
// PATH), and the gallery's list of them.
std::string movies_html(const fs::path& dir, const Plan& plan) {
  std::map<std::string, std::pair<double, bool>> paths;  // folder -> fps, every part done
  for (const auto& t : plan.tasks)
    if (t.frames) {
      const auto at = paths.try_emplace(t.frames->folder, t.frames->fps, true).first;
      at->second.second = at->second.second && task_state(dir, t) == State::done;
    }
  if (paths.empty()) return {};
  std::string html = "<h2>Paths</h2>\n<ul>\n";
  for (const auto& [folder, state] : paths) {
    const fs::path frames = dir / "paths" / folder, movie = frames / "path.mp4";
    const bool made =
        state.second && (fs::exists(movie) || write_frames_movie(frames, kPathFramePattern, state.first, movie));
    html += "<li><a href=\"paths/" + html_escape(folder) + "/\">" + html_escape(folder) + "</a>" +
            (made           ? " · <a href=\"paths/" + html_escape(folder) + "/path.mp4\">path.mp4</a>"
             : state.second ? " (all frames; no ffmpeg on PATH for path.mp4)"
                            : " (frames still to come)") +
            "</li>\n";
  }
  return html + "</ul>\n";
}

}  // namespace

void assemble_batch(const fs::path& dir) {
  const Plan plan = load_plan(dir);
  json all = json::array();
  std::string html =
      "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>Wangscape batch</title><style>"
      "body{font-family:sans-serif;background:#222;color:#ddd}figure{display:inline-block;margin:6px;"
      "vertical-align:top;width:330px}img{width:320px}figcaption{font-size:12px}a{color:#9cf}"
      ".failed{color:#f88;font-size:12px;white-space:pre-wrap}</style></head><body>\n"
      "<h1>Wangscape batch</h1>\n<p><img src=\"contact-sheet.png\" alt=\"contact sheet\" style=\"width:auto\"></p>\n";
  int renders = 0;
  BatchCounts counts;
  for (const auto& t : plan.tasks) {
    json j = task_json(t);
    const State s = task_state(dir, t);
    (s == State::done      ? counts.done
     : s == State::running ? counts.running
     : s == State::failed  ? counts.failed
                           : counts.pending)++;
    j["status"] = state_name(s);
    const json record = read_json(record_of(dir, t, ".json"));
    const double seconds = record.is_object() ? record.value("seconds", 0.0) : 0.0;
    j["seconds"] = seconds;
    j["renders"] = record.is_object() ? record.value("renders", 0) : 0;
    renders += j["renders"].get<int>();
    j["image"] = s == State::done ? "stills/" + t.id + ".png" : "";
    const json failure = s == State::failed ? read_json(record_of(dir, t, ".failed")) : json();
    if (s == State::failed) j["failure"] = failure;
    const TaskLinks links = task_links(t);
    j["links"] = {{"scene", links.scene}, {"log", links.log}, {"inputs", links.inputs}};
    const auto& p = t.camera.position;
    std::string failed;
    if (s == State::failed)
      failed = "<p class=\"failed\">failed: " +
               html_escape(failure.is_object() ? failure.value("error", std::string("?")) : std::string("?")) + "</p>";
    html +=
        "<figure>" +
        (s == State::done ? "<a href=\"stills/" + t.id + ".png\"><img src=\"stills/" + t.id + ".png\" alt=\"still " +
                                t.id + "\"></a>"
         : failed.empty() ? "<p>" + std::string(state_name(s)) + "</p>"
                          : failed) +
        "<figcaption>" + t.id + " " + html_escape(t.viewpoint) +
        "<br>DEM: " + html_escape(valid_utf8(t.dem.empty() ? std::string("flat ground") : t.dem.filename().string())) +
        "<br>camera ENU (" + fixed_text(p[0], 1) + ", " + fixed_text(p[1], 1) + ", " + fixed_text(p[2], 1) +
        ") m, lat/lon " + fixed_text(t.camera_latlon[0], 6) + ", " + fixed_text(t.camera_latlon[1], 6) + "<br>sun " +
        html_escape(t.sun.label) + " (az " + fixed_text(t.sun.azimuth, 1) + ", el " + fixed_text(t.sun.elevation, 1) +
        ")<br>" + std::string(to_string(t.engine)) + ", " + fixed_text(seconds, 2) + " s<br><a href=\"" + links.scene +
        "\">scene folder</a> · <a href=\"" + links.log + "\">" + std::string(to_string(t.engine)) +
        " log</a> · <a href=\"" + links.inputs + "\">inputs</a></figcaption></figure>\n";
    all.push_back(j);
  }
  html += movies_html(dir, plan);
  html += "</body></html>\n";
  write_contact_sheet(dir, plan);
  write_file_atomically(dir / "index.html", html);
  const json batch = {{"tasks", all},
                      {"done", counts.done},
                      {"failed", counts.failed},
                      {"pending", counts.pending},
                      {"running", counts.running},
                      {"renders_total", renders}};
  write_file_atomically(dir / "batch.json", json_text(batch, 1) + "\n");
}

namespace {

// The folders of a batch's output, or an Error naming the one that cannot be made.
void make_output_folders(const fs::path& out) {
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec))
    throw Error(out, "", "the batch output folder exists and is not a folder; name another --out");
  for (const char* sub : {"", "scenes", "work", "stills", "tasks", "logs"}) {
    const fs::path folder = *sub ? out / sub : out;
    fs::create_directories(folder, ec);
    if (ec || !fs::is_directory(folder))
      throw Error(folder, "", "cannot create the batch output folder: " + (ec ? ec.message() : "not a folder"));
  }
  // Durably (core/durable_file.h): the stills and task records are renamed into these folders,
  // which must outlive a power cut as the files do.
  sync_folder(out);
  sync_folder(fs::absolute(out).parent_path());
}

// One `batch run` at a time per output folder: a second one would render every still again
// beside the first. The lock (flock on logs/run.lock) goes with the process, killed or not.
class RunLock {
 public:
  explicit RunLock(const fs::path& out) : file_(out / "logs" / "run.lock") {
    fd_ = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw Error(file_, "", "cannot open the run's lock file");
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      std::string holder = read_text(file_);
      while (!holder.empty() && (holder.back() == '\n' || holder.back() == ' ')) holder.pop_back();
      ::close(fd_);
      throw Error(out, "",
                  "another `wangscape batch run` (" +
                      (holder.empty() ? std::string("pid unknown") : printable(holder)) +
                      ") is rendering into this folder; wait for it (`wangscape batch status " + out.string() +
                      " --progress`) or give another --out");
    }
    const std::string me = "pid " + std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, me.data(), me.size(), 0) < 0) {
    }  // the holder's pid: a courtesy
  }
  ~RunLock() { ::close(fd_); }
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

 private:
  fs::path file_;
  int fd_ = -1;
};

}  // namespace

BatchCounts run_batch(const BatchRunSettings& s) {
  if (s.out_dir.empty()) throw Error("batch run: --out is empty; name the output folder");
  const auto config = load_batch_config(s.batch_file);
  const auto tasks = expand_batch(config);
  // POV-Ray's stills are rendered in folders under --out, named to POV-Ray in double quotes: a
  // name it cannot take is refused before any folder is made, as `build` refuses its --out.
  if (std::any_of(tasks.begin(), tasks.end(), [](const BatchTask& t) { return t.engine == RenderEngine::povray; })) {
    try {
      povray_quoted_path(fs::absolute(s.out_dir));
    } catch (const Error& e) {
      throw Error("batch run --out " + printable(s.out_dir.string()) + ": " + e.message());
    }
  }
  make_output_folders(s.out_dir);
  const RunLock lock(s.out_dir);
  write_plan(s.out_dir, config, tasks);
  const Plan plan = load_plan(s.out_dir);
  if (s.on_message)
    s.on_message(std::to_string(tasks.size()) + " tasks, executor " + std::string(to_string(s.executor)) + ", into " +
                 s.out_dir.string());
  if (s.executor == BatchExecutor::slurm)
    run_slurm(s, plan);
  else
    run_local(s, plan);
  // The Slurm final job assembled already; assembling again is cheap and covers failures.
  assemble_batch(s.out_dir);
  const auto counts = batch_status(s.out_dir);
  if (s.on_progress) s.on_progress(static_cast<int>(tasks.size()), static_cast<int>(tasks.size()));
  if (counts.done != static_cast<int>(tasks.size()))
    throw Error(s.out_dir / "index.html", "",
                std::to_string(counts.done) + " of " + std::to_string(tasks.size()) + " stills done, " +
                    std::to_string(counts.failed) + " failed, " + std::to_string(counts.pending) + " pending" +
                    failure_lines(s.out_dir, plan));
  return counts;
}

std::string_view to_string(BatchExecutor executor) { return executor == BatchExecutor::slurm ? "slurm" : "local"; }

BatchExecutor parse_batch_executor(std::string_view name) {
  for (const BatchExecutor e : kBatchExecutors)
    if (name == to_string(e)) return e;
  throw Error("batch run: executor '" + std::string(name) + "' is not known (local, slurm)");
}

std::vector<std::string> batch_executor_names() {
  std::vector<std::string> names;
  for (const BatchExecutor e : kBatchExecutors) names.emplace_back(to_string(e));
  return names;
}

}  // namespace wangscape
