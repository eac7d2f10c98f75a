// Scene text -> JSON, strictly: a scene is hand-written, so what a plain JSON parser lets pass
// silently is refused here with the key path and the line and column. A key given twice in one
// object (nlohmann::json keeps the last one without a word), a number beyond a double's range (the
// library throws an exception that names no key) and a syntax error all become a SceneError.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace cleave::scene {

// Parses `text` (comments allowed, as in the example scenes). SceneError's key path is the key
// whose value is at fault ("time", "bodies[1].shape.radius"; "(scene)" at the top level); the
// reason gives the line and column, and for a duplicate key both places.
nlohmann::json parse_scene_text(const std::string& text);

// "line L, column C" of byte offset `offset` of `text` (1-based, columns in bytes).
std::string text_position(const std::string& text, std::size_t offset);

}  // namespace cleave::scene
