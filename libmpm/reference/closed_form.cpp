#include "libmpm/reference/closed_form.hpp"

#include <cmath>
#include <stdexcept>

namespace cleave::reference {

double ClosedForm::value(const Values&, double) const {
  throw std::logic_error("this closed form is a stress field: it has no single value");
}

std::array<double, 3> ClosedForm::stress(const Values&, double, double) const {
  throw std::logic_error("this closed form is a single value, not a stress field");
}

std::unique_ptr<ClosedForm> make_closed_form(const std::string& name) {
  const auto& r = ClosedFormRegistry::instance();
  if (!r.has(name)) throw std::invalid_argument(r.unknown("closed form", name));
  return r.create(name);
}

Values complete_values(const ClosedForm& form, const Values& given) {
  Values v;
  for (const auto& p : form.parameters()) {
    if (auto it = given.find(p.name); it != given.end()) v[p.name] = it->second;
    else if (p.default_value) v[p.name] = *p.default_value;
    else throw std::invalid_argument("missing value '" + p.name + "' (" + p.meaning + ")");
  }
  return v;
}

double dilatational_speed(double E, double nu, double rho, bool plane_stress) {
  const double M = plane_stress ? E / (1 - nu * nu) : E * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  return std::sqrt(M / rho);
}

}  // namespace cleave::reference
