#include "core/atomic_file.h"

#include <unistd.h>

#include <system_error>

#include "core/durable_file.h"
#include "core/run_cleanup.h"

namespace wangscape {

namespace {
// ".NAME.tmp-<pid>", which no reader of the folder takes for content (hidden, and its extension
// is the pid, not .csv or .png), even when a killed run left it. Also registers the temporary
// for removal on an interrupt, after clearing the folder of dead runs' temporaries.
std::filesystem::path temporary_beside(const std::filesystem::path& path) {
  remove_stale_temporaries(path.parent_path());
  std::filesystem::path temp = path;
  // Appended, not "." + string: GCC 12 warns (-Wrestrict) on that operator+ where it is inlined.
  std::string name = ".";
  name += path.filename().string();
  name += ".tmp-";
  name += std::to_string(::getpid());
  temp.replace_filename(name);
  register_temporary(temp);
  return temp;
}

// Publishes the complete temporary `from` as `to` durably (core/durable_file.h): its data
// flushed before the rename, the folder after it.
void rename_into_place(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::error_code ec;
  try {
    sync_file(from);
  } catch (const Error& e) {
    std::filesystem::remove(from, ec);
    unregister_temporary(from);
    throw Error(to, "", e.message());
  }
  std::filesystem::rename(from, to, ec);
  if (ec) {
    std::filesystem::remove(from, ec);
    unregister_temporary(from);
    throw Error("cannot write '" + to.string() + "': rename failed");
  }
  unregister_temporary(from);
  sync_folder(to.parent_path());
}

void remove_temporary(const std::filesystem::path& temp) {
  std::error_code ec;
  std::filesystem::remove(temp, ec);
  unregister_temporary(temp);
}
}  // namespace

AtomicFile::AtomicFile(std::filesystem::path path) : path_(std::move(path)), temp_path_(temporary_beside(path_)) {
  stream_.open(temp_path_, std::ios::binary | std::ios::trunc);
  if (!stream_) {
    unregister_temporary(temp_path_);
    throw Error("cannot write '" + path_.string() + "': cannot create a file in its folder");
  }
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  stream_.close();
  remove_temporary(temp_path_);
}

void AtomicFile::commit() {
  stream_.flush();
  const bool ok = static_cast<bool>(stream_);
  stream_.close();
  if (!ok || stream_.fail()) throw Error("cannot write '" + path_.string() + "': write failed (disk full?)");
  rename_into_place(temp_path_, path_);
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, const std::string& contents) {
  AtomicFile file(path);
  file.stream().write(contents.data(), static_cast<std::streamsize>(contents.size()));
  file.commit();
}

AtomicPath::AtomicPath(std::filesystem::path path) : path_(std::move(path)), temp_path_(temporary_beside(path_)) {}

AtomicPath::~AtomicPath() {
  if (committed_) return;
  remove_temporary(temp_path_);
}

void AtomicPath::commit() {
  if (!std::filesystem::exists(temp_path_)) throw Error("cannot write '" + path_.string() + "': nothing was written");
  rename_into_place(temp_path_, path_);
  committed_ = true;
}

}  // namespace wangscape
