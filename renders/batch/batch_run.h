// Running a batch (renders/batch/batch_file.h) into an output folder, on a local pool of worker
// processes or as a Slurm job array, so that a run can be repeated: each task records the hash
// of its inputs and is skipped when its still exists with that hash. The folder:
//   plan.json            the batch as tasks (written by `batch run`, read by every worker)
//   scenes/<key>/        one scene folder per distinct scene (DEM + scene text), shared by the
//                        tasks that differ only in camera, sun, engine or size
//   work/<id>/           per task: scene.pov with the task's camera and sun over the shared
//                        folder (Library_Path), POV-Ray's log
//   stills/<id>.png      the stills, renamed into place when complete
//   tasks/<id>.json      done record (input hash, seconds, times rendered); .running, .failed
//   logs/                worker and Slurm logs
//   index.html, contact-sheet.png, batch.json   the results (assembled at the end)
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "renders/batch/batch_file.h"

namespace wangscape {

// Where a batch's tasks run: worker processes on this machine, or a Slurm job array.
enum class BatchExecutor { local, slurm };
inline constexpr std::array<BatchExecutor, 2> kBatchExecutors{BatchExecutor::local, BatchExecutor::slurm};

// "local", "slurm": as `--executor` takes them.
std::string_view to_string(BatchExecutor executor);
// The executor `name` names; throws Error("batch run: executor 'NAME' is not known (local, slurm)").
BatchExecutor parse_batch_executor(std::string_view name);
// Every executor's name, in kBatchExecutors' order (for the command line's choices).
std::vector<std::string> batch_executor_names();

struct BatchRunSettings {
  std::filesystem::path batch_file;
  std::filesystem::path out_dir;
  BatchExecutor executor = BatchExecutor::local;
  int workers = 0;   // local: worker processes, 0 = the cores
  int chunk = 0;     // slurm: tasks per array element, 0 = 1 up to 256 tasks, then more
  int throttle = 0;  // slurm: array elements running at once (%), 0 = no limit
  int retries = 1;   // slurm: times failed elements are resubmitted (sbatch reads
                     // SBATCH_PARTITION, SBATCH_ACCOUNT, ... from the environment)
  // What a terminal shows of a run (the tasks and executor, Slurm's submissions and
  // resubmissions, and in run-task each task's outcome); empty: nothing. The library prints nothing.
  std::function<void(const std::string& line)> on_message;
  bool json = false;                                         // plan: a JSON list of tasks
  bool watch = false;                                        // status: report progress until no task is running
  std::vector<int> task_range;                               // run-task: first [count]; empty = assemble the gallery
  std::function<void(int finished, int total)> on_progress;  // tasks done or failed so far
};

struct BatchCounts {
  int done = 0, running = 0, failed = 0, pending = 0;
};

// Expands the batch, writes plan.json, runs every task not yet done and assembles the results;
// returns the tasks' states at the end. Throws Error for a bad batch file or output folder before
// any task starts, when another `batch run` holds the folder, and after the run when some task
// failed (the message names each one with its error and log, a line each).
BatchCounts run_batch(const BatchRunSettings& settings);

// At most this many local worker processes (`--workers`).
inline constexpr int kMaxBatchWorkers = 256;

// A batch's plan.json read back: the base scene and its tasks. A plan is input like any other
// (a worker on another node reads it): its size, nesting, ids, keys and numbers are checked.
struct BatchPlan {
  SceneConfig scene;
  std::vector<BatchTask> tasks;
};
inline constexpr std::uintmax_t kMaxPlanBytes = std::uintmax_t{256} << 20;  // 100,000 tasks are ~80 MB
// Parses plan.json's text; throws Error naming `file`, the task and what was expected.
BatchPlan parse_batch_plan(std::string_view text, const std::filesystem::path& file);

// The plan as text (one line per task) or as JSON (a list of tasks), without running anything.
std::string batch_plan_text(const std::filesystem::path& batch_file, bool json);

// Runs tasks [first, first + count) of DIR/plan.json in this process (what a worker or a
// Slurm array element does), each task's outcome to `on_message` (a line for the worker's log).
// Throws Error naming the tasks that failed.
void run_batch_tasks(const std::filesystem::path& dir, int first, int count,
                     const std::function<void(const std::string& line)>& on_message = {});
// `batch run-task`: settings.task_range of settings.out_dir, or assemble_batch when it is empty.
void run_batch_tasks(const BatchRunSettings& settings);

// Each task's state from the files (whichever executor ran it); `report` gets one line per task.
BatchCounts batch_status(const std::filesystem::path& dir, std::string* report = nullptr);
// `batch status`: the report of settings.out_dir; with settings.watch, on_progress is called
// until no task is running first.
std::string batch_status_text(const BatchRunSettings& settings);

// Writes DIR/index.html, DIR/contact-sheet.png and DIR/batch.json from the files.
void assemble_batch(const std::filesystem::path& dir);

}  // namespace wangscape
