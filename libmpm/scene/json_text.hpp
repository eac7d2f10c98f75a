// Scene text -> JSON, strictly: a scene is hand-written, so what a plain JSON parser lets pass
// silently is refused here with the key path and the line and column. A key given twice in one
// object (nlohmann::json keeps the last one without a word), a number beyond a double's range (the
// library throws an exception that names no key) and a syntax error all become a SceneError.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace cleave::scene {

// The most arrays and objects nested in one another that a scene (and a `--set` value where it
// lands) may have: a scene needs about ten (a CSG shape a few more per level). A deeper document is
// refused before it is built: each level costs the reader a key path as long as the level's depth
// (200 000 levels took minutes and gigabytes), and nested copies and dumps recurse.
inline constexpr std::size_t kMaxNesting = 100;

// Parses `text` (comments allowed, as in the example scenes). SceneError's key path is the key
// whose value is at fault ("time", "bodies[1].shape.radius"; "(scene)" at the top level); the
// reason gives the line and column, and for a duplicate key both places. Nesting deeper than
// kMaxNesting is refused at the key of the container that opens the level too many.
nlohmann::json parse_scene_text(const std::string& text);

// "line L, column C" of byte offset `offset` of `text` (1-based, columns in bytes).
std::string text_position(const std::string& text, std::size_t offset);

}  // namespace cleave::scene
