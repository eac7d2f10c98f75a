// 2D explicit cracks (seed 002, CRAMP): a crack is a polyline (ExplicitCrack<2>, explicit_crack.hpp)
// whose vertices are massless crack particles; particle-node pairs whose connecting line crosses it
// use separate velocity fields. This header holds the whole-crack crossing test (with the appendix's
// crack-extent screening) and the scene parser for the "cracks" key.
#pragma once
#include <cstdint>
#include <limits>
#include <utility>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "libmpm/core/registry.hpp"
#include "libmpm/core/types.hpp"
#include "libmpm/crack/crossing.hpp"
#include "libmpm/crack/explicit_crack.hpp"

namespace cleave::crack {

using Crack2D = ExplicitCrack<2>;

// Subtask 1: can the particle-node line touch the crack at all? True when the closed rectangle
// spanned by particle and node intersects the closed extent [lo, hi]. Exact (comparisons only), so
// screening never changes crack_crossing's answer: every crossing point lies in both boxes.
inline bool extent_overlaps(const Crack2D& c, const Vec<2>& particle, const Vec<2>& node) {
  return std::min(particle.x(), node.x()) <= c.hi.x() && std::max(particle.x(), node.x()) >= c.lo.x() &&
         std::min(particle.y(), node.y()) <= c.hi.y() && std::max(particle.y(), node.y()) >= c.lo.y();
}

// Whole-crack crossing for a particle-node pair without screening (polyline_crossing in
// crossing.hpp documents the rules: appendix sign rules per segment, odd/even count, interior
// vertices decided once; an odd count with mixed sides takes the side of the net count).
// A crack whose ends are cut back (ExplicitCrack::cuts) is tested as crossing_polyline says.
inline Side crack_crossing_unscreened(const Crack2D& c, const Vec<2>& particle, const Vec<2>& node) {
  int32_t lo = 0, hi = static_cast<int32_t>(c.points.size()) - 2;
  const Vec<2>* pts = c.crossing_polyline(node, lo, hi);
  return pts ? polyline_crossing(pts + lo, static_cast<std::size_t>(hi - lo + 2), particle, node) : Side::None;
}

// Whole-crack crossing for a particle-node pair: Subtask 1 extent screening, then every segment
// (Subtasks 2-4). Above = velocity field 1 (particle on the left of the directed crack), Below =
// field 2, None = field 0 (for this crack). Requires update_extent() after the points changed.
inline Side crack_crossing(const Crack2D& c, const Vec<2>& particle, const Vec<2>& node) {
  if (!extent_overlaps(c, particle, node)) return Side::None;
  return crack_crossing_unscreened(c, particle, node);
}

// Velocity-field key of the line from x (a particle, or a point standing for one) to the node at
// xn, over every crack: one code per crossed crack, code = 2 crack + (below ? 1 : 0) + 1, two codes
// of kKeyCodeBits in ascending order (bits 0-11, then 12-23); 0 when no crack is crossed,
// kFieldKeyOverflow when three or more are. The same key the stepper's crack fields use
// (whole-crack scan, no spatial index). The stepper adds a body tag in bits 24-31 where bodies in
// contact meet (libmpm/mpm/crack_fields/body_groups.hpp); the crack codes are read with key_code.
inline constexpr uint32_t kFieldKeyOverflow = 0xffffffffu;
inline constexpr int kKeyCodeBits = 12;
inline constexpr uint32_t kKeyCodeMask = (1u << kKeyCodeBits) - 1;
inline constexpr int kMaxCracks = static_cast<int>(kKeyCodeMask / 2) - 1;  // codes up to 2 (kMaxCracks - 1) + 2
// Code c (0 or 1) of a key (0: none).
inline constexpr uint32_t key_code(uint32_t key, int c) { return (key >> (kKeyCodeBits * c)) & kKeyCodeMask; }
// The crack a nonzero code names (code = 2 crack + (below ? 1 : 0) + 1: FieldKeyBuilder).
inline constexpr int code_crack(uint32_t code) { return static_cast<int>((code - 1) / 2); }

// Collects the crossings of one particle-node line into its field key (with the crossed segment of
// each code): add() returns false when a third crack is crossed (the key is then kFieldKeyOverflow).
struct FieldKeyBuilder {
  uint32_t code[2] = {0, 0};
  int32_t seg[2] = {0, 0};
  int count = 0;
  bool add(int crack, Side side, int32_t segment = 0) {
    if (count == 2) return false;
    code[count] = static_cast<uint32_t>(2 * crack + (side == Side::Below ? 1 : 0) + 1);
    seg[count] = segment;
    ++count;
    return true;
  }
  // The key, codes in ascending order; seg_out (optional) receives the segments in the same order.
  uint32_t key(int32_t* seg_out = nullptr) {
    if (count == 2 && code[1] < code[0]) {
      std::swap(code[0], code[1]);
      std::swap(seg[0], seg[1]);
    }
    if (seg_out) seg_out[0] = seg[0], seg_out[1] = seg[1];
    return code[0] | (code[1] << kKeyCodeBits);
  }
};

inline uint32_t field_key(const std::vector<Crack2D>& cracks, const Vec<2>& x, const Vec<2>& xn) {
  FieldKeyBuilder b;
  for (const auto& c : cracks) {
    const Side side = crack_crossing(c, x, xn);
    if (side != Side::None && !b.add(c.id, side)) return kFieldKeyOverflow;
  }
  return b.key();
}

// Parses the scene key "cracks" (key_path is its scene path, normally "cracks"): an array of
//   { "name": string, "points": [[x, y], ...], "contact": {...} }        (polyline, >= 2 points)
//   { "name": string, "from": [x, y], "to": [x, y], "segment_length": L, "contact": {...} }
//        (a straight crack split into ceil(|to - from| / L) equal segments; the ratio is rounded
//         down to an integer when within 1e-9 relative of it, so 1.1 / 0.1 gives 11 segments)
// with the optional "contact": {"law": "stick" | "frictionless" | "friction" | "none", "mu": number,
// "detection": "volume" | "displacement", "v_sep": number, "v_contact": number} and the optional
// "tips": "auto" | "both" | "start" | "end" | "none" (which ends are crack tips; default auto)
// ("law" required inside "contact"; "mu" required and >= 0 for "friction", rejected otherwise;
// default frictionless; detection default "volume" with v_sep 0.9 < 1 < v_contact 1.1, the two
// critical volumes only valid with "volume"). above/below start equal to points; simplices are the
// polyline's segments (i, i + 1). length_scale (scene length unit -> metres) multiplies coordinates and
// segment_length. id = index in the array. Throws cleave::SceneError naming the key path (e.g.
// "cracks[1].points[2]") for: not an array / not an object, missing name or points, empty or
// duplicate name, both or neither of the two forms, fewer than 2 points, non-numeric or non-finite
// coordinates, a zero-length segment (consecutive equal points, or from == to), a self-intersecting
// polyline ("cracks[i].points": two non-adjacent segments that intersect or touch, or adjacent
// segments that fold back onto each other), more than 1,000,000 segments, unknown contact law
// (the valid ones are listed), mu missing / negative / given without "friction", unknown keys.
// Throws std::invalid_argument if length_scale is not finite and > 0 (a caller bug).
// Checks that need the model (a crack outside every body or the grid) are the scene reader's.
std::vector<Crack2D> parse_cracks(const nlohmann::json& cracks, const std::string& key_path,
                                  double length_scale);

// Contact laws by scene name ("contact": {"law": ...}). The crack module's hot loops switch on the
// enum, once per pass; this table is the name <-> law mapping that the reader consults (so an
// unknown name lists the registered ones) and the CLI prints. takes_mu: the law needs "mu".
struct ContactLawStyle {
  ContactLaw law;
  bool takes_mu;
};
using ContactLaws = NameTable<ContactLawStyle>;

// The scene name of a contact law ("stick", "frictionless", "friction", "none").
const char* contact_law_name(ContactLaw law);

// Sets the crack's simplices to its polyline's segments (i, i + 1), after its points changed.
inline void set_polyline_segments(Crack2D& c) {
  c.simplices.clear();
  for (std::size_t k = 0; k + 1 < c.points.size(); ++k)
    c.simplices.push_back({static_cast<int32_t>(k), static_cast<int32_t>(k + 1)});
}

// Exact closed-segment intersection test (shared end points count): used by the
// self-intersection check and exposed for tests.
bool segments_intersect(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c, const Vec<2>& d);

}  // namespace cleave::crack

// Registers a contact law under its scene name; rank orders the list of valid laws.
#define CLEAVE_REGISTER_CONTACT_LAW(name, rank, law, takes_mu)                          \
  namespace {                                                                           \
  [[maybe_unused]] const bool CLEAVE_REGISTRAR(cleave_contact_law_) =                   \
      ::cleave::crack::ContactLaws::instance().add(                                     \
          name,                                                                         \
          ::cleave::crack::ContactLawStyle{::cleave::crack::ContactLaw::law, takes_mu},     \
          rank);                                                                        \
  }
