#include "libmpm/scene/json_text.hpp"

#include <iterator>
#include <map>
#include <optional>
#include <vector>

#include "libmpm/core/error.hpp"

namespace cleave::scene {
namespace {

using nlohmann::json;

// A char iterator that tells how far the parser has read: the SAX interface gives no position for
// a key, but the parser has read exactly up to a key's closing quote when it reports the key.
struct TrackedChar {
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;
  const char* p = nullptr;
  const char** read_to = nullptr;  // shared by the copies the parser makes
  reference operator*() const { return *p; }
  TrackedChar& operator++() {
    *read_to = ++p;
    return *this;
  }
  TrackedChar operator++(int) {
    TrackedChar old = *this;
    ++*this;
    return old;
  }
  bool operator==(const TrackedChar& o) const { return p == o.p; }
  bool operator!=(const TrackedChar& o) const { return p != o.p; }
};

// Builds the document as nlohmann's own DOM parser does, tracking the key path of the value being
// read and, per object, where each key was given.
class StrictBuilder {
 public:
  StrictBuilder(const std::string& text, const char* const& read_to) : text_(text), read_to_(read_to) {}

  bool null() { return put(nullptr) != nullptr; }
  bool boolean(bool v) { return put(v) != nullptr; }
  bool number_integer(json::number_integer_t v) { return put(v) != nullptr; }
  bool number_unsigned(json::number_unsigned_t v) { return put(v) != nullptr; }
  bool number_float(json::number_float_t v, const std::string&) { return put(v) != nullptr; }
  bool string(std::string& v) { return put(std::move(v)) != nullptr; }
  bool binary(json::binary_t& v) { return put(json::binary(std::move(v))) != nullptr; }
  bool start_object(std::size_t) { return open(json::object()); }
  bool start_array(std::size_t) { return open(json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(std::string& k) {
    Level& top = levels_.back();
    // The parser has just read the key's closing quote; its opening quote is the last unescaped one.
    std::size_t end = static_cast<std::size_t>(read_to_ - text_.data()), start = end >= 2 ? end - 2 : 0;
    while (start > 0 && !(text_[start] == '"' && !escaped(start))) --start;
    const auto [it, fresh] = top.keys.emplace(k, start);
    top.key = k;
    if (!fresh) {
      error_.emplace(child_path(), "duplicate key: given at " + text_position(text_, it->second) + " and again at " +
                                       text_position(text_, start) +
                                       " (JSON would keep only the last one silently; remove one)");
      return false;
    }
    return true;
  }

  bool parse_error(std::size_t offset, const std::string& token, const nlohmann::detail::exception& e) {
    std::string path = levels_.empty() ? "" : child_path();
    if (path.empty()) path = "(scene)";
    if (e.id == 406) {  // out_of_range.406: a number beyond a double's range
      const std::size_t start = offset >= token.size() ? offset - token.size() : 0;
      error_.emplace(path, "number " + token + " is out of range (a double holds at most 1.8e308) at " +
                               text_position(text_, start));
    } else {
      std::string what = e.what();  // "[json.exception.parse_error.101] parse error at line 3, ..."
      if (const auto b = what.find("] "); what.rfind("[json.exception", 0) == 0 && b != std::string::npos)
        what = what.substr(b + 2);
      error_.emplace(path, "not valid JSON: " + what);
    }
    return false;
  }

  json& root() { return root_; }
  const std::optional<SceneError>& error() const { return error_; }

 private:
  struct Level {
    json* node;
    std::string path;  // of the container itself ("" for the root)
    std::string key;   // the key whose value is being read (objects)
    std::map<std::string, std::size_t> keys;  // key -> offset of its opening quote
  };

  bool escaped(std::size_t quote) const {
    std::size_t n = 0;
    while (quote > n && text_[quote - n - 1] == '\\') ++n;
    return n % 2 == 1;
  }
  // Key path of the value being read in the innermost container (the container's own between a
  // value and the next key).
  std::string child_path() const {
    const Level& top = levels_.back();
    if (top.node->is_array()) return top.path + "[" + std::to_string(top.node->size()) + "]";
    if (top.key.empty()) return top.path;
    return top.path.empty() ? top.key : top.path + "." + top.key;
  }
  json* put(json v) {
    if (levels_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Level& top = levels_.back();
    if (top.node->is_array()) {
      top.node->push_back(std::move(v));
      return &top.node->back();
    }
    json& slot = (*top.node)[top.key];
    slot = std::move(v);
    top.key.clear();  // read: an error before the next key is the object's
    return &slot;
  }
  bool open(json empty) {
    const std::string path = levels_.empty() ? "" : child_path();
    if (levels_.size() >= kMaxNesting) {
      error_.emplace(path, "arrays and objects nested more than " + std::to_string(kMaxNesting) +
                               " levels deep at " + text_position(text_, static_cast<std::size_t>(read_to_ - text_.data()) - 1) +
                               " (a scene needs about ten)");
      return false;
    }
    levels_.push_back({put(std::move(empty)), path, "", {}});
    return true;
  }
  bool close() {
    levels_.pop_back();
    return true;
  }

  const std::string& text_;
  const char* const& read_to_;
  json root_;
  std::vector<Level> levels_;
  std::optional<SceneError> error_;
};

}  // namespace

std::string text_position(const std::string& text, std::size_t offset) {
  offset = std::min(offset, text.size());
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < offset; ++i)
    if (text[i] == '\n') ++line, line_start = i + 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(offset - line_start + 1);
}

json parse_scene_text(const std::string& text) {
  const char* read_to = text.data();
  StrictBuilder builder(text, read_to);
  TrackedChar first{text.data(), &read_to}, last{text.data() + text.size(), &read_to};
  const bool ok = json::sax_parse(first, last, &builder, json::input_format_t::json, /*strict=*/true,
                                  /*ignore_comments=*/true);
  if (builder.error()) throw *builder.error();
  if (!ok) throw SceneError("(scene)", "not valid JSON");
  return std::move(builder.root());
}

}  // namespace cleave::scene
