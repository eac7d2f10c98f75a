// cleave study STUDY.json --out DIR: runs a study's scenes one after another (apps/cleave/study_cli.cpp).
#pragma once
#include <string>
#include <vector>

namespace cleave::app {

// args[0] == "study". Returns the exit status.
int study_command(const std::vector<std::string>& args);

}  // namespace cleave::app
