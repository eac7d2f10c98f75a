// Binary restart state (checkpoint.bin): a method writes the arrays and counters that change during
// a run, in a fixed order, and reads them back in the same order. Raw bytes of plain values (numbers,
// Eigen fixed-size vectors and matrices: standard layout, no pointers), so a resumed run continues
// bit for bit on the same machine.
#pragma once
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace cleave {

template <class T>
inline constexpr bool kPlainValue = std::is_standard_layout_v<T> && !std::is_pointer_v<T>;

class StateWriter {
 public:
  explicit StateWriter(std::ostream& o) : o_(o) {}  // any stream: the run estimate counts the bytes
  template <class T>
  void value(const T& v) {
    static_assert(kPlainValue<T>);
    o_.write(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  // The length first, so a reader checks it against what the scene builds.
  template <class T>
  void array(const std::vector<T>& v) {
    static_assert(kPlainValue<T>);
    value<uint64_t>(v.size());
    o_.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
  }

 private:
  std::ostream& o_;
};

class StateReader {
 public:
  StateReader(std::ifstream& i, std::string file) : i_(i), file_(std::move(file)) {}
  template <class T>
  void value(T& v) {
    static_assert(kPlainValue<T>);
    i_.read(reinterpret_cast<char*>(&v), sizeof(T));
    if (!i_) throw std::runtime_error(file_ + ": checkpoint is truncated");
  }
  // Reads an array written by StateWriter::array into v, whose size the scene fixed; `what` names
  // the array in the error when the sizes differ ("particles").
  template <class T>
  void array(std::vector<T>& v, const char* what) {
    uint64_t n = 0;
    value(n);
    if (n != v.size())
      throw std::runtime_error(file_ + ": the checkpoint holds " + std::to_string(n) + " " + what +
                               "; the scene builds " + std::to_string(v.size()) +
                               " (a checkpoint of another scene: run without --resume)");
    i_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
    if (!i_) throw std::runtime_error(file_ + ": checkpoint is truncated");
  }
  // Reads an array whose size the run changes (a growing crack's points): at least `least` and at
  // most `most` elements, else the checkpoint is of another scene or damaged.
  template <class T>
  void array_sized(std::vector<T>& v, const char* what, std::size_t least, std::size_t most) {
    uint64_t n = 0;
    value(n);
    if (n < least || n > most)
      throw std::runtime_error(file_ + ": the checkpoint holds " + std::to_string(n) + " " + what + "; the scene allows " +
                               std::to_string(least) + " to " + std::to_string(most) +
                               " (a checkpoint of another scene: run without --resume)");
    v.resize(n);
    i_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
    if (!i_) throw std::runtime_error(file_ + ": checkpoint is truncated");
  }
  const std::string& file() const { return file_; }

 private:
  std::ifstream& i_;
  std::string file_;
};

}  // namespace cleave
