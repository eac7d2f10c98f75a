// The Brazilian disk: radius R, thickness t, diametral loads P at (0, +-R) pressing it together
// (validation.md section 7, with r1^2 = x^2 + (R - y)^2, r2^2 = x^2 + (R + y)^2 about the centre).
#include <cmath>

#include "libmpm/reference/closed_form.hpp"

namespace cleave::reference {
namespace {

class BrazilianDisk final : public ClosedForm {
 public:
  std::string formula() const override {
    return "sxx = -(2P/pi t)[x^2(R-y)/r1^4 + x^2(R+y)/r2^4 - 1/2R], syy = -(2P/pi t)[(R-y)^3/r1^4 + (R+y)^3/r2^4 - "
           "1/2R], sxy = (2P/pi t)[x(R-y)^2/r1^4 - x(R+y)^2/r2^4] (validation.md section 7)";
  }
  std::vector<Parameter> parameters() const override {
    return {{"force", Quantity::Force, "the diametral load P (along y)"},
            {"radius", Quantity::Length, "the disk's radius R"},
            {"thickness", Quantity::Length, "the disk's thickness t"},
            {"centre_x", Quantity::Length, "the disk's centre, x", 0.0},
            {"centre_y", Quantity::Length, "the disk's centre, y", 0.0}};
  }
  std::string unit() const override { return "Pa"; }
  bool field() const override { return true; }
  std::array<double, 3> stress(const Values& v, double X, double Y) const override {
    const double P = v.at("force"), R = v.at("radius"), t = v.at("thickness");
    const double x = X - v.at("centre_x"), y = Y - v.at("centre_y");
    const double r1 = x * x + (R - y) * (R - y), r2 = x * x + (R + y) * (R + y);
    const double r14 = r1 * r1, r24 = r2 * r2, c = 2 * P / (M_PI * t);
    return {-c * (x * x * (R - y) / r14 + x * x * (R + y) / r24 - 1 / (2 * R)),
            -c * ((R - y) * (R - y) * (R - y) / r14 + (R + y) * (R + y) * (R + y) / r24 - 1 / (2 * R)),
            c * (x * (R - y) * (R - y) / r14 - x * (R + y) * (R + y) / r24)};
  }
};

const bool registered =
    ClosedFormRegistry::instance().add("brazilian_disk", [] { return std::make_unique<BrazilianDisk>(); });

}  // namespace
}  // namespace cleave::reference
