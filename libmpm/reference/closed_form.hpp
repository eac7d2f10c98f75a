// Closed-form references that runs are measured against (cleave study, the validation tests):
// a registry of small classes, one file each, that register themselves by name. Each declares the
// values it needs (with their physical quantity, so that a study may read them from a scene in the
// scene's units) and gives either a number (a time series when it depends on t) or a 2D stress field.
// Formulas and sources: ../shared/reference/validation.md, quoted in each file.
#pragma once
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "libmpm/core/registry.hpp"
#include "libmpm/core/units.hpp"

namespace cleave::reference {

// A value a closed form needs. `quantity`: its physical quantity (for unit conversion from a scene),
// none for plain numbers (Poisson's ratio, a count). A default makes it optional.
struct Parameter {
  std::string name;
  std::optional<Quantity> quantity;
  std::string meaning;
  std::optional<double> default_value = std::nullopt;
};

using Values = std::map<std::string, double>;  // SI

class ClosedForm {
 public:
  virtual ~ClosedForm() = default;
  virtual std::string formula() const = 0;  // the formula and its source, one line
  virtual std::vector<Parameter> parameters() const = 0;
  virtual std::string unit() const = 0;     // SI unit of value(): "Pa m^1/2", "m", ...
  // A field reference gives stress(), not value().
  virtual bool field() const { return false; }
  // The reference value at time t (s); those that do not depend on time ignore t. NaN where the form
  // does not apply (before a load arrives).
  virtual double value(const Values& v, double t) const;
  // In-plane stress (sxx, syy, sxy) in Pa at (x, y) m, for field references.
  virtual std::array<double, 3> stress(const Values& v, double x, double y) const;
};

using ClosedFormRegistry = Registry<ClosedForm>;

// The closed form of that name; std::invalid_argument "unknown closed form 'x'; valid: ..." otherwise.
std::unique_ptr<ClosedForm> make_closed_form(const std::string& name);

// Every parameter of `form` from `given` or its default; std::invalid_argument naming the first
// missing one and what it means.
Values complete_values(const ClosedForm& form, const Values& given);

// Wave speeds of validation.md section 1 (plane stress: the thin plate's dilatational speed).
double dilatational_speed(double E, double nu, double rho, bool plane_stress);

}  // namespace cleave::reference
