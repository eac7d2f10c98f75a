// The seam between the scene and the methods: every method (MPM, peridynamics, ...) is a class
// implementing Method<Dim>, registered by name where it is defined (CLEAVE_REGISTER_METHOD in its
// own folder). The one run loop (method/run_loop.hpp) and run_scene (method/run_scene.hpp) drive
// any of them; nothing outside a method's folder knows its types.
//
// Data flow: scene JSON -> Method<Dim> (built by its factory) -> run loop -> writers (io/) -> files
// that the renderer (viz/) reads.
#pragma once
#include <cstddef>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "libmpm/core/registry.hpp"
#include "libmpm/core/run_settings.hpp"
#include "libmpm/io/point_set.hpp"
#include "libmpm/method/state_io.hpp"

namespace cleave {

// A problem found during a step (NaN, a point outside the grid); empty when all is well.
struct StepProblem {
  long particle = -1;
  std::string what;
  explicit operator bool() const { return particle >= 0; }
};

// One row of global.csv, with the two figures the run loop checks named apart.
struct GlobalRow {
  std::vector<double> values;  // in the order of Method::global_columns()
  double total_energy = 0.0, external_work = 0.0;
};

template <int Dim>
class Method {
 public:
  virtual ~Method() = default;

  // --- what was built ---
  virtual const char* name() const = 0;  // the registered name ("mpm")
  virtual const RunSettings& settings() const = 0;
  // Lines for `cleave check` after "scene OK" (what the run would build and do).
  virtual std::vector<std::string> describe() const = 0;
  // The unit of work of a step, for the summary line: (count, name), e.g. (15740, "particle").
  virtual std::pair<double, std::string> work_per_step() const = 0;

  // --- stepping ---
  virtual StepProblem step() = 0;
  virtual double time() const = 0;
  virtual long step_count() const = 0;
  // A message for the log (empty when there is none), e.g. a node that needed more velocity fields.
  virtual std::string take_warning() { return {}; }
  // The fastest point, for the message of an energy blow-up: "particle 12 at (x, y) m, speed v m/s".
  virtual std::string fastest_point() const = 0;

  // --- observables ---
  // global.csv: time_s, step, then the method's energies, works and momenta, each column name
  // ending in its SI unit (kinetic_energy_J; counts such as step have none).
  virtual std::vector<std::string> global_columns() const = 0;
  virtual GlobalRow global_row() const = 0;
  // The point-set series written at every frame: "particles" first, then e.g. "cracks".
  virtual std::vector<std::string> frame_series() const = 0;
  virtual io::PointSet frame(std::size_t series) = 0;
  // crack_tips.csv: empty columns when the scene asks for no tip output. The leading columns are
  // the same for every method (method/tip_table.hpp): time_s, crack, tip, x_m, y_m[, z_m],
  // speed_m_per_s (crack: index of the crack or tracker; tip: 0 the start, 1 the end of a crack);
  // then the method's quantities with their units (J1_J_per_m2, KI_Pa_sqrt_m, ...).
  virtual std::vector<std::string> tip_columns() const { return {}; }
  // The table's file: crack_tips.csv, or crack_fronts.csv for MPM's 3D fronts (one row per front
  // node: time_s, crack, front, node, s_m, x_m, y_m, z_m, then the quantities; docs/scenes.md).
  virtual std::string tip_file() const { return "crack_tips.csv"; }
  // Rows per record of the table (for the size estimate).
  virtual std::size_t tip_rows_per_record() const { return 2; }
  virtual std::vector<std::vector<double>> tip_rows() { return {}; }
  // A table of events (MPM: crack_growth.csv, a row per growth of a crack tip): its file, its columns
  // (empty: the run has none) and the rows since the last call, which the run loop writes after
  // every step (each row's first column is its time, so a resumed run cuts the table there).
  virtual std::string event_file() const { return "events.csv"; }
  virtual std::vector<std::string> event_columns() const { return {}; }
  virtual std::vector<std::vector<double>> take_event_rows() { return {}; }
  // Dynamic relaxation (RunSettings::static_tolerance > 0, method/relaxation.hpp): whether the state
  // is static now (the run loop ends the run there), and where the relaxation stands (for the message
  // when time.end comes first).
  virtual bool static_reached() const { return false; }
  virtual std::string relaxation_state() const { return {}; }
  // Keys added to run.json beside the status (e.g. the first branching of a peridynamic crack).
  virtual nlohmann::json run_info() const { return nlohmann::json::object(); }

  // --- restart ---
  // Everything that changes during a run (point state, counters, crack state), bit for bit.
  virtual void save(StateWriter& w) const = 0;
  virtual void load(StateReader& r) = 0;
};

// A method factory builds the method from a validated scene (SceneError names the key otherwise).
template <int Dim>
using MethodRegistry = Registry<Method<Dim>, const nlohmann::json&>;

// Builds the scene's method ("method", default "mpm") in the scene's dimension. SceneError("method")
// for a name no method registered, listing the registered ones.
template <int Dim>
std::unique_ptr<Method<Dim>> build_method(const nlohmann::json& scene);

}  // namespace cleave

// Registers a method class for 2D and 3D under `name`; the class template takes the dimension and
// has a constructor from the scene JSON. Put it in the method's own .cpp.
#define CLEAVE_REGISTER_METHOD(name, Class)                                                                  \
  namespace {                                                                                                \
  [[maybe_unused]] const bool cleave_method_registered_2 = ::cleave::MethodRegistry<2>::instance().add(      \
      name, [](const nlohmann::json& s) { return std::unique_ptr<::cleave::Method<2>>(new Class<2>(s)); });  \
  [[maybe_unused]] const bool cleave_method_registered_3 = ::cleave::MethodRegistry<3>::instance().add(      \
      name, [](const nlohmann::json& s) { return std::unique_ptr<::cleave::Method<3>>(new Class<3>(s)); });  \
  }
