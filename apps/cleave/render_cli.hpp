#pragma once
#include <string>
#include <vector>

namespace cleave::app {
// args[0] is the command (render, compare, plot). Returns the exit status.
int viz_command(const std::vector<std::string>& args);
// args[0] is "fit" (apps/cleave/fit_cli.cpp). Returns the exit status.
int fit_command(const std::vector<std::string>& args);
}  // namespace cleave::app
