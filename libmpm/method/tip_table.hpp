// crack_tips.csv, one schema for every method. The leading columns mean the same whatever wrote them
// (each name ends in its SI unit, as in every CSV Cleave writes; counts and indices have none):
//   time_s           the row's time
//   crack            which crack: an index into run.json's list (MPM: "cracks", the scene's cracks[];
//                    peridynamics: "crack_tip_trackers", the scene's peridynamics.crack_tips[])
//   tip              which front of that crack (2D: 0 = its first point, 1 = its last; a tracker: 0)
//   x_m, y_m[, z_m]  where the tip is now
//   speed_m_per_s    |x - x_prev| / (t - t_prev) since the same tip's previous row (seed 003); 0 on its first
// then the method's own quantities (MPM: J1_J_per_m2, J2_J_per_m2, KI_Pa_sqrt_m, KII_Pa_sqrt_m). A
// reader finds a column by its header name.
#pragma once
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "libmpm/core/types.hpp"
#include "libmpm/method/state_io.hpp"

namespace cleave {

template <int Dim>
class TipTable {
 public:
  // cracks x fronts tips, each front keeping its last record for the speed; `quantities` name the
  // method's columns after the shared ones.
  TipTable(std::size_t cracks, std::size_t fronts, std::vector<std::string> quantities)
      : fronts_(fronts), quantities_(std::move(quantities)),
        last_x_(cracks * fronts, Vec<Dim>::Constant(std::nan(""))), last_t_(cracks * fronts, -1.0) {}

  std::vector<std::string> columns() const {
    std::vector<std::string> c = {"time_s", "crack", "tip", "x_m", "y_m"};
    if (Dim == 3) c.push_back("z_m");
    c.push_back("speed_m_per_s");
    c.insert(c.end(), quantities_.begin(), quantities_.end());
    return c;
  }

  // The row of tip `front` of crack `crack` at x and time t, followed by the method's quantities
  // (as many as it named); remembers x and t for the next row's speed.
  std::vector<double> row(double t, std::size_t crack, std::size_t front, const Vec<Dim>& x,
                          const std::vector<double>& quantities) {
    const std::size_t k = crack * fronts_ + front;
    const double speed = last_t_[k] >= 0 && t > last_t_[k] ? (x - last_x_[k]).norm() / (t - last_t_[k]) : 0.0;
    last_x_[k] = x;
    last_t_[k] = t;
    std::vector<double> r = {t, double(crack), double(front)};
    for (int d = 0; d < Dim; ++d) r.push_back(x[d]);
    r.push_back(speed);
    r.insert(r.end(), quantities.begin(), quantities.end());
    return r;
  }

  // The last records are restart state: a resumed run's speeds continue as in an uninterrupted one.
  void save(StateWriter& w) const { w.array(last_x_), w.array(last_t_); }
  void load(StateReader& r) { r.array(last_x_, "crack tips"), r.array(last_t_, "crack tips"); }

 private:
  std::size_t fronts_;
  std::vector<std::string> quantities_;
  std::vector<Vec<Dim>> last_x_;
  std::vector<double> last_t_;
};

}  // namespace cleave
