// What this run created and has not published yet (temporary files, staging folders) and the
// child processes it runs, so an interrupted run (SIGINT, SIGTERM, SIGHUP) leaves nothing
// behind, and a later run can remove what a killed one (SIGKILL, power loss) left.
//
// install_run_cleanup() blocks those signals in every thread and waits for them in one thread
// of its own (sigwait), so no work happens inside a signal handler. That thread removes every
// registered path, stops the registered children and ends the process with 128 + the signal
// (130 for SIGINT, 143 for SIGTERM). Thread safe.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <mutex>

namespace wangscape {

// Call first in main, before any thread starts (threads inherit the blocked signals). Also
// ignores SIGXFSZ, so a write beyond the file-size limit fails (EFBIG) and is reported as an
// error instead of killing the process with a half-written file.
void install_run_cleanup();

// Between fork and exec in a child: restores the default signal handling the child's program
// expects (unblocks the signals above, SIGXFSZ default). Async-signal-safe.
void reset_signals_in_child();

// A path (file or folder) removed if the run is interrupted while it is registered.
void register_temporary(const std::filesystem::path& path);
void unregister_temporary(const std::filesystem::path& path);

// A child process sent SIGTERM if the run is interrupted while it is registered.
void register_child(pid_t pid);
void unregister_child(pid_t pid);

// Held while a sequence of renames must complete as a whole (a folder swap): an interrupt
// waits until it is released.
std::unique_lock<std::recursive_mutex> hold_run_cleanup();

// Removes from `folder` what runs that no longer exist left there: ".NAME.tmp-<pid>" and
// ".tmp-<pid>-NAME" files, ".NAME.partial-<pid>" staging folders, and ".NAME.old-<pid>" earlier builds (moved back to
// NAME when NAME is missing, as the swap was cut short). A pid is dead only when kill(pid, 0)
// fails with ESRCH: files of live processes, this one included, are never touched. Each folder
// is scanned once per run; errors are ignored (a later run tries again).
void remove_stale_temporaries(const std::filesystem::path& folder);

}  // namespace wangscape
