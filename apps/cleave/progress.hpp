// Terminal progress for long runs: an updating line on a terminal, periodic plain lines in a log;
// and the lines that close a run.
#pragma once
#include <string>
#include <vector>

#include "libmpm/core/part_costs.hpp"
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

// The line `cleave run` prints when it ends well: what this invocation did, so a resumed run
// reports its own part, and a resumed complete run says there was nothing to do.
std::string summary_line(const RunSummary& s, double work, const std::string& unit, int threads,
                         const std::string& out);

// The line `cleave run` prints after the summary: each part the scene switched on as a share of the
// wall time, e.g. "cost: step 60.2 %, crack fields 1.3 %, contact 0.4 %, J/K 8.3 %, output 29.8 % of
// 6.2 s wall" (five_disks.json); a part the scene did not switch on is not named.
std::string cost_line(const costs::Totals& t);

// The command line `args` (argv as typed) as one shell-pasteable string, quoting where needed;
// with_resume appends --resume unless it is there.
std::string shell_command(const std::vector<std::string>& args, bool with_resume);

}  // namespace cleave::app
