// A folder written whole or not at all (a scene folder's build, a folder of tiles): staged as
// ".<name>.partial-<pid>" beside the target and published by one rename, or by one exchange with
// an earlier folder of that name, so a reader, or a kill at any moment, finds the old folder or
// the new one, never none and never a part. Durably (core/durable_file.h): every file and folder
// staged is flushed to disk before the rename, the folders around it after. Errors are
// wangscape::Error naming the folder.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace wangscape {

class StagedFolder {
 public:
  // Makes the target's missing parent folders and the staging folder beside it (registered with
  // core/run_cleanup.h, so an interrupted run removes it), after removing what dead runs left
  // there. Throws Error naming the staging folder when it cannot be made (and removes the parent
  // folders it made).
  explicit StagedFolder(const std::filesystem::path& target);
  // Unless published: removes the staging folder and the parent folders it made.
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  const std::filesystem::path& path() const { return staging_; }   // where the files go until publish()
  const std::filesystem::path& target() const { return target_; }  // absolute

  // Replaces the target, whole, by the staged folder: one rename when there is none, else one
  // exchange of the two folders (renameat2 RENAME_EXCHANGE), the earlier one removed after.
  // Where the filesystem cannot exchange, the earlier folder is renamed aside first and `warning`
  // told (in between, for a moment, there is none; a run killed there puts it back on the next
  // write). Throws Error naming the target; the target is then as it was.
  void publish(const std::function<void(const std::string&)>& warning = {});

 private:
  std::filesystem::path target_, staging_;
  std::vector<std::filesystem::path> made_;  // parent folders this made, nearest first
  bool published_ = false;
};

}  // namespace wangscape
