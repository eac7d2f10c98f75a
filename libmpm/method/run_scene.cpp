#include "libmpm/method/run_scene.hpp"

#include "libmpm/core/error.hpp"
#include "libmpm/scene/scene.hpp"

namespace cleave {

template <int Dim>
std::unique_ptr<Method<Dim>> build_method(const nlohmann::json& scene) {
  const std::string name = scene_method(scene);
  const auto& reg = MethodRegistry<Dim>::instance();
  if (!reg.has(name)) throw SceneError("method", "unknown method '" + name + "'; valid: " + reg.names_joined());
  return reg.create(name, scene);
}
template std::unique_ptr<Method<2>> build_method<2>(const nlohmann::json&);
template std::unique_ptr<Method<3>> build_method<3>(const nlohmann::json&);

SceneMethod SceneMethod::build(const nlohmann::json& scene) {
  SceneMethod s;
  const int dim = scene_dimension(scene);
  if (dim == 2) s.m2_ = build_method<2>(scene);
  else s.m3_ = build_method<3>(scene);
  s.hash_ = scene_hash(scene);
  return s;
}

const char* SceneMethod::name() const { return m2_ ? m2_->name() : m3_->name(); }
const RunSettings& SceneMethod::settings() const { return m2_ ? m2_->settings() : m3_->settings(); }
std::vector<std::string> SceneMethod::describe() const { return m2_ ? m2_->describe() : m3_->describe(); }
std::vector<std::pair<std::string, std::vector<std::string>>> SceneMethod::tables() const {
  auto of = [](const auto& m) {
    std::vector<std::pair<std::string, std::vector<std::string>>> t{{"global.csv", m.global_columns()}};
    if (auto c = m.tip_columns(); !c.empty()) t.push_back({m.tip_file(), std::move(c)});
    if (auto c = m.event_columns(); !c.empty()) t.push_back({m.event_file(), std::move(c)});
    return t;
  };
  return m2_ ? of(*m2_) : of(*m3_);
}

std::pair<double, std::string> SceneMethod::work_per_step() const {
  return m2_ ? m2_->work_per_step() : m3_->work_per_step();
}
RunEstimate SceneMethod::estimate() { return m2_ ? estimate_run<2>(*m2_) : estimate_run<3>(*m3_); }
RunSummary SceneMethod::run(RunOptions opt) {
  check_disk(estimate(), opt.out);
  opt.scene_hash = hash_;
  return m2_ ? run_method<2>(*m2_, opt) : run_method<3>(*m3_, opt);
}

RunSummary run_scene(nlohmann::json scene, const std::vector<std::string>& overrides, const RunOptions& opt) {
  apply_overrides(scene, overrides);
  return SceneMethod::build(scene).run(opt);
}

}  // namespace cleave
