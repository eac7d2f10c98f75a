// A study file (cleave study STUDY.json, docs/speed-accuracy.md): a base scene, the settings to vary
// (any scene key, as --set takes them), the quantities to measure and what to measure them against.
// read_study checks the file's own keys; whether each run's scene is valid is the runner's check
// (cleave check on every run before any runs).
#pragma once
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cleave::study {

// A bad study: the key (as in a scene error: quantities[1].reference.values.E) and the reason.
class StudyError : public std::runtime_error {
 public:
  StudyError(std::string key, std::string reason)
      : std::runtime_error(key + ": " + reason), key_(std::move(key)), reason_(std::move(reason)) {}
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string key_, reason_;
};

struct Setting {
  std::string key;       // scene key path (mpm.shape_function, resolution)
  nlohmann::json value;  // as --set takes it
};

// What a run of the extremes suite must do: complete (with the energy drift at most
// `energy_drift` when given), stop with exit 3 naming `cause`, be refused (exit 2), or either of
// the first two ("complete or stop").
struct Expectation {
  std::string outcome;  // complete | stop | refuse | complete_or_stop
  std::optional<double> energy_drift;
  std::string cause;    // a phrase the message must hold (stop / refuse)
};

struct RunPlan {
  std::string label;                // folder name under the study's --out
  std::filesystem::path scene;      // absolute
  std::vector<Setting> settings;    // every override, the study's "set" first
  std::vector<Setting> varied;      // the study's columns: the varied keys' values (and a run's own set)
  std::optional<Expectation> expect;
  bool named = false;  // the label is the study's own (its "runs" list): the report names the run by it
};

struct Reference {
  enum class Kind { None, ClosedForm, Finest, Value, File, Points, Image } kind = Kind::None;
  std::string closed_form;
  std::map<std::string, nlohmann::json> values;  // number (SI) or scene key path (scene units)
  double value = 0;
  std::filesystem::path file;                    // File: CSV series; Points: x,y,N fringe orders; Image: a photo
  std::array<double, 4> map{0, 0, 1e-4, 0};      // Image: x0, y0 (m, top-left corner), m per pixel, angle (rad)
  bool light_field = false;                      // Image: a light-field (else dark-field) circular polariscope
  std::filesystem::path mask;                    // Image: pixels compared where the mask is bright (optional)
  std::string time_column, column;
  std::string key;                               // for messages: quantities[i].reference
};

struct QuantitySpec {
  enum class Kind { Column, EnergyDrift, FringeRms, RunInfo } kind = Kind::Column;
  enum class When { Last, At, Window, Max } when = When::Last;
  std::string name, key;  // key: quantities[i]
  std::string file = "crack_tips.csv", column;
  std::string info_key;  // run_info: a key path in run.json ("branching.time")
  std::map<std::string, double> where;  // row filter: column -> value (crack, tip, front, node)
  double at = 0, t0 = 0, t1 = 0;
  // fringe_rms: the frame nearest `at`, fringe constant (Pa m / fringe) and thickness (m); points
  // on a grid of `grid` spacing inside a circle (centre, radius), or the reference's points.
  double fringe_constant = 0, thickness = 0, grid = 0, radius = 0;
  std::array<double, 2> centre{0, 0};
  Reference reference;
  std::vector<double> tolerances;  // relative errors (fringe orders for fringe_rms) to report the cheapest run for
};

struct Study {
  std::filesystem::path file;
  std::string title, description;
  std::vector<std::string> varied_keys;  // in the order the study gives them
  std::string cell_key;                  // the varied key that is the cell size ("" if none)
  std::vector<std::string> series_keys;  // keys whose values make the diagrams' lines
  std::vector<RunPlan> runs;
  std::vector<QuantitySpec> quantities;
  int threads = 0;                       // 0: cleave run's default
};

// Reads and checks a study file. StudyError naming the key for every bad value; an empty settings
// list, an unknown quantity kind or reference, a cell-size key that is not varied.
Study read_study(const std::filesystem::path& file);

// "resolution=0.5, mpm.shape_function=ugimp" (or the run's label when nothing varies).
std::string settings_text(const std::vector<Setting>& s);

// A JSON value as a short text: strings bare, numbers as %g.
std::string value_text(const nlohmann::json& v);

}  // namespace cleave::study
