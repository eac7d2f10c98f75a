// The files every run writes into its output directory besides the frames' contents: the status
// file run.json, frame file names, and the clean-up of an earlier run's files (MPM and PD runs
// share them, so a directory written by one solver is handled the same way by the other).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libmpm/io/pvd_writer.hpp"

namespace cleave::io {

// run.json: {"status", "message", "step", "time"} plus the keys of `extra`, replaced atomically
// (written beside and renamed), so a reader never sees half a file. Throws std::runtime_error
// naming the file and the cause (strerror) when it cannot be written.
void write_run_status(const std::filesystem::path& out, const std::string& status, const std::string& message,
                      long step, double time, const nlohmann::json& extra = nlohmann::json::object());

// The last word of a run whose disk is full: like write_run_status, but when the atomic write
// fails, run.json is overwritten in place (its blocks are already allocated). Never throws; returns
// "" or why run.json could not be written.
std::string write_final_run_status(const std::filesystem::path& out, const std::string& status,
                                   const std::string& message, long step, double time,
                                   const nlohmann::json& extra = nlohmann::json::object());

// Removes the temporaries ("NAME.tmp") that atomic writes of the run's outputs leave when they are
// cut short: frames and indexes of `series`, and the named `files` (checkpoint.bin, run.json, ...).
void remove_temporaries(const std::filesystem::path& out, const std::vector<std::string>& series,
                        const std::vector<std::string>& files);

// "<series>_NNNNNN.vtu"
std::string frame_file_name(const std::string& series, int k);

// A fresh run replaces an earlier one's outputs: removes every "<series>_*.vtu" and "<series>.pvd"
// of `series`, and the named `files` (global.csv, checkpoint.bin, run.json, ...). Other files stay.
void remove_run_outputs(const std::filesystem::path& out, const std::vector<std::string>& series,
                        const std::vector<std::string>& files);

// A resumed run's time-series index: the collection as written, cut after the checkpoint time.
PvdIndex resumed_series(const std::filesystem::path& pvd_file, double checkpoint_time);

}  // namespace cleave::io
