#include "renders/povray_render.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "exporters/atomic_file.h"

namespace wangscape {

namespace {

std::string read_tail(const std::filesystem::path& path, std::size_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::size_t>(in.tellg());
  const auto start = size > max_bytes ? size - max_bytes : 0;
  in.seekg(static_cast<std::streamoff>(start));
  std::string text(size - start, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  return text;
}

// The last `count` non-empty lines of a log (POV-Ray ends progress lines with '\r').
std::string last_lines(const std::string& text, int count) {
  std::vector<std::string> lines;
  std::string line;
  for (char c : text) {
    if (c == '\n' || c == '\r') {
      if (line.find_first_not_of(" \t") != std::string::npos) lines.push_back(line);
      line.clear();
    } else {
      line.push_back(c);
    }
  }
  if (line.find_first_not_of(" \t") != std::string::npos) lines.push_back(line);
  std::string out;
  const auto first =
      lines.size() > static_cast<std::size_t>(count) ? lines.size() - static_cast<std::size_t>(count) : 0;
  for (auto i = first; i < lines.size(); ++i) out += "\n  | " + lines[i];
  return out;
}

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
  if (program.find('/') != std::string::npos)
    return ::access(program.c_str(), X_OK) == 0 ? std::filesystem::path(program) : std::filesystem::path();
  const char* path_env = std::getenv("PATH");
  std::stringstream dirs(path_env ? path_env : "/usr/local/bin:/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) dir = ".";
    const auto candidate = std::filesystem::path(dir) / program;
    if (::access(candidate.c_str(), X_OK) == 0 && !std::filesystem::is_directory(candidate)) return candidate;
  }
  return {};
}

PovrayRenderResult render_povray(const std::filesystem::path& dir_in, const PovrayRenderOptions& options) {
  std::error_code ec;
  const auto dir = std::filesystem::absolute(dir_in, ec);
  if (!std::filesystem::is_regular_file(dir / "scene.ini"))
    throw RenderError("render: '" + dir_in.string() + "' has no scene.ini (write one with `wangscape build`)");
  const auto povray = find_povray(options.executable);
  if (povray.empty()) {
    const char* env = std::getenv("WANGSCAPE_POVRAY");
    const std::string wanted = !options.executable.empty() ? options.executable : (env && *env) ? env : "povray";
    throw RenderError("render: POV-Ray ('" + wanted +
                      "') is not installed or not in PATH; install it (apt install povray) or set WANGSCAPE_POVRAY");
  }

  PovrayRenderResult result{dir / options.image_name, dir / "povray.log", 0};
  AtomicPath image(result.image);
  AtomicPath log(result.log);

  // Everything the child needs, prepared before fork (only async-signal-safe calls after it).
  std::vector<std::string> args{
      povray.string(),    "scene.ini", "+O" + image.temp_path().filename().string(), "+FN", "-D", "-P",
      "+L" + dir.string()};
  if (options.width > 0) args.push_back("+W" + std::to_string(options.width));
  if (options.height > 0) args.push_back("+H" + std::to_string(options.height));
  if (options.threads > 0) args.push_back("+WT" + std::to_string(options.threads));
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string dir_string = dir.string();
  const std::string log_string = log.temp_path().string();

  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) throw RenderError("render: cannot start POV-Ray: " + std::string(std::strerror(errno)));
  if (pid == 0) {
    const int fd = ::open(log_string.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || ::chdir(dir_string.c_str()) != 0) ::_exit(126);
    ::dup2(fd, STDOUT_FILENO);
    ::dup2(fd, STDERR_FILENO);
    ::close(fd);
    const int null_fd = ::open("/dev/null", O_RDONLY);
    if (null_fd >= 0) ::dup2(null_fd, STDIN_FILENO);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }

  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR)
      throw RenderError("render: lost the POV-Ray process: " + std::string(std::strerror(errno)));
    if (options.on_progress) {
      std::uint64_t pixels = 0, total = 0;
      parse_progress(read_tail(log.temp_path(), 4096), pixels, total);
      options.on_progress(pixels, total);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const bool log_written = std::filesystem::exists(log.temp_path());
  if (log_written) log.commit();
  const bool exited_ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (!exited_ok || !std::filesystem::exists(image.temp_path())) {
    const std::string how = WIFEXITED(status)     ? "exited with status " + std::to_string(WEXITSTATUS(status))
                            : WIFSIGNALED(status) ? "was killed by signal " + std::to_string(WTERMSIG(status))
                                                  : "failed";
    const std::string tail = log_written ? last_lines(read_tail(result.log, 16384), 8) : std::string();
    throw RenderError("render: POV-Ray " + how + " rendering '" + (dir / "scene.pov").string() + "'" +
                      (exited_ok ? " without writing an image" : "") + "; log " + result.log.string() +
                      (tail.empty() ? std::string() : ", last lines:" + tail));
  }
  image.commit();
  return result;
}

}  // namespace wangscape
