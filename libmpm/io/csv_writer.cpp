// Rows are written with to_chars (17 significant digits, locale independent) and flushed one by
// one: a CSV of a few thousand rows is cheap, and losing the tail of a crashed run is not.
#include "libmpm/io/csv_writer.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "libmpm/io/file_sync.hpp"
#include "libmpm/io/vtu_writer.hpp"

namespace cleave::io {

namespace {

std::string format17(double v) {
  if (v == 0.0) v = 0.0;  // -0 (a sum of cancelling terms, -1 * 0) is printed as 0
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof(buf), v, std::chars_format::general, 17);
  return std::string(buf, r.ptr);
}

std::string join(const std::vector<std::string>& cols) {
  std::string s;
  for (std::size_t i = 0; i < cols.size(); ++i) {
    if (i) s += ',';
    s += cols[i];
  }
  return s;
}

// Reads one line without its terminator ("\n" or "\r\n"); false at end of file.
bool read_line(std::istream& in, std::string& line, bool& terminated) {
  if (!std::getline(in, line)) return false;
  terminated = !in.eof();
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
}

bool file_has_content(const std::filesystem::path& f) {
  std::error_code ec;
  return std::filesystem::exists(f, ec) && std::filesystem::file_size(f, ec) > 0 && !ec;
}

// A run killed mid-row leaves an unterminated last line; appending to it would glue two rows
// together, so cut the file back to its last newline.
void drop_partial_last_line(const std::filesystem::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.empty() || text.back() == '\n') return;
  in.close();
  if (text.find('\n') == std::string::npos) {  // only the (matching) header, unterminated
    std::ofstream(f, std::ios::binary | std::ios::app) << '\n';
    return;
  }
  std::error_code ec;
  std::filesystem::resize_file(f, text.rfind('\n') + 1, ec);
  if (ec) throw std::runtime_error("cannot truncate " + f.string() + ": " + ec.message());
}

}  // namespace

CsvSeries::CsvSeries(std::filesystem::path file, std::vector<std::string> columns, bool append)
    : file_(std::move(file)), columns_(columns.size()) {
  if (columns.empty()) throw std::invalid_argument("CsvSeries " + file_.string() + ": no columns");
  for (const auto& c : columns)
    if (c.find_first_of(",\"\r\n") != std::string::npos)
      throw std::invalid_argument("CsvSeries " + file_.string() + ": bad column name '" + c + "'");
  const std::string header = join(columns);

  const bool resume = append && file_has_content(file_);
  if (resume) {
    std::ifstream in(file_, std::ios::binary);
    std::string existing;
    bool terminated = false;
    if (!in || !read_line(in, existing, terminated))
      throw std::runtime_error("cannot read " + file_.string());
    if (existing != header)
      throw std::runtime_error(file_.string() + ": existing header \"" + existing +
                               "\" does not match \"" + header + "\"");
    drop_partial_last_line(file_);
  }
  out_.open(file_, std::ios::binary | (resume ? std::ios::app : std::ios::trunc));
  if (!out_) throw std::runtime_error("cannot open " + file_.string() + " for writing");
  if (!resume) out_ << header << '\n' << std::flush;
  if (!out_) throw std::runtime_error("cannot write " + file_.string());
}

void CsvSeries::row(const std::vector<double>& values) {
  if (values.size() != columns_)
    throw std::invalid_argument("CsvSeries " + file_.string() + ": row has " +
                                std::to_string(values.size()) + " values, expected " +
                                std::to_string(columns_));
  std::string line;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) line += ',';  // appended, not "," + s: GCC 12 warns falsely (-Wrestrict) on the latter
    line += format17(values[i]);
  }
  line += '\n';
  out_.write(line.data(), static_cast<std::streamsize>(line.size()));
  out_.flush();
  if (!out_) throw std::runtime_error("cannot write " + file_.string());
}

void CsvSeries::sync() {
  out_.flush();
  if (!out_) throw std::runtime_error("cannot write " + file_.string());
  if (const int err = sync_file(file_))
    throw std::runtime_error("cannot sync " + file_.string() + ": " + std::strerror(err));
}

void CsvSeries::truncate_after(const std::filesystem::path& file, double time) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return;
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string());

  std::string header, line, kept;
  bool terminated = false;
  if (!read_line(in, header, terminated)) return;  // empty file: nothing to keep or drop
  const auto fields = static_cast<std::size_t>(std::count(header.begin(), header.end(), ',')) + 1;
  kept = header + '\n';
  while (read_line(in, line, terminated)) {
    // An unterminated last line is a row cut short by a crash; so is a wrong field count.
    const auto n = static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
    if (!terminated || n != fields) continue;
    double t = 0.0;
    const char* end = line.data() + std::min(line.find(','), line.size());
    auto r = std::from_chars(line.data(), end, t);
    if (r.ec != std::errc() || r.ptr != end || !(t <= time)) continue;
    kept += line + '\n';
  }
  in.close();
  detail::write_atomically(file, [&](std::ostream& out) {
    out.write(kept.data(), static_cast<std::streamsize>(kept.size()));
  });
}

}  // namespace cleave::io
