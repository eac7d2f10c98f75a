// One quantity of one run, measured from its folder: a table column (its last value, its value at
// a time, its largest magnitude, or its series over a window), the energy drift of global.csv, or
// the fringe-order RMS of a frame against a stress field or digitised points.
#pragma once
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "libmpm/reference/closed_form.hpp"
#include "study/run_tables.hpp"
#include "study/study_spec.hpp"

namespace cleave::study {

struct Measurement {
  double value = 0;       // SI; a window's RMS; the drift (fraction); the fringe RMS (fringes)
  double time = 0;        // when the value was taken (s): the row's, or `at`
  Series series;          // window quantities: the run's rows inside the window
  std::string problem;    // not empty: why the run gave no value
  bool ok() const { return problem.empty(); }
};

// The closed form's values for a run: numbers as given (SI), key paths read from the run's scene and
// converted from its units; E, nu and density default to materials[0]'s. StudyError naming
// KEY.values.NAME when a value is missing or the scene has no such key.
reference::Values closed_form_values(const Reference& ref, const nlohmann::json& scene);

// Measures q in the run folder `dir`; `scene` is the run's scene (with its overrides).
Measurement measure(const QuantitySpec& q, const std::filesystem::path& dir, const nlohmann::json& scene);

}  // namespace cleave::study
