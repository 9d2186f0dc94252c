// Durable publishing: what a rename publishes survives a power cut or a kernel crash, not only a
// killed process. ext4 and XFS may commit a rename before the data of the file it names, so after
// a reboot the final name could hold an empty or truncated file. As git's core.fsync and SQLite's
// journal do: before a rename publishes a file, its data is flushed (fsync); a folder published by
// one rename (a staging folder) is flushed with every file and folder in it first; after the
// rename, the folder the rename wrote into is flushed.
//
// Every publisher goes through these: AtomicFile and AtomicPath (core/atomic_file.h), the scene
// folder's swap (folder/scene_folder.h), the cleanup that puts a cut-short swap's old build
// back (core/run_cleanup.h). Errors are wangscape::Error naming the file or folder. Thread safe.
#pragma once

#include <filesystem>

namespace wangscape {

// Flushes the data and the size of the file open as `fd` to the disk (fsync). Throws Error naming
// `path` (what `fd` was opened as) when the disk reports a failure (EIO, ENOSPC, EDQUOT).
void sync_file(int fd, const std::filesystem::path& path);

// Opens `path` and flushes it as above: for a file another library or a child process wrote.
void sync_file(const std::filesystem::path& path);

// Flushes a folder's entries (the names created, renamed or removed in it). Throws Error naming
// the folder; a filesystem that cannot flush a folder at all (EINVAL, ENOTSUP) is not an error.
void sync_folder(const std::filesystem::path& folder);

// Flushes every regular file and folder under `root`, each folder after its entries, `root`
// last: a staging folder before the rename that publishes it whole. Symbolic links are not
// followed. Throws Error naming the first file or folder that cannot be flushed.
void sync_tree(const std::filesystem::path& root);

}  // namespace wangscape
