#include "core/staged_folder.h"

#include <fcntl.h>  // AT_FDCWD; renameat2 and RENAME_EXCHANGE come from <cstdio> (glibc 2.28+, _GNU_SOURCE)
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/durable_file.h"
#include "core/error.h"
#include "core/run_cleanup.h"

namespace wangscape {

namespace fs = std::filesystem;

namespace {

// The folder a target is staged in and the one an earlier folder is moved to during the swap.
fs::path sibling(const fs::path& target, const char* role) {
  std::string name(1, '.');  // appended piecewise: GCC 12 warns falsely on "." + ...
  name += target.filename().string();
  name += '.';
  name += role;
  name += '-';
  name += std::to_string(::getpid());
  return target.parent_path() / name;
}

}  // namespace

StagedFolder::StagedFolder(const fs::path& target) : target_(fs::absolute(target).lexically_normal()) {
  if (target_.filename().empty()) target_ = target_.parent_path();
  std::error_code ec;
  for (fs::path p = target_.parent_path(); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    made_.push_back(p);
    if (p == p.parent_path()) break;
  }
  fs::create_directories(target_.parent_path(), ec);
  remove_stale_temporaries(target_.parent_path());
  staging_ = sibling(target_, "partial");
  fs::remove_all(staging_, ec);
  register_temporary(staging_);
  if (!fs::create_directory(staging_, ec) || ec) {
    unregister_temporary(staging_);
    const std::string why = ec.message();
    for (const fs::path& p : made_) fs::remove(p, ec);  // only while empty
    throw Error(staging_, "", "cannot create the staging folder beside the output folder: " + why);
  }
}

StagedFolder::~StagedFolder() {
  if (published_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
  unregister_temporary(staging_);
  for (const fs::path& p : made_) fs::remove(p, ec);  // only while empty
}

void StagedFolder::publish(const std::function<void(const std::string&)>& warning) {
  sync_tree(staging_);
  auto uninterrupted = hold_run_cleanup();  // an interrupt waits until the swap is done
  std::error_code ec;
  if (fs::exists(target_, ec)) {
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) == 0) {
      uninterrupted.unlock();  // staging (still a registered temporary) now holds the earlier folder
      sync_folder(target_.parent_path());
      fs::remove_all(staging_, ec);
      unregister_temporary(staging_);
      published_ = true;
      return;
    }
    if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP)
      throw Error(target_, "", std::string("cannot swap the new folder in: ") + std::strerror(errno));
    if (warning)
      warning("this filesystem cannot exchange two folders at once (" + std::string(std::strerror(errno)) +
              "); replacing " + target_.string() + " with two renames");
    const fs::path old = sibling(target_, "old");
    fs::remove_all(old, ec);
    fs::rename(target_, old, ec);
    if (ec) throw Error(target_, "", "cannot move the earlier folder aside: " + ec.message());
    fs::rename(staging_, target_, ec);
    if (ec) {
      std::error_code restore;
      fs::rename(old, target_, restore);
      throw Error(target_, "", "cannot move the new folder into place: " + ec.message());
    }
    unregister_temporary(staging_);
    register_temporary(old);
    uninterrupted.unlock();
    sync_folder(target_.parent_path());
    fs::remove_all(old, ec);
    unregister_temporary(old);
  } else {
    fs::rename(staging_, target_, ec);
    if (ec) throw Error(target_, "", "cannot create the folder: " + ec.message());
    unregister_temporary(staging_);
    sync_folder(target_.parent_path());
  }
  // The folders this made hold their entries durably too (the nearest, the target's parent, is
  // flushed above).
  for (const fs::path& p : made_) sync_folder(p.parent_path());
  published_ = true;
}

}  // namespace wangscape
