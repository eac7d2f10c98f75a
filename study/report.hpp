// What a study writes: study.csv (one row per run: settings, costs, quantities and errors),
// summary.md (the cheapest setting per tolerance, observed orders, runs that failed or stopped),
// work_precision.png and convergence.png (one of each per quantity with errors after the first:
// work_precision_NAME.png).
#pragma once
#include <filesystem>
#include <vector>

#include "study/analysis.hpp"

namespace cleave::study {

void write_study_csv(const std::filesystem::path& file, const Study& st, const std::vector<RunRecord>& runs);

// `stopped`: the study was stopped before every run ran.
void write_summary(const std::filesystem::path& file, const Study& st, const std::vector<RunRecord>& runs,
                   const std::vector<OrderFit>& fits, bool stopped);

// The diagrams, into dir; returns the files written (none when no quantity has errors).
std::vector<std::filesystem::path> write_plots(const std::filesystem::path& dir, const Study& st,
                                               const std::vector<RunRecord>& runs, const std::vector<OrderFit>& fits);

}  // namespace cleave::study
