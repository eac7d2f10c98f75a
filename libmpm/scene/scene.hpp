// Scene → model: reads a scene JSON file (documented key by key in docs/scenes.md), validates every
// value with errors that name the key path, converts declared units to SI once, and builds the model.
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>

#include "libmpm/model/model.hpp"

namespace cleave {

// Reads and parses the file; SceneError names the file on a missing file or a JSON syntax error.
nlohmann::json load_scene_file(const std::filesystem::path& file);

// 2 or 3, from "analysis.type".
int scene_dimension(const nlohmann::json& scene);

// Validates the scene and builds the model (bodies filled with particles, loads resolved).
template <int Dim>
Model<Dim> build_model(const nlohmann::json& scene);

}  // namespace cleave
