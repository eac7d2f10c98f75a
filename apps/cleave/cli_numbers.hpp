// Numbers on the command line: "1.5" and "x,y,z" lists, refused with the option's name.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace cleave::app {
// Comma-separated finite numbers, lo..hi of them; std::invalid_argument naming `opt` otherwise.
std::vector<double> numbers(const std::string& opt, const std::string& s, std::size_t lo, std::size_t hi);
double number(const std::string& opt, const std::string& s);
}  // namespace cleave::app
