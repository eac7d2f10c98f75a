// The .pvd is small, so it is rebuilt as a string and written atomically each time. load() only
// has to understand what write() produces: one <DataSet .../> element per entry.
#include "libmpm/io/pvd_writer.hpp"

#include <cctype>
#include <charconv>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "libmpm/io/vtu_writer.hpp"

namespace cleave::io {

namespace {

// to_chars, unlike printf, ignores the C locale, so a decimal comma can never sneak in.
std::string format17(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof(buf), v, std::chars_format::general, 17);
  return std::string(buf, r.ptr);
}

std::string xml_unescape(const std::string& s) {
  static const std::pair<std::string_view, char> ents[] = {
      {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
  std::string r;
  for (std::size_t i = 0; i < s.size();) {
    bool matched = false;
    if (s[i] == '&')
      for (auto [e, c] : ents)
        if (std::string_view(s).substr(i, e.size()) == e) {
          r += c;
          i += e.size();
          matched = true;
          break;
        }
    if (!matched) r += s[i++];
  }
  return r;
}

// Attributes name="value" (or 'value') inside one start tag, after the element name.
// Returns false on malformed text.
bool parse_attributes(const std::string& t, std::map<std::string, std::string>& attrs) {
  std::size_t i = 0;
  auto skip_ws = [&] {
    while (i < t.size() && std::isspace(static_cast<unsigned char>(t[i]))) ++i;
  };
  while (true) {
    skip_ws();
    if (i >= t.size() || t[i] == '/' || t[i] == '>') return true;
    std::size_t b = i;
    while (i < t.size() && t[i] != '=' && !std::isspace(static_cast<unsigned char>(t[i]))) ++i;
    std::string name = t.substr(b, i - b);
    skip_ws();
    if (i >= t.size() || t[i] != '=') return false;
    ++i;
    skip_ws();
    if (i >= t.size() || (t[i] != '"' && t[i] != '\'')) return false;
    char q = t[i++];
    std::size_t e = t.find(q, i);
    if (e == std::string::npos) return false;
    attrs[name] = xml_unescape(t.substr(i, e - i));
    i = e + 1;
  }
}

}  // namespace

PvdIndex::PvdIndex(std::filesystem::path pvd_file) : file_(std::move(pvd_file)) {}

void PvdIndex::add(double time, const std::string& relative_vtu_name) {
  entries_.emplace_back(time, relative_vtu_name);
}

void PvdIndex::write() const {
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const auto& [t, name] : entries_)
    xml += "    <DataSet timestep=\"" + format17(t) + "\" group=\"\" part=\"0\" file=\"" +
           detail::xml_escape(name) + "\"/>\n";
  xml += "  </Collection>\n</VTKFile>\n";
  detail::write_atomically(file_, [&](std::ostream& out) {
    out.write(xml.data(), static_cast<std::streamsize>(xml.size()));
  });
}

void PvdIndex::truncate_after(double time) {
  std::erase_if(entries_, [time](const auto& e) { return e.first > time; });
}

PvdIndex PvdIndex::load(const std::filesystem::path& pvd_file) {
  auto fail = [&](const std::string& why) -> PvdIndex {
    throw std::runtime_error("cannot load " + pvd_file.string() + ": " + why);
  };
  std::ifstream in(pvd_file, std::ios::binary);
  if (!in) return fail("cannot open");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  if (text.find("type=\"Collection\"") == std::string::npos ||
      text.find("</VTKFile>") == std::string::npos)
    return fail("not a complete VTK collection file");

  PvdIndex index(pvd_file);
  static const std::string kTag = "<DataSet";
  for (std::size_t pos = text.find(kTag); pos != std::string::npos; pos = text.find(kTag, pos)) {
    pos += kTag.size();
    std::size_t end = text.find('>', pos);
    if (end == std::string::npos) return fail("unterminated <DataSet>");
    std::map<std::string, std::string> attrs;
    if (!parse_attributes(text.substr(pos, end - pos), attrs))
      return fail("malformed <DataSet> attributes");
    auto ts = attrs.find("timestep");
    auto file = attrs.find("file");
    if (ts == attrs.end() || file == attrs.end())
      return fail("<DataSet> without timestep or file");
    double t = 0.0;
    const std::string& s = ts->second;
    auto r = std::from_chars(s.data(), s.data() + s.size(), t);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size())
      return fail("bad timestep \"" + s + "\"");
    index.add(t, file->second);
    pos = end;
  }
  return index;
}

}  // namespace cleave::io
