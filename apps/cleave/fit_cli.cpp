// cleave fit: K_I, K_II and T from fringe-order points (viz/fit/fringe_fit.hpp), checked on a run's
// own fringes, and calibration of the fringe constant or the load scale against a run
// (viz/job/fringe_fit_job.hpp). docs/photoelasticity.md.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/cleave/cli_numbers.hpp"
#include "apps/cleave/render_cli.hpp"
#include "viz/job/fringe_fit_job.hpp"
#include "viz/job/photo_field.hpp"
#include "viz/render/headless.hpp"

namespace cleave::app {
namespace {
namespace fs = std::filesystem;
using namespace cleave::viz;

const char* kFitHelp = R"(Usage:
  cleave fit --points FILE --tip X,Y [--crack-angle DEG] --fringe-constant F --thickness MM [options]
                 K_I, K_II, T (and higher Williams terms) from digitised fringe orders
  cleave fit OUT --frame SPEC [--points FILE | --sample R0,R1] [tip] [options]
                 the same against a run: --points fitted as above with the run's tip, or --sample:
                 the run's own fringe orders at points R0..R1 from the tip, fitted and set beside
                 the K the run computed from J (a check of the method on a known K)
  cleave fit OUT --frame SPEC --points FILE --calibrate fringe-constant|load-scale [options]
                 the fringe constant (or load scale) that makes the run's fringes fit the points,
                 the other held fixed
  cleave fit OUT --frame SPEC --photo IMG --map X0,Y0,S[,A] [--radii R0,R1] [tip] [options]
                 K from a photograph: its fringe centre-lines (dark and bright lines) read as
                 points R0..R1 from the tip, their orders counted on the run's fringes (scaled by
                 the photo's calibration), and fitted
  cleave fit OUT --frame SPEC --photo IMG --map X0,Y0,S[,A] --calibrate fringe-constant|load-scale
                 the same against a photograph: the scale whose model fringes correlate best with
                 the photo's intensity (--fringes, --mask, --roi choose what is compared)

Points:
  --points FILE        "x y N" per line (comma or space separated, '#' comments): position and
                       measured fringe order (integer and half orders of the fringes' centre lines)
  --length-unit U      unit of points, --tip, --sample, --pixel-map: m, mm, cm, um (default: the
                       run's scene unit from OUT/run.json, mm without a run)
  --pixel-map X0,Y0,S[,A]  points are photo pixels (x right, y down): X0,Y0 is the model position
                       of the photo's top-left corner, S the model length per pixel, A the rotation
                       of the photo's x axis in degrees (as compare --map; --map is the same option)
  --pixel-ref U1,V1,X1,Y1,U2,V2,X2,Y2  points are photo pixels; two reference pixels (U,V) and
                       their model positions (X,Y) fix scale, rotation and origin
Tip:
  --tip X,Y            crack tip position (the start when --fit-tip)
  --crack-angle DEG    direction the crack points to at the tip, from +x (default 0)
  --crack C --tip-index I   with OUT: crack C's tip I as the run left it at the frame
                       (crack_tips.csv; default 0 and 0) when --tip is not given
  --fit-tip            the tip position as two more unknowns
  --fit-angle          the crack direction as one more unknown
Model:
  --terms N            Williams terms per mode (default 5: K, T and three more; 1..8)
  --fringe-constant F  f_sigma in N/mm/fringe (F,kgf for kgf/mm/fringe)   --thickness MM   in mm
  --fringes MODE       the photo's polariscope: dark (default), light, crossed, parallel
Photo (calibration):
  --photo IMG          PNG or JPEG photograph, mapped by --map; with --points in pixels, points
                       outside it are refused
  --mask IMG           compare only where this image (the photo's size) is white
  --roi X0,Y0,X1,Y1    compare only inside this box (in --length-unit)
  --sample R0,R1       with OUT: points on 9 rings from R0 to R1 (in --length-unit) every 10 degrees
  --smooth S           with OUT: the run's stress smoothed over S particle spacings as cleave render
                       draws it (default 0: the particles' stresses as written; smoothing flattens
                       the singular field and reads K low, 5-15 % at 1.5 spacings)
Output:
  --out PREFIX         PREFIX_points.csv (per point: position, measured and model order,
                       residual), PREFIX_parameters.csv (value, standard error, 95 % interval)
                       (default: no files)

Exit status: 0 fitted; 2 bad input (too few points, points off the body, a parameter the points do
not determine); 3 the fit did not converge.
)";

struct FitArgs {
  std::optional<fs::path> run, points, out;
  std::string frame = "last";
  std::optional<std::vector<double>> tip, sample, pixel_map, pixel_ref, roi, window;
  std::optional<fs::path> photo, mask;
  Polariscope mode = Polariscope::CircularDark;
  double angle_deg = 0, f_nmm = 0, t_mm = 0;
  int crack = 0, tip_index = 0, terms = 5;
  bool fit_tip = false, fit_angle = false;
  double smooth = 0;
  std::string calibrate, unit;
};

double unit_factor(const std::string& u) {
  if (u == "m") return 1.0;
  if (u == "mm") return 1e-3;
  if (u == "cm") return 1e-2;
  if (u == "um") return 1e-6;
  throw std::invalid_argument("--length-unit must be m, mm, cm or um, not '" + u + "'");
}

// Points file to model coordinates (m): lengths in the unit L, or photo pixels through a map.
std::vector<FringePoint> model_points(const FitArgs& a, double L) {
  std::vector<FringePoint> pts;
  std::vector<std::array<double, 3>> raw;
  try {
    raw = read_fringe_points(*a.points);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(e.what());  // bad input: exit 2
  }
  for (const auto& p : raw) pts.push_back({p[0], p[1], p[2]});
  double x0 = 0, y0 = 0, s = L, ang = 0;
  bool pixels = false;
  if (a.pixel_map) {
    const auto& m = *a.pixel_map;
    if (!(m[2] > 0)) throw std::invalid_argument("--pixel-map: the length per pixel must be positive");
    x0 = m[0] * L, y0 = m[1] * L, s = m[2] * L, ang = m.size() > 3 ? m[3] * std::numbers::pi / 180 : 0.0, pixels = true;
  } else if (a.pixel_ref) {
    const auto& r = *a.pixel_ref;
    const double du = r[4] - r[0], dv = -(r[5] - r[1]), dx = (r[6] - r[2]) * L, dy = (r[7] - r[3]) * L;
    const double dp = std::hypot(du, dv), dm = std::hypot(dx, dy);
    if (!(dp > 0) || !(dm > 0)) throw std::invalid_argument("--pixel-ref: the two reference points must differ");
    s = dm / dp, ang = std::atan2(dy, dx) - std::atan2(dv, du);
    // Origin: the model position of pixel (0, 0), from the first reference.
    const double c = std::cos(ang), sn = std::sin(ang), u = r[0] * s, v = -r[1] * s;
    x0 = r[2] * L - (c * u - sn * v), y0 = r[3] * L - (sn * u + c * v), pixels = true;
  }
  if (pixels && a.photo) {
    Image photo;
    try {
      photo = read_image(*a.photo);
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(e.what());
    }
    for (std::size_t k = 0; k < pts.size(); ++k)
      if (pts[k].x < 0 || pts[k].y < 0 || pts[k].x > photo.width || pts[k].y > photo.height)
        throw std::invalid_argument("point " + std::to_string(k + 1) + " (" + std::to_string(pts[k].x) + ", " +
                                    std::to_string(pts[k].y) + ") px lies outside the " + std::to_string(photo.width) +
                                    "x" + std::to_string(photo.height) + " photo");
  }
  if (pixels) {
    const double c = std::cos(ang), sn = std::sin(ang);
    for (auto& p : pts) {
      const double u = p.x * s, v = -p.y * s;  // y down in the photo
      p.x = x0 + c * u - sn * v, p.y = y0 + sn * u + c * v;
    }
  } else {
    for (auto& p : pts) p.x *= L, p.y *= L;
  }
  return pts;
}

void write_csvs(const fs::path& prefix, const std::vector<FringePoint>& pts, const FringeFitResult& r) {
  const TipField& f = r.field;
  std::ofstream p(prefix.string() + "_points.csv");
  p << "x_m,y_m,r_m,theta_deg,N_measured,N_model,residual\n";
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const double dx = pts[k].x - f.x0, dy = pts[k].y - f.y0;
    const double th = std::remainder(std::atan2(dy, dx) - f.alpha, 2 * std::numbers::pi);
    p << pts[k].x << ',' << pts[k].y << ',' << std::hypot(dx, dy) << ',' << th * 180 / std::numbers::pi << ','
      << pts[k].N << ',' << r.model_N[k] << ',' << r.residual[k] << '\n';
  }
  std::ofstream q(prefix.string() + "_parameters.csv");
  q << "name,unit,value,std_error,ci95_low,ci95_high\n";
  for (const auto& e : r.parameters)
    q << e.name << ',' << e.unit << ',' << e.value << ',' << e.std_error << ',' << e.value - 1.96 * e.std_error << ','
      << e.value + 1.96 * e.std_error << '\n';
  if (!p || !q) throw std::runtime_error(prefix.string() + "_*.csv: cannot write");
}

void print_fit(const FringeFitResult& r, std::size_t n_points, const FringeFitOptions& o) {
  std::printf("fit of %zu points, %d Williams term%s per mode, tip (%.4f, %.4f) mm %s, crack direction %.2f deg %s\n",
              n_points, o.terms, o.terms == 1 ? "" : "s", r.field.x0 * 1e3, r.field.y0 * 1e3, o.fit_tip ? "fitted" : "given",
              r.field.alpha * 180 / std::numbers::pi, o.fit_angle ? "fitted" : "given");
  for (const auto& e : r.parameters) {
    double k = 1;
    std::string u = e.unit;
    if (e.name == "K_I" || e.name == "K_II") k = 1e-6, u = "MPa m^0.5";
    else if (e.name == "T") k = 1e-6, u = "MPa";
    else if (e.name == "x0" || e.name == "y0") k = 1e3, u = "mm";
    else if (e.name == "alpha") k = 180 / std::numbers::pi, u = "deg";
    std::printf("  %-5s = %.6g +- %.2g %s (95 %%: %.6g .. %.6g)\n", e.name.c_str(), e.value * k, e.std_error * k, u.c_str(),
                (e.value - 1.96 * e.std_error) * k, (e.value + 1.96 * e.std_error) * k);
  }
  std::printf("  RMS residual %.4f fringe orders (%d degrees of freedom, %d iterations)", r.rms, r.degrees_of_freedom,
              r.iterations);
  // Per order where the points are digitised fringes (orders in quarter steps), not sampled values.
  bool digitised = r.orders.size() <= 40;
  for (const auto& s : r.orders) digitised = digitised && std::abs(4 * s.N - std::round(4 * s.N)) < 1e-9;
  if (digitised) {
    std::printf("; per order (RMS, points):");
    for (const auto& s : r.orders) std::printf(" %g: %.3f (%zu)", s.N, s.rms, s.count);
  }
  std::printf("\n");
}

void print_irwin(const std::vector<FringePoint>& pts, const FringeFitResult& r, const FringeFitOptions& o) {
  const auto est = irwin_two_point(pts, r.field.x0, r.field.y0, r.field.alpha, o.fringe_constant, o.thickness);
  if (est.empty()) {
    std::printf("Irwin two-point: no fringe loop with its apogee between the points (needs points along a loop)\n");
    return;
  }
  std::printf("Irwin two-point (cross-check, K and sigma_ox from each loop's apogee):\n");
  for (const auto& e : est)
    std::printf("  order %g: K_I %.5g MPa m^0.5, sigma_ox %.4g MPa (r_m %.3f mm, theta_m %.1f deg)\n", e.N, e.KI * 1e-6,
                e.sigma_ox * 1e-6, e.r_m * 1e3, e.theta_m * 180 / std::numbers::pi);
}

std::string format_se(double se) {
  char b[48];
  std::snprintf(b, sizeof b, "; +- %.2g", se);
  return b;
}

// The calibrated scale as a fringe constant or a load scale; se 0: no standard error (a photo).
void print_scale(const FitArgs& a, double scale, double se) {
  if (a.calibrate == "fringe-constant")
    std::printf("  fringe constant that fits: %.5g N/mm/fringe (%.5g kgf/mm/fringe%s; given %.5g)\n", a.f_nmm / scale,
                a.f_nmm / scale / 9.80665, se > 0 ? format_se(a.f_nmm * se / (scale * scale)).c_str() : "", a.f_nmm);
  else
    std::printf("  load scale that fits: %.5f%s: the run's loads x that (stresses are linear in the load for an "
                "elastic static run)\n", scale, se > 0 ? format_se(se).c_str() : "");
}

// The photo against the run's frame: where it lies (--map), the pixels compared (--mask, --roi), and
// the scale that fits its fringes.
struct PhotoInput {
  PhotoMap map;
  Image photo;
  PhotoField field;
  std::vector<uint8_t> use;
  PhotoCalibration calibration;
};
PhotoInput photo_input(const FitArgs& a, const ParticleFrame& frame, const PhotoelasticSettings& ps, double L) {
  if (!a.pixel_map) throw std::invalid_argument("--photo needs --map X0,Y0,S[,A] (where the photo lies on the model)");
  const auto& m = *a.pixel_map;
  if (!(m[2] > 0)) throw std::invalid_argument("--map: the length per pixel must be positive");
  PhotoInput in;
  in.map = {m[0] * L, m[1] * L, m[2] * L, m.size() > 3 ? m[3] * std::numbers::pi / 180 : 0.0};
  Image mask;
  try {
    in.photo = read_image(*a.photo);
    if (a.mask) mask = read_image(*a.mask);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(e.what());
  }
  std::optional<std::array<double, 4>> roi;
  if (a.roi) roi = std::array<double, 4>{(*a.roi)[0] * L, (*a.roi)[1] * L, (*a.roi)[2] * L, (*a.roi)[3] * L};
  in.field = photo_field(frame, in.photo.width, in.photo.height, in.map);
  in.use = compared_pixels(in.field, in.map, a.mask ? &mask : nullptr, roi);
  in.calibration = calibrate_to_photo(in.photo, in.field, in.use, ps);
  return in;
}

int calibrate_photo(const FitArgs& a, const ParticleFrame& frame, const PhotoelasticSettings& ps, double L) {
  const PhotoCalibration c = photo_input(a, frame, ps, L).calibration;
  std::printf("calibration on %zu photo pixels at t = %.6g s: the photo's fringes are those of the run's stresses x "
              "%.5f (intensity correlation %.4f there, %.4f at 1)\n", c.pixels, frame.time, c.scale, c.ncc, c.ncc_at_one);
  print_scale(a, c.scale, 0.0);
  return 0;
}

// The photo's fringe centre-lines as points (orders from the run, scaled by the photo's calibration),
// fitted as digitised points are.
int fit_photo(const FitArgs& a, const ParticleFrame& frame, const PhotoelasticSettings& ps, FringeFitOptions o, double L) {
  const PhotoInput in = photo_input(a, frame, ps, L);
  std::optional<RunTip> rt;
  if (!a.tip) {
    rt = run_tip(*a.run, frame.time, a.crack, a.tip_index);
    o.x0 = rt->x, o.y0 = rt->y, o.alpha = rt->alpha;
  }
  const double r0 = a.window ? (*a.window)[0] * L : 0.0, r1 = a.window ? (*a.window)[1] * L : 1e300;
  const auto pts = extract_fringe_points(in.photo, in.field, in.map, in.use, ps, in.calibration.scale, o.x0, o.y0, r0, r1);
  std::printf("read %zu fringe centre-line points from the photo (orders from the run's fringes x %.4f, the photo's "
              "calibration; intensity correlation %.4f)\n", pts.size(), in.calibration.scale, in.calibration.ncc);
  const auto r = fit_fringe_orders(pts, o);
  print_fit(r, pts.size(), o);
  print_irwin(pts, r, o);
  if (rt)
    std::printf("run: K_I %.6g MPa m^0.5 from J at t = %.6g s; photo fit / run K_I = %.4f\n", rt->KI * 1e-6, rt->time,
                r.parameter("K_I").value / rt->KI);
  if (a.out) write_csvs(*a.out, pts, r);
  return 0;
}

int fit(const FitArgs& a) {
  if (!(a.f_nmm > 0)) throw std::invalid_argument("fit needs --fringe-constant F (N/mm/fringe, > 0)");
  if (!(a.t_mm > 0)) throw std::invalid_argument("fit needs --thickness MM (> 0)");
  if ((a.pixel_map || a.pixel_ref) && !a.points && !a.photo)
    throw std::invalid_argument("--pixel-map (--map) and --pixel-ref are for --points and --photo");
  if (a.pixel_map && a.pixel_ref) throw std::invalid_argument("give --pixel-map or --pixel-ref, not both");
  const std::string unit = !a.unit.empty() ? a.unit : a.run ? run_length_unit(*a.run) : "mm";
  const double L = unit_factor(unit);
  PhotoelasticSettings ps;
  ps.fringe_constant = a.f_nmm * 1e3, ps.thickness = a.t_mm * 1e-3, ps.mode = a.mode;
  FringeFitOptions o;
  o.terms = a.terms, o.fit_tip = a.fit_tip, o.fit_angle = a.fit_angle;
  o.fringe_constant = ps.fringe_constant, o.thickness = ps.thickness;
  o.alpha = a.angle_deg * std::numbers::pi / 180;
  if (a.tip) o.x0 = (*a.tip)[0] * L, o.y0 = (*a.tip)[1] * L;

  if (!a.run) {
    if (!a.points) throw std::invalid_argument("fit needs --points FILE (or a run folder OUT with --sample)");
    if (!a.tip) throw std::invalid_argument("fit needs --tip X,Y (the crack tip; add --fit-tip to fit it)");
    if (!a.calibrate.empty()) throw std::invalid_argument("--calibrate needs a run folder OUT to scale");
    if (a.sample) throw std::invalid_argument("--sample needs a run folder OUT to sample");
    const auto pts = model_points(a, L);
    const auto r = fit_fringe_orders(pts, o);
    print_fit(r, pts.size(), o);
    print_irwin(pts, r, o);
    if (a.out) write_csvs(*a.out, pts, r);
    return 0;
  }

  RenderOptions ro;
  ro.series = *a.run;
  ro.smooth = a.smooth;
  const auto entries = read_series(ro.series);
  const auto sel = select_frames(entries, a.frame);
  if (sel.size() != 1) throw std::invalid_argument("fit needs exactly one frame (--frame time:T, last, index:I)");
  const auto& e = entries[sel[0]];
  const ParticleFrame frame = drawn_frame(read_particle_frame(e.file, e.time), ro);
  if (frame.dim != 2) throw std::invalid_argument("fit works on 2D runs (fringes of a plane specimen)");

  if (!a.calibrate.empty()) {
    if (a.calibrate != "fringe-constant" && a.calibrate != "load-scale")
      throw std::invalid_argument("--calibrate must be fringe-constant or load-scale, not '" + a.calibrate + "'");
    if (a.photo && !a.points) return calibrate_photo(a, frame, ps, L);
    if (!a.points) throw std::invalid_argument("--calibrate needs --points FILE (the measured orders) or --photo IMG");
    const auto pts = model_points(a, L);
    const Calibration c = calibrate_scale(frame, ps, pts);
    std::printf("calibration on %zu points at t = %.6g s: measured orders = %.5f x the run's (+- %.2g)\n", c.points,
                frame.time, c.scale, c.std_error);
    print_scale(a, c.scale, c.std_error);
    std::printf("  RMS residual %.4f fringe orders before, %.4f after\n", c.rms_before, c.rms_after);
    return 0;
  }

  if (a.photo && !a.points && !a.sample) return fit_photo(a, frame, ps, o, L);
  std::optional<RunTip> rt;
  if (!a.tip) {
    rt = run_tip(*a.run, frame.time, a.crack, a.tip_index);
    o.x0 = rt->x, o.y0 = rt->y, o.alpha = rt->alpha;
  }
  std::vector<FringePoint> pts;
  if (a.sample) {
    if (a.points) throw std::invalid_argument("give --points or --sample, not both");
    const double r0 = (*a.sample)[0] * L, r1 = (*a.sample)[1] * L;
    if (!(r0 > 0 && r1 > r0)) throw std::invalid_argument("--sample needs 0 < R0 < R1");
    pts = sampled_points(frame, ps, o.x0, o.y0, o.alpha, r0, r1);
    std::printf("sampled the run's fringe orders at %zu points %.4g..%.4g %s from the tip at t = %.6g s\n", pts.size(),
                (*a.sample)[0], (*a.sample)[1], unit.c_str(), frame.time);
  } else if (a.points) {
    pts = model_points(a, L);
  } else {
    throw std::invalid_argument("fit OUT needs --points FILE or --sample R0,R1");
  }
  const auto r = fit_fringe_orders(pts, o);
  print_fit(r, pts.size(), o);
  print_irwin(pts, r, o);
  if (!rt && a.sample) {
    try {
      rt = run_tip(*a.run, frame.time, a.crack, a.tip_index);
    } catch (const std::exception&) {
    }
  }
  if (rt)
    std::printf("run: K_I %.6g MPa m^0.5, K_II %.4g MPa m^0.5 from J at t = %.6g s (crack_tips.csv); fit / run K_I = %.4f\n",
                rt->KI * 1e-6, rt->KII * 1e-6, rt->time, r.parameter("K_I").value / rt->KI);
  if (a.out) write_csvs(*a.out, pts, r);
  return 0;
}

}  // namespace

int fit_command(const std::vector<std::string>& args) {
  FitArgs a;
  try {
    std::size_t i = 1;
    if (args.size() < 2 || args[1] == "--help" || args[1] == "-h") {
      std::fputs(kFitHelp, args.size() < 2 ? stderr : stdout);
      return args.size() < 2 ? 2 : 0;
    }
    if (!args[1].starts_with("-")) a.run = args[1], i = 2;
    for (; i < args.size(); ++i) {
      const std::string& s = args[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= args.size()) throw std::invalid_argument(s + " needs a value");
        return args[++i];
      };
      auto whole = [&](int lo, int hi) {
        const double d = number(s, value());
        if (d != std::floor(d) || d < lo || d > hi)
          throw std::invalid_argument(s + " must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi));
        return int(d);
      };
      if (s == "--help" || s == "-h") {
        std::fputs(kFitHelp, stdout);
        return 0;
      } else if (s == "--points") a.points = value();
      else if (s == "--frame") a.frame = value();
      else if (s == "--tip") a.tip = numbers(s, value(), 2, 2);
      else if (s == "--crack-angle") a.angle_deg = number(s, value());
      else if (s == "--crack") a.crack = whole(0, 1000000);
      else if (s == "--tip-index") a.tip_index = whole(0, 1);
      else if (s == "--fit-tip") a.fit_tip = true;
      else if (s == "--fit-angle") a.fit_angle = true;
      else if (s == "--terms") a.terms = whole(1, 8);
      else if (s == "--fringe-constant") {
        const std::string v = value();
        const bool kgf = v.ends_with(",kgf");
        a.f_nmm = number(s, kgf ? v.substr(0, v.size() - 4) : v) * (kgf ? 9.80665 : 1.0);
      } else if (s == "--fringes") {
        const auto m = polariscope_from_name(value());
        if (!m || *m == Polariscope::Seed002) throw std::invalid_argument("--fringes must be dark, light, crossed or parallel");
        a.mode = *m;
      } else if (s == "--photo") a.photo = value();
      else if (s == "--mask") a.mask = value();
      else if (s == "--roi") a.roi = numbers(s, value(), 4, 4);
      else if (s == "--thickness") a.t_mm = number(s, value());
      else if (s == "--length-unit") a.unit = value(), unit_factor(a.unit);
      else if (s == "--pixel-map" || s == "--map") a.pixel_map = numbers(s, value(), 3, 4);
      else if (s == "--pixel-ref") a.pixel_ref = numbers(s, value(), 8, 8);
      else if (s == "--sample") a.sample = numbers(s, value(), 2, 2);
      else if (s == "--radii") a.window = numbers(s, value(), 2, 2);
      else if (s == "--calibrate") a.calibrate = value();
      else if (s == "--smooth") {
        a.smooth = number(s, value());
        if (!(a.smooth >= 0) || a.smooth > 20) throw std::invalid_argument("--smooth must be between 0 and 20 particle spacings");
      }
      else if (s == "--out") a.out = value();
      else throw std::invalid_argument("unknown option '" + s + "'");
    }
    return fit(a);
  } catch (const FitNotConverged& e) {
    std::fprintf(stderr, "cleave fit: %s\n", e.what());
    return 3;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "cleave fit: %s\n(see cleave fit --help)\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cleave fit: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace cleave::app
