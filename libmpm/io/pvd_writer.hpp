// ParaView collection (.pvd) index of a time series of .vtu frames. Rewritten whole after every
// frame (atomically), so ParaView can open the series while the run is going, and reloaded and
// truncated when a run resumes from a checkpoint.
#pragma once
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace cleave::io {

class PvdIndex {
 public:
  explicit PvdIndex(std::filesystem::path pvd_file);

  // Appends an entry; `relative_vtu_name` is relative to the .pvd's directory.
  void add(double time, const std::string& relative_vtu_name);
  // Writes the whole index to the .pvd (file + ".tmp", then rename). Times are printed with 17
  // significant digits so load() gives back exactly the doubles that were added.
  void write() const;
  // Drops entries with time > t (resuming from a checkpoint at time t).
  void truncate_after(double time);
  // Parses a .pvd written by this class; throws std::runtime_error naming the file if it cannot.
  static PvdIndex load(const std::filesystem::path& pvd_file);

  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }
  const std::filesystem::path& path() const { return file_; }

 private:
  std::filesystem::path file_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace cleave::io
