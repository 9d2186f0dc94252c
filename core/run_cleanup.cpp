#include "core/run_cleanup.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "core/durable_file.h"
#include "core/error.h"

namespace wangscape {

namespace fs = std::filesystem;

namespace {

struct Registry {
  std::recursive_mutex mutex;
  std::vector<fs::path> temporaries;
  std::vector<pid_t> children;
  std::set<fs::path> scanned_folders;
};

// Never destroyed: the signal thread may still use it while static objects are destroyed.
Registry& registry() {
  static Registry* instance = new Registry;
  return *instance;
}

constexpr int kInterrupts[] = {SIGINT, SIGTERM, SIGHUP};

sigset_t interrupt_signals() {
  sigset_t set;
  sigemptyset(&set);
  for (const int signal_number : kInterrupts) sigaddset(&set, signal_number);
  return set;
}

// The interrupts this run handles: those not ignored when it started (nohup ignores SIGHUP, a
// shell's background job SIGINT; they stay ignored, as the caller asked).
sigset_t handled_interrupts() {
  sigset_t set;
  sigemptyset(&set);
  for (const int signal_number : kInterrupts) {
    struct sigaction current {};
    if (::sigaction(signal_number, nullptr, &current) == 0 && current.sa_handler != SIG_IGN)
      sigaddset(&set, signal_number);
  }
  return set;
}

void remove_quietly(const fs::path& path) {
  // A writer thread may still add a file to a folder being removed: try a few times.
  std::error_code ec;
  for (int attempt = 0; attempt < 5 && fs::symlink_status(path, ec).type() != fs::file_type::not_found; ++attempt)
    fs::remove_all(path, ec);
}

[[noreturn]] void clean_up_and_exit(int signal_number) {
  Registry& r = registry();
  r.mutex.lock();  // never released: the process ends here
  for (const pid_t child : r.children) ::kill(child, SIGTERM);
  // Let them end (up to 2 s) before removing what they may still write.
  for (int wait = 0; wait < 100 && !r.children.empty(); ++wait) {
    std::erase_if(r.children, [](pid_t child) { return ::waitpid(child, nullptr, WNOHANG) != 0; });
    if (!r.children.empty()) ::usleep(20000);
  }
  for (auto it = r.temporaries.rbegin(); it != r.temporaries.rend(); ++it) remove_quietly(*it);
  const char* name = signal_number == SIGINT ? "SIGINT" : signal_number == SIGTERM ? "SIGTERM" : "SIGHUP";
  std::string message = "\nwangscape: interrupted by ";
  message += name;
  message += "; removed this run's unfinished files\n";
  [[maybe_unused]] const auto written = ::write(STDERR_FILENO, message.data(), message.size());
  ::_exit(128 + signal_number);
}

// A pid in a temporary's name, or 0 when `digits` is not one.
pid_t parse_pid(std::string_view digits) {
  long value = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec != std::errc() || end != digits.data() + digits.size() || value <= 0 || value > 0x3fffffff) return 0;
  return static_cast<pid_t>(value);
}

bool process_is_gone(pid_t pid) { return pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH; }

// For ".NAME.ROLE-<pid>": NAME, or empty when `entry` is not such a name.
std::string staged_name(const std::string& entry, const std::string& role, pid_t& pid) {
  const auto dash = entry.rfind("." + role + "-");
  if (entry.size() < 2 || entry[0] != '.' || dash == std::string::npos || dash < 2) return {};
  pid = parse_pid(std::string_view(entry).substr(dash + role.size() + 2));
  return pid != 0 ? entry.substr(1, dash - 1) : std::string();
}

void remove_if_stale(const fs::path& folder, const std::string& entry) {
  std::error_code ec;
  pid_t pid = 0;
  if (entry.starts_with(".tmp-")) {
    const auto dash = entry.find('-', 5);
    if (dash == std::string::npos || dash + 1 == entry.size()) return;
    pid = parse_pid(std::string_view(entry).substr(5, dash - 5));
    if (pid != 0 && process_is_gone(pid)) fs::remove_all(folder / entry, ec);
    return;
  }
  if (!staged_name(entry, "tmp", pid).empty() || !staged_name(entry, "partial", pid).empty()) {
    if (process_is_gone(pid)) fs::remove_all(folder / entry, ec);
    return;
  }
  const std::string old_of = staged_name(entry, "old", pid);
  if (old_of.empty() || !process_is_gone(pid)) return;
  if (fs::symlink_status(folder / old_of, ec).type() == fs::file_type::not_found) {
    fs::rename(folder / entry, folder / old_of, ec);  // the swap was cut short: the old build is all there is
    try {
      if (!ec) sync_folder(folder);  // durably: the old build's files were flushed when it was published
    } catch (const Error&) {         // ignored, as every error here
    }
  } else
    fs::remove_all(folder / entry, ec);
}

}  // namespace

void install_run_cleanup() {
  const sigset_t set = handled_interrupts();
  ::pthread_sigmask(SIG_BLOCK, &set, nullptr);
  ::signal(SIGXFSZ, SIG_IGN);
  std::thread([set] {
    for (;;) {
      int signal_number = 0;
      if (::sigwait(&set, &signal_number) == 0) clean_up_and_exit(signal_number);
    }
  }).detach();
}

void reset_signals_in_child() {
  const sigset_t set = interrupt_signals();
  ::pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
  ::signal(SIGXFSZ, SIG_DFL);
}

void register_temporary(const fs::path& path) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  r.temporaries.push_back(path);
}

void unregister_temporary(const fs::path& path) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  const auto it = std::find(r.temporaries.rbegin(), r.temporaries.rend(), path);
  if (it != r.temporaries.rend()) r.temporaries.erase(std::next(it).base());
}

void register_child(pid_t pid) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  r.children.push_back(pid);
}

void unregister_child(pid_t pid) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  std::erase(r.children, pid);
}

std::unique_lock<std::recursive_mutex> hold_run_cleanup() { return std::unique_lock(registry().mutex); }

void remove_stale_temporaries(const fs::path& folder_in) {
  std::error_code ec;
  const fs::path folder = fs::absolute(folder_in.empty() ? fs::path(".") : folder_in, ec).lexically_normal();
  if (ec) return;
  {
    Registry& r = registry();
    const std::lock_guard lock(r.mutex);
    if (!r.scanned_folders.insert(folder).second) return;
  }
  std::vector<std::string> entries;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.starts_with('.')) entries.push_back(name);
  }
  for (const auto& entry : entries) remove_if_stale(folder, entry);
}

}  // namespace wangscape
