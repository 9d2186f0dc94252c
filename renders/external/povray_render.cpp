#include "renders/external/povray_render.h"

#include <unistd.h>

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
  std::vector<std::string> args{povray.string(), "scene.ini", "+O-", "+FN", "-D", "-P", "+L" + povray_quoted_path(dir)};
  if (options.width > 0) args.push_back("+W" + std::to_string(options.width));
  if (options.height > 0) args.push_back("+H" + std::to_string(options.height));
  if (options.threads > 0) args.push_back("+WT" + std::to_string(options.threads));
  const auto report_progress = [&] {
    std::uint64_t pixels = 0, total = 0;
    if (parse_progress(read_log_tail(log.temp_path(), 4096), pixels, total)) options.on_progress(pixels, total);
  };
  ChildExit exit;
  try {
    exit = run_logged(args, log.temp_path(), dir,
                      options.on_progress ? std::function<void()>(report_progress) : nullptr, image.temp_path());
  } catch (const std::runtime_error& e) {
    throw Error("render: POV-Ray: " + std::string(e.what()));
  }
  result.seconds = exit.seconds;

  const bool log_written = std::filesystem::exists(log.temp_path());
  if (log_written) log.commit();
  const bool exited_ok = exit.exited && exit.status == 0;
  std::error_code size_error;
  const bool image_written = std::filesystem::file_size(image.temp_path(), size_error) > 0 && !size_error;
  if (!exited_ok || !image_written) {
    const std::string how = exit.describe();
    const std::string tail = log_written ? last_log_lines(result.log, 8) : std::string();
    throw Error("render: POV-Ray " + how + " rendering '" + (dir / "scene.pov").string() + "'" +
                (exited_ok ? " without writing an image" : "") + "; log " + result.log.string() +
                (tail.empty() ? std::string() : ", last lines:" + tail));
  }
  image.commit();
  return result;
}

}  // namespace wangscape
