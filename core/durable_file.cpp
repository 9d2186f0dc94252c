#include "core/durable_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>
#include <vector>

#include "core/error.h"

namespace wangscape {

namespace {

// A descriptor closed on every path out.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

int open_for_sync(const std::filesystem::path& path, int flags, const char* what) {
  int fd = -1;
  do fd = ::open(path.c_str(), flags | O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  while (fd < 0 && errno == EINTR);
  if (fd < 0)
    throw Error(path, "", std::string("cannot open the ") + what + " to flush it to disk: " + std::strerror(errno));
  return fd;
}

// fsync, retried when a signal interrupts it. Returns 0 or the errno.
int fsync_errno(int fd) {
  while (::fsync(fd) != 0)
    if (errno != EINTR) return errno;
  return 0;
}

}  // namespace

void sync_file(int fd, const std::filesystem::path& path) {
  if (const int error = fsync_errno(fd); error != 0)
    throw Error(path, "", std::string("cannot flush the file to disk: ") + std::strerror(error));
}

void sync_file(const std::filesystem::path& path) {
  const Descriptor fd(open_for_sync(path, 0, "file"));
  sync_file(fd.get(), path);
}

void sync_folder(const std::filesystem::path& folder_in) {
  const std::filesystem::path folder = folder_in.empty() ? std::filesystem::path(".") : folder_in;
  const Descriptor fd(open_for_sync(folder, O_DIRECTORY, "folder"));
  const int error = fsync_errno(fd.get());
  if (error != 0 && error != EINVAL && error != ENOTSUP && error != ENOSYS)
    throw Error(folder, "", std::string("cannot flush the folder to disk: ") + std::strerror(error));
}

void sync_tree(const std::filesystem::path& root) {
  namespace fs = std::filesystem;
  std::vector<fs::path> folders{root};  // in the order found: parents before their children
  std::error_code ec;
  for (fs::recursive_directory_iterator it(root, ec), end; it != end; it.increment(ec)) {
    if (ec) break;
    const fs::file_type type = it->symlink_status(ec).type();
    if (type == fs::file_type::directory)
      folders.push_back(it->path());
    else if (type == fs::file_type::regular)
      sync_file(it->path());
  }
  if (ec) throw Error(root, "", "cannot list the folder to flush it to disk: " + ec.message());
  for (auto it = folders.rbegin(); it != folders.rend(); ++it) sync_folder(*it);
}

}  // namespace wangscape
