#include "libmpm/crack/crack2d.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "libmpm/core/error.hpp"
#include "libmpm/core/json_reader.hpp"
#include "libmpm/crack/contact_keys.hpp"

namespace cleave::crack {

// The laws the crack module implements (crack_fields.hpp), in the order the documentation lists them.
CLEAVE_REGISTER_CONTACT_LAW("stick", 1, Stick, false)
CLEAVE_REGISTER_CONTACT_LAW("frictionless", 2, Frictionless, false)
CLEAVE_REGISTER_CONTACT_LAW("friction", 3, Friction, true)
CLEAVE_REGISTER_CONTACT_LAW("none", 4, None, false)

const char* contact_law_name(ContactLaw law) {
  const char* name = "?";
  ContactLaws::instance().each([&](const std::string& n, const ContactLawStyle& s) {
    if (s.law == law) name = n.c_str();  // the table's own key: lives as long as the program
  });
  return name;
}

namespace {

constexpr std::size_t kMaxSegments = 1000000;

// c is exactly collinear with a-b: is it inside the segment's closed box (hence on the segment)?
bool within(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c) {
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
}

int sign_of(double v) { return (v > 0.0) - (v < 0.0); }

// Adjacent segments a->b->c fold back onto each other: exactly collinear and reversing direction.
// (The sign of a floating difference is exact, so the direction test is exact too.)
bool folds_back(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c) {
  if (area_sign(a, b, c) != 0) return false;
  return sign_of(b.x() - a.x()) * sign_of(c.x() - b.x()) < 0 ||
         sign_of(b.y() - a.y()) * sign_of(c.y() - b.y()) < 0;
}

void check_simple(const std::vector<Vec<2>>& p, const std::string& path) {
  const std::size_t nseg = p.size() - 1;
  auto seg = [&](std::size_t i) {
    return "segment " + std::to_string(i) + " (points[" + std::to_string(i) + "] to points[" +
           std::to_string(i + 1) + "])";
  };
  for (std::size_t i = 0; i + 1 < nseg; ++i)
    if (folds_back(p[i], p[i + 1], p[i + 2]))
      throw SceneError(path, "self-intersecting crack: " + seg(i + 1) + " folds back onto " + seg(i));
  // Non-adjacent pairs, with a box prefilter (exact: comparisons only).
  for (std::size_t i = 0; i < nseg; ++i) {
    const Vec<2> lo = p[i].cwiseMin(p[i + 1]), hi = p[i].cwiseMax(p[i + 1]);
    for (std::size_t j = i + 2; j < nseg; ++j) {
      const Vec<2> lo2 = p[j].cwiseMin(p[j + 1]), hi2 = p[j].cwiseMax(p[j + 1]);
      if ((lo.array() > hi2.array()).any() || (lo2.array() > hi.array()).any()) continue;
      if (segments_intersect(p[i], p[i + 1], p[j], p[j + 1]))
        throw SceneError(path, "self-intersecting crack: " + seg(i) + " and " + seg(j) +
                                   " intersect or touch");
    }
  }
}

std::vector<Vec<2>> read_points(const ObjectReader& r, double scale) {
  const std::string path = r.at("points");
  const nlohmann::json& pts = r["points"];
  if (!pts.is_array()) throw SceneError(path, "expected an array of points [[x, y], ...]");
  if (pts.size() < 2)
    throw SceneError(path, "a crack needs at least 2 points (got " + std::to_string(pts.size()) + ")");
  if (pts.size() - 1 > kMaxSegments)
    throw SceneError(path, "too many points (at most " + std::to_string(kMaxSegments + 1) + ")");
  std::vector<Vec<2>> out;
  out.reserve(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const std::string pi = index_path(path, i);
    out.push_back(ObjectReader::vec_of<2>(pts[i], pi, scale));
    if (!out.back().allFinite()) throw SceneError(pi, "coordinates overflow after unit scaling");
    if (i > 0 && out[i] == out[i - 1])
      throw SceneError(pi, "zero-length crack segment (same point as points[" + std::to_string(i - 1) + "])");
  }
  check_simple(out, path);
  return out;
}

std::vector<Vec<2>> read_straight(const ObjectReader& r, double scale) {
  const Vec<2> from = r.vec<2>("from", scale);
  const Vec<2> to = r.vec<2>("to", scale);
  const double len = r.positive("segment_length", scale);
  if (!from.allFinite()) throw SceneError(r.at("from"), "coordinates overflow after unit scaling");
  if (!to.allFinite()) throw SceneError(r.at("to"), "coordinates overflow after unit scaling");
  if (to == from) throw SceneError(r.at("to"), "zero-length crack (same point as \"from\")");
  const double ratio = (to - from).norm() / len;
  if (!std::isfinite(ratio) || ratio > static_cast<double>(kMaxSegments))
    throw SceneError(r.at("segment_length"), "too small: more than " + std::to_string(kMaxSegments) +
                                                 " segments");
  const double nearest = std::round(ratio);
  const double n_real = std::abs(ratio - nearest) <= 1e-9 * ratio ? nearest : std::ceil(ratio);
  const std::size_t n = std::max<std::size_t>(1, static_cast<std::size_t>(n_real));
  std::vector<Vec<2>> out(n + 1);
  for (std::size_t k = 0; k <= n; ++k)
    out[k] = from + (to - from) * (static_cast<double>(k) / static_cast<double>(n));
  out[n] = to;
  for (std::size_t k = 1; k <= n; ++k)
    if (out[k] == out[k - 1])
      throw SceneError(r.at("segment_length"), "too small for the coordinates' precision");
  return out;
}

}  // namespace

template <int Dim>
void read_crack_contact(const ObjectReader& cr, ExplicitCrack<Dim>& c) {
  const ObjectReader r(cr["contact"], cr.at("contact"), {"law", "mu", "detection", "v_sep", "v_contact"});
  read_contact_settings(r, c, false);
}
template void read_crack_contact<2>(const ObjectReader&, ExplicitCrack<2>&);
template void read_crack_contact<3>(const ObjectReader&, ExplicitCrack<3>&);

double read_tip_cut(const ObjectReader& r, double fallback) {
  const double cut = r.number_or("tip_cut", fallback);
  if (!(cut >= 0.0 && cut <= 1.0))
    throw SceneError(r.at("tip_cut"), "must lie in [0, 1] cells (got " + r["tip_cut"].dump() + ")");
  return cut;
}

void read_contact_settings(const ObjectReader& r, ContactSettings& c, bool bodies) {
  const std::string law = r.string("law");
  const ContactLaws& laws = ContactLaws::instance();
  const ContactLawStyle* style = laws.find(law);
  if (!style) throw SceneError(r.at("law"), "unknown contact law \"" + law + "\"; valid laws: " + laws.names_joined());
  c.contact_law = style->law;
  if (style->takes_mu) {
    if (!r.has("mu")) throw SceneError(r.at("mu"), "missing (required for law \"" + law + "\")");
    const double mu = r.number("mu");
    if (!(mu >= 0.0)) throw SceneError(r.at("mu"), "must be >= 0 (got " + r["mu"].dump() + ")");
    c.friction = mu;
  } else if (r.has("mu")) {
    auto with_mu = laws.names_where([](const std::string&, const ContactLawStyle& s) { return s.takes_mu; });
    for (auto& n : with_mu) n = "\"" + n + "\"";
    throw SceneError(r.at("mu"), "only valid with law " + join_names(with_mu, " or ") + " (law is \"" + law + "\")");
  }
  // Crack faces: volume (default) or displacement; bodies: position (default) or volume.
  const char* valid = bodies ? "position, volume" : "volume, displacement";
  const std::string det = r.string_or("detection", bodies ? "position" : "volume");
  for (const char* k : {"v_sep", "v_contact"})
    if (r.has(k) && det != "volume") throw SceneError(r.at(k), "only valid with detection \"volume\"");
  if (r.has("d_contact") && det != "position") throw SceneError(r.at("d_contact"), "only valid with detection \"position\"");
  if (det == "volume") {
    c.detection = Detection::Volume;
    c.v_sep = r.number_or("v_sep", 0.9);
    c.v_contact = r.number_or("v_contact", 1.1);
    if (!(c.v_sep > 0.0 && c.v_sep < 1.0))
      throw SceneError(r.at("v_sep"), "must lie between 0 and 1 (relative nodal volume below which faces are apart)");
    if (!(c.v_contact > 1.0 && std::isfinite(c.v_contact)))
      throw SceneError(r.at("v_contact"), "must be greater than 1 (relative nodal volume above which faces touch)");
  } else if (det == "displacement" && !bodies) {
    c.detection = Detection::Displacement;
  } else if (det == "position" && bodies) {
    c.detection = Detection::Position;
    c.d_contact = r.number_or("d_contact", c.d_contact);
    if (!(c.d_contact > 0.0 && c.d_contact <= 2.0))
      throw SceneError(r.at("d_contact"), "must lie in (0, 2] cells (the distance between the two bodies' mass "
                                          "centres at a node below which they touch)");
  } else if (det == "displacement") {
    throw SceneError(r.at("detection"), "\"displacement\" compares the displacements of two crack faces that start "
                                        "together; bodies detect contact by \"position\" (default) or \"volume\"");
  } else {
    throw SceneError(r.at("detection"), "unknown contact detection \"" + det + "\"; valid: " + valid);
  }
}

bool segments_intersect(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c, const Vec<2>& d) {
  const int o1 = area_sign(a, b, c), o2 = area_sign(a, b, d);
  const int o3 = area_sign(c, d, a), o4 = area_sign(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && within(a, b, c)) || (o2 == 0 && within(a, b, d)) ||
         (o3 == 0 && within(c, d, a)) || (o4 == 0 && within(c, d, b));
}

std::vector<Crack2D> parse_cracks(const nlohmann::json& cracks, const std::string& key_path,
                                  double length_scale) {
  if (!std::isfinite(length_scale) || length_scale <= 0.0)
    throw std::invalid_argument("parse_cracks: length_scale must be finite and > 0");
  if (!cracks.is_array()) throw SceneError(key_path, "expected an array of crack objects");
  std::vector<Crack2D> out;
  out.reserve(cracks.size());
  std::map<std::string, std::size_t> names;
  for (std::size_t i = 0; i < cracks.size(); ++i) {
    const ObjectReader r(cracks[i], index_path(key_path, i),
                         {"name", "points", "from", "to", "segment_length", "contact", "tips", "propagation", "tip_cut",
                          "tip_split"});
    Crack2D c;
    c.id = static_cast<int>(i);
    c.key = index_path(key_path, i);
    c.name = r.string("name");
    if (c.name.empty()) throw SceneError(r.at("name"), "must not be empty");
    if (const auto [it, fresh] = names.emplace(c.name, i); !fresh)
      throw SceneError(r.at("name"), "duplicate crack name \"" + c.name + "\" (also " +
                                         index_path(key_path, it->second) + ")");
    const bool has_points = r.has("points");
    const bool has_straight = r.has("from") || r.has("to") || r.has("segment_length");
    if (has_points && has_straight) {
      const char* k = r.has("from") ? "from" : r.has("to") ? "to" : "segment_length";
      throw SceneError(r.at(k), "give either \"points\" or \"from\"/\"to\"/\"segment_length\", not both");
    }
    if (!has_points && !has_straight)
      throw SceneError(r.at("points"), "missing (give \"points\", or \"from\", \"to\" and \"segment_length\")");
    c.points = has_points ? read_points(r, length_scale) : read_straight(r, length_scale);
    if (r.has("contact")) read_crack_contact(r, c);
    c.tips = r.string_or("tips", "auto");
    if (c.tips != "auto" && c.tips != "both" && c.tips != "start" && c.tips != "end" && c.tips != "none")
      throw SceneError(r.at("tips"), "unknown value \"" + c.tips + "\"; valid: auto, both, start, end, none");
    // Cells by which the crossing test cuts each tip back (ExplicitCrack::update_crossing); the MPM
    // scene reader converts it to metres once the grid is known.
    c.tip_cut = read_tip_cut(r, kDefaultTipCut);
    // How the cut splits the nodes near a tip (ExplicitCrack::node_split): node by node for a growing
    // crack (its direction reads K_II / K_I), line by line otherwise.
    const std::string split = r.string_or("tip_split", r.has("propagation") ? "node" : "line");
    if (split != "node" && split != "line")
      throw SceneError(r.at("tip_split"), "unknown value \"" + split + "\"; valid: node, line");
    c.node_split = split == "node";
    c.tip[0] = c.tips == "both" || c.tips == "start" || c.tips == "auto";
    c.tip[1] = c.tips == "both" || c.tips == "end" || c.tips == "auto";
    set_polyline_segments(c);
    c.update_extent();
    c.above = c.below = c.reference = c.points;
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace cleave::crack
