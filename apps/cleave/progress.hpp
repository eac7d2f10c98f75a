// Terminal progress for long runs: an updating line on a terminal, periodic plain lines in a log.
#pragma once
#include "libmpm/method/run_loop.hpp"

namespace cleave::app {

class ProgressPrinter {
 public:
  ProgressPrinter();
  void operator()(const RunProgress& p);
  void finish();  // ends the updating line
  double interval() const { return tty_ ? 0.5 : 10.0; }

 private:
  bool tty_;
  bool dirty_ = false;
};

std::string format_seconds(double s);

}  // namespace cleave::app
