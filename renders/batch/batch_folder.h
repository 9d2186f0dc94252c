// A batch's output folder as its workers share it (the layout: renders/batch/batch_run.h): the plan
// in and out of plan.json, each task's still and records, and a task's state read from the files,
// whichever executor ran it. Internal to renders/batch (batch_run.cpp, batch_gallery.cpp).
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "renders/batch/batch_run.h"

namespace wangscape::batch_detail {

using nlohmann::json;
using Plan = BatchPlan;

// A task as plan.json and batch.json hold it.
json task_json(const BatchTask& t);
// The whole text of a file ("" when it cannot be read).
std::string read_text(const std::filesystem::path& file);
// A task record (tasks/ID.json, .failed): small files of this run; anything else (a torn write,
// a folder, a FIFO, a foreign or deep file) is null.
json read_json(const std::filesystem::path& file);
// DIR/plan.json read back; Error for a folder that is not a batch's output.
Plan load_plan(const std::filesystem::path& dir);
void write_plan(const std::filesystem::path& dir, const BatchConfig& config, const std::vector<BatchTask>& tasks);

// Task t's still (stills/ID.png) and its records (tasks/ID.json, .running, .failed).
std::filesystem::path still_of(const std::filesystem::path& dir, const BatchTask& t);
std::filesystem::path record_of(const std::filesystem::path& dir, const BatchTask& t, const char* ext);
// Its still is there with a record of the same inputs.
bool task_done(const std::filesystem::path& dir, const BatchTask& t);

enum class State { done, running, failed, pending };
const char* state_name(State s);
// From the files: done, running (a live worker's marker, or one on another host), failed, pending.
State task_state(const std::filesystem::path& dir, const BatchTask& t);

}  // namespace wangscape::batch_detail
