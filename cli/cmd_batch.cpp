// wangscape batch plan|example|run|status|run-task (hidden: what workers run): renders/batch/batch_run.h.
#include <cstdio>
#include <iostream>
#include "cli/command.h"
#include "cli/progress.h"
#include "renders/batch/batch_run.h"

namespace wangscape::cli {

void register_batch_command(CLI::App& app, const GlobalOptions& global) {
  auto* batch = app.add_subcommand("batch", "Stills over DEMs x viewpoints x suns x engines")->require_subcommand(1);
  auto s = std::make_shared<BatchRunSettings>();
  auto* plan = batch->add_subcommand("plan", "Print the tasks a batch file expands to (runs nothing)");
  plan->add_option("batch", s->batch_file, "Batch file")->required();
  plan->add_flag("--json", s->json, "A JSON list of tasks");
  plan->callback([=] { std::cout << batch_plan_text(s->batch_file, s->json); });
  batch->add_subcommand("example", "Print a small batch file")->callback([] { std::cout << example_batch_text(); });
  auto* run = batch->add_subcommand("run", "Render every still of a batch not yet done into --out DIR");
  run->add_option("batch", s->batch_file, "Batch file")->required();
  run->add_option("--out", s->out_dir, "Output folder")->required();
  auto executor = std::make_shared<std::string>("local");
  run->add_option("--executor", *executor, "local or slurm")->check(CLI::IsMember(batch_executor_names()));
  run->add_option("--workers", s->workers, "Local worker processes (default: the cores)")
      ->check(CLI::Range(1, kMaxBatchWorkers));
  // Ranges with their real bounds (CLI11's PositiveNumber printed the largest double, 309 digits).
  run->add_option("--chunk", s->chunk, "Slurm: tasks per array element")->check(CLI::Range(1, kMaxBatchTasks));
  run->add_option("--throttle", s->throttle, "Slurm: array elements running at once")
      ->check(CLI::Range(1, kMaxBatchTasks));
  run->add_option("--retries", s->retries, "Slurm: resubmissions of failed elements")
      ->check(CLI::Range(0, kMaxBatchRetries));
  run->callback([=, &global] {
    s->executor = parse_batch_executor(*executor);
    if (chatty(global))
      s->on_message = [](const std::string& line) { std::fprintf(stderr, "wangscape: %s\n", line.c_str()); };
    const WriteReport report(global.quiet);
    const BatchCounts counts = run_batch(*s);  // failures end in the error instead, which names them
    report.wrote(s->out_dir,
                 std::to_string(counts.done) + " stills, 0 failed, gallery " + (s->out_dir / "index.html").string());
  });
  auto* status = batch->add_subcommand("status", "Done / running / failed / pending per task of DIR");
  status->add_option("dir", s->out_dir, "Batch output folder")->required();
  status->add_flag("--progress", s->watch, "On a terminal: a bar until no task is running");
  status->callback([=] { std::cout << batch_status_text(*s); });
  // The examples' run renders four stills of the default scene (half a minute on two cores).
  set_help_footer(plan, "nothing: the tasks on stdout",
                  {"wangscape batch example > batch.toml", "wangscape batch plan batch.toml",
                   "wangscape batch plan batch.toml --json"});
  set_help_footer(batch->get_subcommand("example"), "the batch file on stdout",
                  {"wangscape batch example > batch.toml", "wangscape batch plan batch.toml"});
  set_help_footer(run,
                  "the folder --out: a scene folder and its still per task, the logs, and the gallery index.html; "
                  "a run again renders only what is not done",
                  {"wangscape batch example > batch.toml", "wangscape batch run batch.toml --out stills",
                   "wangscape batch run batch.toml --out stills --workers 1"});
  set_help_footer(status, "nothing: one line per task on stdout",
                  {"wangscape batch example > batch.toml", "wangscape batch run batch.toml --out stills",
                   "wangscape batch status stills"});
  set_help_footer(batch, "see each command's --help (docs/batch-file.md)",
                  {"wangscape batch example > batch.toml", "wangscape batch plan batch.toml",
                   "wangscape batch run batch.toml --out stills"});
  // A worker's lines go to its log (logs/<id>.log, Slurm's), --quiet or not.
  auto* task = batch->add_subcommand("run-task")->group("")->callback([=] {
    s->on_message = [](const std::string& line) { std::printf("%s\n", line.c_str()); };
    run_batch_tasks(*s);
  });
  task->add_option("dir", s->out_dir)->required();
  task->add_option("tasks", s->task_range, "FIRST [COUNT]; none: assemble the gallery")->expected(0, 2);
  // The bar of `run` and `status --progress` (only on a terminal, never with --quiet).
  auto bar = std::make_shared<std::unique_ptr<Progress>>();
  s->on_progress = [bar, &global](int done, int total) {
    if (!*bar) *bar = std::make_unique<Progress>("stills", total, global.quiet);
    (*bar)->update(done);
    if (done >= total) bar->reset();
  };
}

}  // namespace wangscape::cli
