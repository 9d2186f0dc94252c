// A batch's results (renders/batch/batch_run.h: assemble_batch): the gallery index.html, the contact
// sheet, batch.json, and each path's path.mp4, made from the output folder's files.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <cmath>
#include <map>

#include "core/atomic_file.h"
#include "core/json_text.h"
#include "core/number_text.h"
#include "core/printable.h"
#include "folder/folder_files.h"
#include "renders/batch/batch_folder.h"
#include "renders/batch/batch_run.h"
#include "renders/external/movie.h"

namespace wangscape {

namespace fs = std::filesystem;
using namespace batch_detail;  // the output folder's files (batch_folder.h)

namespace {

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
  const std::string scene = "scenes/" + t.scene_key + "/";
  if (t.engine == RenderEngine::embree)
    return {scene, work + "embree.log", FolderFiles(scene).scene_file().generic_string()};
  return {scene, work + "povray.log", FolderFiles(work).povray_scene().generic_string()};
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

// A path's frames folder as the assembly leaves it.
enum class PathMovie { frames_to_come, no_ffmpeg, made };

// Each path (its frames folder) whose parts are all done made into paths/FOLDER/path.mp4, once,
// when ffmpeg is on PATH.
std::map<std::string, PathMovie> make_path_movies(const fs::path& dir, const Plan& plan) {
  std::map<std::string, std::pair<double, bool>> paths;  // folder -> fps, every part done
  for (const auto& t : plan.tasks)
    if (t.frames) {
      const auto at = paths.try_emplace(t.frames->folder, t.frames->fps, true).first;
      at->second.second = at->second.second && task_state(dir, t) == State::done;
    }
  std::map<std::string, PathMovie> movies;
  for (const auto& [folder, state] : paths) {
    const fs::path frames = dir / "paths" / folder, movie = frames / "path.mp4";
    movies[folder] = !state.second ? PathMovie::frames_to_come
                     : fs::exists(movie) || write_frames_movie(frames, kPathFramePattern, state.first, movie)
                         ? PathMovie::made
                         : PathMovie::no_ffmpeg;
  }
  return movies;
}

// The gallery's list of the paths and their movies.
std::string movies_html(const std::map<std::string, PathMovie>& movies) {
  if (movies.empty()) return {};
  std::string html = "<h2>Paths</h2>\n<ul>\n";
  for (const auto& [folder, movie] : movies)
    html += "<li><a href=\"paths/" + html_escape(folder) + "/\">" + html_escape(folder) + "</a>" +
            (movie == PathMovie::made        ? " · <a href=\"paths/" + html_escape(folder) + "/path.mp4\">path.mp4</a>"
             : movie == PathMovie::no_ffmpeg ? " (all frames; no ffmpeg on PATH for path.mp4)"
                                             : " (frames still to come)") +
            "</li>\n";
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
  html += movies_html(make_path_movies(dir, plan));
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

}  // namespace wangscape
