#include "renders/external/child_process.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "core/run_cleanup.h"

namespace wangscape {

std::filesystem::path find_program(const std::string& program) {
  if (program.empty()) return {};
  const auto executable = [](const std::filesystem::path& p) {
    return ::access(p.c_str(), X_OK) == 0 && !std::filesystem::is_directory(p);
  };
  if (program.find('/') != std::string::npos) return executable(program) ? std::filesystem::path(program) : "";
  const char* path_env = std::getenv("PATH");
  std::stringstream dirs(path_env ? path_env : "/usr/local/bin:/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const auto candidate = std::filesystem::path(dir.empty() ? "." : dir) / program;
    if (executable(candidate)) return candidate;
  }
  return {};
}

std::string ChildExit::describe() const {
  return exited ? "exited with status " + std::to_string(status) : "was killed by signal " + std::to_string(status);
}

ChildExit run_logged(const std::vector<std::string>& args, const std::filesystem::path& log,
                     const std::filesystem::path& working_dir, const std::function<void()>& while_running,
                     const std::filesystem::path& output) {
  // Everything the child needs, prepared before fork (only async-signal-safe calls after it).
  std::vector<std::string> owned = args;
  std::vector<char*> argv;
  for (auto& a : owned) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string log_string = log.string();
  const std::string dir_string = working_dir.string();
  const std::string output_string = output.string();

  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("cannot start '" + args.at(0) + "': " + std::strerror(errno));
  if (pid == 0) {
    reset_signals_in_child();
    const int fd = ::open(log_string.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd < 0) ::_exit(126);
    if (!dir_string.empty() && ::chdir(dir_string.c_str()) != 0) ::_exit(126);
    ::dup2(fd, STDERR_FILENO);
    if (output_string.empty()) {
      ::dup2(fd, STDOUT_FILENO);
    } else {
      const int out_fd = ::open(output_string.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (out_fd < 0) ::_exit(126);
      ::dup2(out_fd, STDOUT_FILENO);
      ::close(out_fd);
    }
    ::close(fd);
    const int null_fd = ::open("/dev/null", O_RDONLY);
    if (null_fd >= 0) ::dup2(null_fd, STDIN_FILENO);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  register_child(pid);  // stopped if this run is interrupted
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, while_running ? WNOHANG : 0);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) {
      unregister_child(pid);
      throw std::runtime_error("lost the process '" + args.at(0) + "': " + std::strerror(errno));
    }
    if (done == 0) {
      while_running();
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
  }
  unregister_child(pid);
  ChildExit result;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.exited = WIFEXITED(status);
  result.status = result.exited ? WEXITSTATUS(status) : WIFSIGNALED(status) ? WTERMSIG(status) : -1;
  return result;
}

std::string read_log_tail(const std::filesystem::path& path, std::size_t max_bytes) {
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

std::string last_log_lines(const std::filesystem::path& path, int count) {
  std::vector<std::string> lines;
  std::string line;
  const auto flush = [&] {
    if (line.find_first_not_of(" \t") != std::string::npos) lines.push_back(line);
    line.clear();
  };
  for (const char c : read_log_tail(path, 16384)) {
    if (c == '\n' || c == '\r')
      flush();
    else
      line.push_back(c);
  }
  flush();
  std::string quoted;
  const auto first =
      lines.size() > static_cast<std::size_t>(count) ? lines.size() - static_cast<std::size_t>(count) : 0;
  for (auto i = first; i < lines.size(); ++i) quoted += "\n  | " + lines[i];
  return quoted;
}

std::map<int, std::filesystem::path> numbered_frames(const std::filesystem::path& dir) {
  std::map<int, std::filesystem::path> frames;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() < 6 || name.size() > 14 || name[0] != 'f' || !name.ends_with(".png")) continue;
    const std::string digits = name.substr(1, name.size() - 5);
    if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) continue;
    frames[std::stoi(digits)] = entry.path();
  }
  return frames;
}

}  // namespace wangscape
