// Outputs are written atomically: to a temporary file beside the target, renamed into
// place only when complete, so a failed run never leaves a partial file; and durably
// (core/durable_file.h): the temporary is flushed to disk before the rename and the folder
// after it, so a power cut leaves the old file or the new one, never a truncated one. Errors
// are wangscape::Error naming the file.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"

namespace wangscape {

class AtomicFile {
 public:
  // Opens ".<name>.tmp-<pid>" beside `path` for writing (binary): a name no reader of the folder
  // takes for content (its extension is not the target's); the pid lets a later run tell a dead
  // process's leftovers. Throws Error naming `path`.
  explicit AtomicFile(std::filesystem::path path);
  // Removes the temporary file unless commit() succeeded.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return stream_; }
  const std::filesystem::path& temp_path() const { return temp_path_; }
  const std::filesystem::path& path() const { return path_; }

  // Flushes, closes, flushes to disk and renames into place, then flushes the folder. Throws
  // Error if any write or flush failed.
  void commit();

 private:
  std::filesystem::path path_;
  std::filesystem::path temp_path_;
  std::ofstream stream_;
  bool committed_ = false;
};

// Writes `contents` to `path` atomically.
void write_file_atomically(const std::filesystem::path& path, const std::string& contents);

// For outputs produced by another library (OIIO, a renderer): a temporary path named as
// AtomicFile's (".<name>.tmp-<pid>"), renamed into place by commit(); removed on destruction
// otherwise. The temporary does not carry the target's extension: tell the writer the format
// (OIIO's create() by the target's name, POV-Ray's +FN and stdout, Blender's file_format).
class AtomicPath {
 public:
  explicit AtomicPath(std::filesystem::path path);
  ~AtomicPath();
  AtomicPath(const AtomicPath&) = delete;
  AtomicPath& operator=(const AtomicPath&) = delete;
  const std::filesystem::path& temp_path() const { return temp_path_; }
  void commit();

 private:
  std::filesystem::path path_;
  std::filesystem::path temp_path_;
  bool committed_ = false;
};

}  // namespace wangscape
