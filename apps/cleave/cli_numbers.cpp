#include "apps/cleave/cli_numbers.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace cleave::app {

std::vector<double> numbers(const std::string& opt, const std::string& s, std::size_t lo, std::size_t hi) {
  std::vector<double> v;
  std::stringstream ss(s);
  for (std::string part; std::getline(ss, part, ',');) {
    char* end = nullptr;
    const double d = std::strtod(part.c_str(), &end);
    if (part.empty() || *end != '\0' || !std::isfinite(d)) throw std::invalid_argument(opt + ": '" + part + "' is not a number");
    v.push_back(d);
  }
  if (v.size() < lo || v.size() > hi)
    throw std::invalid_argument(opt + " needs " + (lo == hi ? std::to_string(lo) : std::to_string(lo) + " to " + std::to_string(hi)) +
                                " comma-separated numbers");
  return v;
}

double number(const std::string& opt, const std::string& s) { return numbers(opt, s, 1, 1)[0]; }

}  // namespace cleave::app
