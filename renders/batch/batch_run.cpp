// Batch runs: tasks that can be run twice and the local and Slurm executors (see batch_run.h);
// the output folder's files are batch_folder.h's, the gallery batch_gallery.cpp's.
#include "renders/batch/batch_run.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
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
#include "folder/scene_folder.h"
#include "renders/batch/batch_folder.h"
#include "renders/external/blender_render.h"
#include "renders/external/child_process.h"
#include "renders/external/povray_render.h"

namespace wangscape {

namespace fs = std::filesystem;
using namespace batch_detail;  // the output folder's files (batch_folder.h)

namespace {

using Messages = std::function<void(const std::string& line)>;

// ---- one task -----------------------------------------------------------------------------------

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

// Builds the shared scene folder of `t` unless it is there (SceneFolder publishes it whole, so a
// folder with its scene file is complete).
fs::path shared_scene(const fs::path& dir, const Plan& plan, const BatchTask& t) {
  const fs::path folder = fs::absolute(dir / "scenes" / t.scene_key);
  FileLock lock(dir / "scenes" / (t.scene_key + ".lock"));
  if (!fs::exists(FolderFiles(folder).scene_file())) {
    SceneConfig scene = task_scene_config(plan.scene, scene_owner(plan, t));
    scene.exports = {};
    scene.exports.povray = true;
    SceneFolder::build(scene, folder);
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
  Sun sun;
  sun.azimuth_degrees = t.sun.azimuth;
  sun.elevation_degrees = t.sun.elevation;
  sun.strength = plan.scene.sun.strength;
  const fs::path pov = FolderFiles(scene).povray_scene();
  write_file_atomically(FolderFiles(work).povray_scene(),
                        povray_scene_with_camera_and_sun(read_text(pov), t.camera, sun, pov));
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
  SceneFolder::build(scene, work);
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
      if (!fs::exists(FolderFiles(scene).scene_file())) SceneFolder::build(config, scene);
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

}  // namespace

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
