// From measurements to errors: each quantity of each run against its reference (a closed form, a
// value, a file, or the finest run of the same series with Richardson extrapolation), the observed
// order of convergence per series, and the cheapest run that meets each tolerance.
#pragma once
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/measure.hpp"
#include "study/study_spec.hpp"

namespace cleave::study {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct RunRecord {
  const RunPlan* plan = nullptr;
  std::string status = "not run";  // complete | stopped | aborted | refused | failed | not run
  int exit_code = -1;
  std::string message;             // run.json's message, or the error the run printed
  double wall_s = kNaN, cpu_s = kNaN, peak_mb = kNaN;
  long steps = -1, particles = -1;
  nlohmann::json scene;            // the run's scene, overrides applied
  std::vector<Measurement> q;      // per quantity (empty until measured)
  std::vector<double> error;       // per quantity; NaN where there is none
  std::string expectation;         // extremes: "met" or "MISSED: why"; empty without one
};

// The cell size of a run (the value of the study's cell key), NaN without one.
double cell_of(const Study& st, const RunRecord& r);
// The run's series: "key=value, ..." of the study's series keys ("" when there are none).
std::string series_of(const Study& st, const RunRecord& r);

struct OrderFit {
  std::string quantity, series;
  int points = 0;
  double order = kNaN;              // slope of log error against log cell size (least squares)
  double richardson = kNaN;         // finest reference: the extrapolated value (three finest runs), when
                                    // it moves less than the last refinement did (else NaN: not asymptotic)
  double richardson_order = kNaN;   // the order the three finest imply (also when not asymptotic)
};

// Three values q(h) = q* + C h^p at distinct h: p and q*. false when the differences change sign
// (not in the asymptotic range) or p cannot be bracketed in (0.05, 20).
bool richardson(const double h[3], const double q[3], double& order, double& extrapolated);

// Fills every record's `error` and returns the order fits, one per quantity and series.
std::vector<OrderFit> compute_errors(const Study& st, std::vector<RunRecord>& runs);

// Whether a run met its expectation (extremes); sets r.expectation. `drift` is its measured energy
// drift (NaN when none), `nan_found` whether its tables hold a non-finite number.
void judge_expectation(RunRecord& r, double drift, bool nan_found);

}  // namespace cleave::study
