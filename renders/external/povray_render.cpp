#include "renders/external/povray_render.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/atomic_file.h"
#include "exporters/povray_writer.h"
#include "renders/external/child_process.h"

namespace wangscape {

namespace {

// Finds the last "Rendered <done> of <total> pixels" in `text`.
bool parse_progress(const std::string& text, std::uint64_t& done, std::uint64_t& total) {
  const auto at = text.rfind("Rendered ");
  if (at == std::string::npos) return false;
  unsigned long long d = 0, t = 0;
  if (std::sscanf(text.c_str() + at, "Rendered %llu of %llu pixels", &d, &t) != 2) return false;
  done = d;
  total = t;
  return true;
}

}  // namespace

std::filesystem::path find_povray(const std::string& executable) {
  std::string program = executable;
  if (program.empty()) {
    const char* env = std::getenv("WANGSCAPE_POVRAY");
    program = (env && *env) ? env : "povray";
  }
  return find_program(program);
}

PovrayRenderResult render_povray(const std::filesystem::path& dir_in, const PovrayRenderOptions& options) {
  std::error_code ec;
  const auto dir = std::filesystem::absolute(dir_in, ec);
  if (!std::filesystem::is_regular_file(dir / "scene.ini"))
    throw Error("render: '" + dir_in.string() + "' has no scene.ini (write one with `wangscape build`)");
  const auto povray = find_povray(options.executable);
  if (povray.empty()) {
    const char* env = std::getenv("WANGSCAPE_POVRAY");
    const std::string wanted = !options.executable.empty() ? options.executable : (env && *env) ? env : "povray";
    throw Error("render: POV-Ray ('" + wanted +
                "') is not installed or not in PATH; install it (apt install povray) or set WANGSCAPE_POVRAY");
  }

  PovrayRenderResult result{dir / options.image_name, dir / "povray.log", 0};
  AtomicPath image(result.image);
  AtomicPath log(result.log);

  // The PNG goes to stdout (+O-), captured in a temporary renamed into place only when POV-Ray
  // succeeds: given a file name, POV-Ray appends ".png" to any name not ending in it, so a killed
  // run would leave a ".png" behind. POV-Ray rejoins its arguments and splits them at spaces:
  // paths go quoted.
  const bool animation = options.frames > 0;
  std::vector<std::string> args{povray.string(), "scene.ini", "+FN", "-D", "-P", "+L" + povray_quoted_path(dir)};
  if (!options.input_file.empty()) args.push_back("+I" + povray_quoted_path(options.input_file));
  if (animation) {
    // Frames 0 .. N - 1, into FRAMES_DIR/f<k>.png (a final frame of at least 1, so that POV-Ray
    // numbers even a single frame's file; +EF renders only the frames asked).
    args.push_back("+KFI0");
    args.push_back("+KFF" + std::to_string(std::max(options.frames - 1, 1)));
    args.push_back("+SF0");
    args.push_back("+EF" + std::to_string(options.frames - 1));
    args.push_back("+O" + povray_quoted_path(options.frames_dir / "f.png"));
  } else {
    args.push_back("+O-");
  }
  if (options.width > 0) args.push_back("+W" + std::to_string(options.width));
  if (options.height > 0) args.push_back("+H" + std::to_string(options.height));
  if (options.threads > 0) args.push_back("+WT" + std::to_string(options.threads));
  // A frame is complete once POV-Ray has begun writing the next (or has exited).
  const auto hand_over_frames = [&](bool all) {
    auto frames = numbered_frames(options.frames_dir);
    if (!all && !frames.empty()) frames.erase(std::prev(frames.end()));
    for (const auto& [k, file] : frames)
      if (k < options.frames && options.on_frame) options.on_frame(k, file);
  };
  const auto while_running = [&] {
    std::uint64_t pixels = 0, total = 0;
    if (options.on_progress && parse_progress(read_log_tail(log.temp_path(), 4096), pixels, total))
      options.on_progress(pixels, total);
    if (animation) hand_over_frames(false);
  };
  ChildExit exit;
  try {
    exit = run_logged(args, log.temp_path(), dir,
                      options.on_progress || animation ? std::function<void()>(while_running) : nullptr,
                      animation ? std::filesystem::path() : image.temp_path());
  } catch (const std::runtime_error& e) {
    throw Error("render: POV-Ray: " + std::string(e.what()));
  }
  result.seconds = exit.seconds;

  const bool log_written = std::filesystem::exists(log.temp_path());
  if (log_written) log.commit();
  const bool exited_ok = exit.exited && exit.status == 0;
  if (animation) {
    if (exited_ok) hand_over_frames(true);
    const bool every_frame = numbered_frames(options.frames_dir).empty();  // all handed over
    if (exited_ok && every_frame) {
      result.image.clear();
      return result;
    }
  }
  std::error_code size_error;
  const bool image_written = !animation && std::filesystem::file_size(image.temp_path(), size_error) > 0 && !size_error;
  if (!exited_ok || !image_written) {
    const std::string how = exit.describe();
    const std::string tail = log_written ? last_log_lines(result.log, 8) : std::string();
    const std::string input = options.input_file.empty() ? kPovraySceneFile : options.input_file;
    throw Error("render: POV-Ray " + how + " rendering '" + (dir / input).string() + "'" +
                (exited_ok ? " without writing an image" : "") + "; log " + result.log.string() +
                (tail.empty() ? std::string() : ", last lines:" + tail));
  }
  image.commit();
  return result;
}

}  // namespace wangscape
