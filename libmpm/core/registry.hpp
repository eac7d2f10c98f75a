// LAMMPS-style "one style, one file" registry: a style registers itself under its name at static
// initialisation, in the file that defines it; the scene reader looks styles up by the name written
// in the scene, and an unknown name is answered with the registered ones. The library is linked
// whole-archive (libmpm/CMakeLists.txt), so those static registrars are never dropped.
#pragma once
#include <cxxabi.h>

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

namespace cleave {

// "a, b, c"; with `last` = " or ": "a, b or c".
inline std::string join_names(const std::vector<std::string>& names, const std::string& last = ", ") {
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i) s += (i == 0 ? "" : i + 1 == names.size() ? last : ", ") + names[i];
  return s;
}

// "unknown <what> '<name>'; valid: <valid>", the one wording of every unknown-name error.
inline std::string unknown_name(const std::string& what, const std::string& name, const std::string& valid) {
  return "unknown " + what + " '" + name + "'; valid: " + valid;
}

// Name -> entry. Names are listed by rank, then alphabetically: a rank keeps a list in the order
// the documentation gives it (shape types, load kinds) whatever the order the files register in.
// Tag tells apart two tables of the same entry type.
template <class Entry, class Tag = Entry>
class NameTable {
 public:
  static NameTable& instance() {
    static NameTable t;
    return t;
  }
  // A second style under a taken name would replace the first without a word (which one wins would
  // depend on the link order), so it is a programming error, raised at static initialisation.
  bool add(const std::string& name, Entry e, int rank = 0) {
    if (!items_.emplace(name, Item{rank, std::move(e)}).second)
      throw std::logic_error("duplicate registration: '" + name + "' is already registered in the table of " +
                             table_name() + " (two styles under one name; rename one)");
    return true;
  }
  // The table's name in messages: its tag type, demangled ("cleave::Method<2>", "cleave::LoadKind").
  static std::string table_name() {
    int status = 0;
    char* d = abi::__cxa_demangle(typeid(Tag).name(), nullptr, nullptr, &status);
    std::string n = status == 0 && d ? d : typeid(Tag).name();
    std::free(d);
    return n;
  }
  bool has(const std::string& name) const { return items_.count(name) != 0; }
  const Entry* find(const std::string& name) const {
    auto it = items_.find(name);
    return it == items_.end() ? nullptr : &it->second.entry;
  }
  const Entry& at(const std::string& name) const {
    if (const Entry* e = find(name)) return *e;
    throw std::out_of_range("'" + name + "' is not registered");
  }
  // f(name, entry) for every entry, in listing order.
  template <class F>
  void each(F&& f) const {
    for (const auto* kv : ordered()) f(kv->first, kv->second.entry);
  }
  // The names for which keep(name, entry) holds, in listing order.
  template <class Keep>
  std::vector<std::string> names_where(Keep&& keep) const {
    std::vector<std::string> n;
    each([&](const std::string& name, const Entry& e) {
      if (keep(name, e)) n.push_back(name);
    });
    return n;
  }
  std::vector<std::string> names() const {
    return names_where([](const std::string&, const Entry&) { return true; });
  }
  std::string names_joined() const { return join_names(names()); }

 private:
  struct Item {
    int rank;
    Entry entry;
  };
  using Pair = typename std::map<std::string, Item>::value_type;
  std::vector<const Pair*> ordered() const {
    std::vector<const Pair*> v;
    for (const auto& kv : items_) v.push_back(&kv);
    std::stable_sort(v.begin(), v.end(), [](const Pair* a, const Pair* b) { return a->second.rank < b->second.rank; });
    return v;
  }
  std::map<std::string, Item> items_;
};

// Name -> factory building a Base from Args (methods, materials).
template <class Base, class... Args>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Base>(Args...)>;

  static Registry& instance() {
    static Registry r;
    return r;
  }
  bool add(const std::string& name, Factory f, int rank = 0) { return table_.add(name, std::move(f), rank); }
  bool has(const std::string& name) const { return table_.has(name); }
  std::unique_ptr<Base> create(const std::string& name, Args... args) const {
    return table_.at(name)(std::forward<Args>(args)...);
  }
  std::vector<std::string> names() const { return table_.names(); }
  std::string names_joined() const { return table_.names_joined(); }
  // The message for a name no style registered: "unknown <what> '<name>'; valid: ...".
  std::string unknown(const std::string& what, const std::string& name) const {
    return unknown_name(what, name, names_joined());
  }

 private:
  NameTable<Factory, Base> table_;  // tagged by Base: its messages say "cleave::Method<2>"
};

}  // namespace cleave

// A distinct name per registrar (one per line), so one file can register several styles.
#define CLEAVE_REGISTRY_CAT2(a, b) a##b
#define CLEAVE_REGISTRY_CAT(a, b) CLEAVE_REGISTRY_CAT2(a, b)
#define CLEAVE_REGISTRAR(prefix) CLEAVE_REGISTRY_CAT(prefix, __LINE__)
