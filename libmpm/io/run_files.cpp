#include "libmpm/io/run_files.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>

namespace cleave::io {
namespace fs = std::filesystem;

void write_run_status(const fs::path& out, const std::string& status, const std::string& message, long step,
                      double time, const nlohmann::json& extra) {
  nlohmann::json j = {{"status", status}, {"message", message}, {"step", step}, {"time", time}};
  for (auto it = extra.begin(); it != extra.end(); ++it) j[it.key()] = it.value();
  const fs::path tmp = out / "run.json.tmp";
  std::ofstream(tmp) << j.dump(2) << "\n";
  fs::rename(tmp, out / "run.json");
}

std::string frame_file_name(const std::string& series, int k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%06d.vtu", k);
  return series + buf;
}

void remove_run_outputs(const fs::path& out, const std::vector<std::string>& series,
                        const std::vector<std::string>& files) {
  std::vector<fs::path> doomed;
  for (const auto& e : fs::directory_iterator(out)) {
    const std::string n = e.path().filename().string();
    bool remove = std::find(files.begin(), files.end(), n) != files.end();
    for (const auto& s : series)
      remove = remove || n == s + ".pvd" || (n.rfind(s + "_", 0) == 0 && e.path().extension() == ".vtu");
    if (remove) doomed.push_back(e.path());
  }
  for (const auto& p : doomed) fs::remove(p);
}

PvdIndex resumed_series(const fs::path& pvd_file, double checkpoint_time) {
  PvdIndex pvd = PvdIndex::load(pvd_file);
  pvd.truncate_after(checkpoint_time);
  return pvd;
}

}  // namespace cleave::io
