// Time series of scalars (energies, forces, crack length) as CSV, one row per output step. Rows
// are flushed as they are written so a crashed run keeps its history, and a resumed run cuts the
// rows after its checkpoint time and appends to the same file. By convention (docs/scenes.md,
// "Output files") every column name ends in its SI unit ("time_s", "J1_J_per_m2"), counts and
// indices have none ("step", "crack"), and the first column is the time.
#pragma once
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace cleave::io {

class CsvSeries {
 public:
  // Opens `file` and writes the header line, or, when `append` is set and the file exists and is
  // not empty, keeps its rows and appends after them; then the existing header must equal
  // `columns` (std::runtime_error naming the file otherwise). Column names may not contain
  // ',', '"' or line breaks (std::invalid_argument).
  CsvSeries(std::filesystem::path file, std::vector<std::string> columns, bool append);

  // Writes one row with 17 significant digits (round-trip exact; -0 as 0) and flushes. values.size() must
  // equal the number of columns (std::invalid_argument); I/O failure throws std::runtime_error.
  void row(const std::vector<double>& values);

  // Rewrites `file` (atomically) keeping the header and the rows whose first column is <= time.
  // Rows that do not parse or have the wrong number of fields (a crash mid-row) are dropped too.
  // A missing file is left missing.
  static void truncate_after(const std::filesystem::path& file, double time);

  // Forces the rows written so far to the disk (fsync). The run loop calls it before each
  // checkpoint: a row is flushed to the kernel at once, but only a sync makes it survive a power
  // cut, and a resumed run keeps the rows up to its checkpoint rather than recomputing them.
  // Throws std::runtime_error naming the file and the cause when the sync fails.
  void sync();

  const std::filesystem::path& path() const { return file_; }

 private:
  std::filesystem::path file_;
  std::size_t columns_;
  std::ofstream out_;
};

}  // namespace cleave::io
