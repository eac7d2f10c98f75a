// LAMMPS-style "one style, one file" registry: a style registers a factory under its name at static
// initialisation; the scene reader looks styles up by the name written in the scene.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace cleave {

template <class Base, class... Args>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Base>(Args...)>;

  static Registry& instance() {
    static Registry r;
    return r;
  }
  bool add(const std::string& name, Factory f) {
    factories_[name] = std::move(f);
    return true;
  }
  bool has(const std::string& name) const { return factories_.count(name) != 0; }
  std::unique_ptr<Base> create(const std::string& name, Args... args) const {
    return factories_.at(name)(std::forward<Args>(args)...);
  }
  std::vector<std::string> names() const {
    std::vector<std::string> n;
    for (auto& [k, v] : factories_) n.push_back(k);
    return n;
  }
  std::string names_joined() const {
    std::string s;
    for (auto& n : names()) s += (s.empty() ? "" : ", ") + n;
    return s;
  }

 private:
  std::map<std::string, Factory> factories_;
};

}  // namespace cleave
