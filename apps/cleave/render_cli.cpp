// cleave render | compare | plot: the renderer's command line (viz/job/render_job.hpp does the work).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <sstream>
#include <unistd.h>
#include <string>
#include <vector>

#include "apps/cleave/cli_numbers.hpp"
#include "apps/cleave/render_cli.hpp"
#include "viz/job/render_job.hpp"

namespace cleave::app {
namespace {

const char* kRenderHelp = R"(Usage:
  cleave render OUT [options]      images (and a movie) of the particle series in OUT
  cleave compare OUT --photo IMG --frame SPEC --map X0,Y0,SCALE[,ANGLE] [--points FILE] [options]
  cleave compare OUT --run OTHER --frame SPEC --fringes MODE [options]
                                   fringe-order RMS difference between two runs of a scene
  cleave plot OUT [--size WxH] [--images DIR] [--cod TIME] [--front-time T] [--front-axis s|phi]
                [--front-nodes I,J,...]
                                   energy (global.csv) and J/K (crack_tips.csv) plots, and K along 3D
                                   crack fronts (crack_fronts.csv): K_front.png, K_front_time.png;
                                   --cod: the crack-opening profile of the crack frame nearest TIME (s)

Frames and image:
  --frames SPEC        all (default) | every:K | time:T (nearest, seconds) | first | last | index:I
  --frame SPEC         the same, for compare (one frame)
  --size WxH           image size in pixels (default 1280x720)
  --images DIR         where PNGs go (default OUT/render)
  --length-unit U      unit of --roi, --map, --cut-plane, --slice, --view and --points: m, mm, cm,
                       um (default: the unit of the run's scene, run.json "length_unit"; m for runs
                       written before it was recorded)
  --roi X0,Y0,X1,Y1    region of interest in model coordinates
  --zoom Z             zoom about the window centre (default 1)
  --background C       white (default) | black | gray | R,G,B (0-1)
  --title TEXT         title above the image
  --no-time            no time stamp       --no-colorbar   no colour bar
Figures (2D frames and sections; all on by default, docs/rendering.md "Figures"):
  --keep-size          the image is exactly --size (default: cropped to the bodies, --size the most)
  --no-outline         no outline (default: smooth outlines in dark grey, not the particles' squares)
  --no-scale-bar       no scale bar (default: a round length with its unit below the bodies)
  --smooth S           stress smoothing width in particle spacings (default 1.5; 0: the particles'
                       stresses as written, with MPM's cell-crossing noise)
Colouring (default: principal_stress_difference, viridis; signed fields get a diverging map):
  --field NAME         sxx syy szz sxy von_mises principal_stress_difference ux uy |u| vx vy |v| damage
                       or any point array, ARRAY:K for a component
  --colormap NAME      viridis | cividis | coolwarm | gray
  --range LO,HI        fixed range in display units (stresses in MPa, displacements in mm)
  --log                logarithmic colour scale
Photoelastic fringes (per pixel from the stress at that pixel):
  --fringes MODE       dark | light (circular polariscope) | crossed | parallel (plane, with
                       isoclinics) | seed002 (cos(k_f dsigma), seed 002 eq. 23)
  --white-light        white light (CIE 1931 observer, D65): Michel-Levy colours
  --thickness MM       specimen thickness in mm (default 1; a --slice is its own thickness)
  --fringe-constant F  material fringe constant f_sigma in N/mm/fringe at the wavelength
                       (F,kgf: in kgf/mm/fringe)
  --load-scale S       stresses, strains, displacements and velocities x S: an elastic static
                       run drawn at S times its load (one run serves a load sequence)
  --stress-optic C     stress-optic coefficient in Brewster (1e-12 /Pa), instead of F
  --wavelength NM      monochromatic wavelength in nm (default 546)
  --polarizer DEG      plane polariscope axis from x, degrees (default 0)
  --kf K               seed002 constant in 1/MPa (default 0.0889)
3D series (docs/rendering.md, "3D cracks"):
  --cut-plane PX,PY,PZ,NX,NY,NZ   render the section through point P with normal N: the particle
                       layer at the plane, with the traces of the crack faces (red above, blue below)
  --slice T            with --cut-plane: a frozen-stress slice of thickness T (in --length-unit)
                       centred on the plane: the in-plane stress averaged through it, fringes with T
                       as the specimen thickness (not with --thickness)
  --opening-scale K    crack faces drawn with the opening K times what it is (default 1), over the
                       cubes (red above, blue below; shaded when K != 1) and in sections
  --camera NAME        iso (default) | xy | xz | yz   (without a cut plane: particles as cubes)
  --view PX,PY,PZ,FX,FY,FZ,UX,UY,UZ   explicit camera: position, focal point, view-up
                       (in --length-unit), perspective
Movie:
  --movie FILE         encode the frames with ffmpeg (H.264 MP4); the PNG frames are kept
  --fps N              frame rate (default 10)
3D crack fronts (plot; docs/rendering.md, "3D crack fronts: K along the front"):
  --front-time T       K_front.png at the output time nearest T (s; default the last)
  --front-axis s|phi   K_front.png against the arc length s in mm (default) or the ellipse angle
                       phi in degrees (needs the phi_rad column: an elliptical or penny reference)
  --front-nodes I,J    the nodes of K_front_time.png (KI against time), of every front (default:
                       node 0, the middle node and the last). Flagged nodes (contour incomplete)
                       break the curves and are drawn as black crosses
Photo comparison (compare):
  --photo IMG          PNG or JPEG photograph
  --map X0,Y0,S[,A]    model position of the photo's top-left corner, model length per photo
                       pixel, rotation of the photo's x axis in degrees
  --points FILE        digitised points "x y N" per line: prints the RMS fringe-order difference
  --mask IMG           compare only where this image (the photo's size) is white: leave out the
                       slit, the grips, the far field; --roi X0,Y0,X1,Y1 restricts in model units
  --out PREFIX         output prefix for PREFIX_side_by_side.png and PREFIX_overlay.png (the
                       model's fringe centre-lines over the photo: integer orders red and labelled,
                       half orders blue) (default OUT/compare)
  --run OTHER          instead of a photo: another run of the scene (another resolution, say);
                       prints the RMS of the fringe-order difference over the bodies; with --out,
                       PREFIX_difference.png shows |difference| (white 0, black 1 fringe or more)
)";

// --front-nodes I,J,...: node indices, whole numbers from 0.
std::vector<int> node_indices(const std::string& opt, const std::string& s) {
  std::vector<int> v;
  std::stringstream ss(s);
  for (std::string part; std::getline(ss, part, ',');) {
    char* end = nullptr;
    const long i = std::strtol(part.c_str(), &end, 10);
    if (part.empty() || *end != '\0' || i < 0 || i > 1000000)
      throw std::invalid_argument(opt + ": '" + part + "' is not a node index (a whole number from 0)");
    v.push_back(int(i));
  }
  if (v.empty()) throw std::invalid_argument(opt + " needs node indices, e.g. 0,12,23");
  return v;
}

double length_factor(const std::string& u) {
  return u == "m" ? 1.0 : u == "mm" ? 1e-3 : u == "cm" ? 1e-2 : u == "um" ? 1e-6 : -1.0;
}

}  // namespace

int viz_command(const std::vector<std::string>& args) {
  using namespace cleave::viz;
  if (args.size() < 2 || args[1] == "--help" || args[1] == "-h") {
    std::fputs(kRenderHelp, args.size() < 2 ? stderr : stdout);
    return args.size() < 2 ? 2 : 0;
  }
  const std::string cmd = args[0];
  RenderOptions o;
  o.series = args[1];
  double L = 1.0;
  bool unit_given = false;
  std::vector<std::pair<std::string, std::string>> coords;  // options whose numbers use --length-unit
  std::optional<std::string> photo, points, map, other_run, mask;
  std::string out_prefix;
  std::optional<double> cod_time;
  FrontPlotOptions front;
  std::string front_option;  // the first --front-* option given, for the messages of other commands
  bool thickness_given = false;
  std::optional<std::string> slice;  // in --length-unit, read once the unit is known
  double thickness_mm = 1.0, fringe_constant = 0, brewster = 0, wavelength_nm = 546, polarizer_deg = 0, kf = 0.0889;
  try {
    for (std::size_t i = 2; i < args.size(); ++i) {
      const std::string& a = args[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= args.size()) throw std::invalid_argument(a + " needs a value");
        return args[++i];
      };
      if (a.starts_with("--front-") && front_option.empty()) front_option = a;
      if (a == "--help" || a == "-h") {
        std::fputs(kRenderHelp, stdout);
        return 0;
      } else if (a == "--frames" || a == "--frame") o.frames = value();
      else if (a == "--size") {
        const std::string v = value();
        const auto x = v.find('x');
        if (x == std::string::npos) throw std::invalid_argument("--size needs WxH, e.g. 1920x1080");
        o.width = int(number("--size", v.substr(0, x)));
        o.height = int(number("--size", v.substr(x + 1)));
        if (o.width < 16 || o.height < 16 || o.width > 16384 || o.height > 16384)
          throw std::invalid_argument("--size must be between 16 and 16384 pixels each way");
      } else if (a == "--images") o.image_dir = value();
      else if (a == "--length-unit") {
        const std::string u = value();
        L = length_factor(u);
        if (L < 0) throw std::invalid_argument("--length-unit must be m, mm, cm or um");
        unit_given = true;
      } else if (a == "--roi" || a == "--cut-plane") coords.push_back({a, value()});
      else if (a == "--zoom") {
        o.zoom = number(a, value());
        if (!(o.zoom > 0)) throw std::invalid_argument("--zoom must be positive");
      } else if (a == "--background") {
        const std::string v = value();
        if (v == "white") o.background = {1, 1, 1};
        else if (v == "black") o.background = {0, 0, 0};
        else if (v == "gray" || v == "grey") o.background = {0.5, 0.5, 0.5};
        else {
          const auto c = numbers(a, v, 3, 3);
          o.background = {c[0], c[1], c[2]};
        }
      } else if (a == "--title") o.title = value();
      else if (a == "--no-time") o.time_stamp = false;
      else if (a == "--no-colorbar") o.colorbar = false;
      else if (a == "--keep-size") o.tight = false;
      else if (a == "--no-outline") o.outline = false;
      else if (a == "--no-scale-bar") o.scale_bar = false;
      else if (a == "--smooth") {
        o.smooth = number(a, value());
        if (!(o.smooth >= 0) || o.smooth > 20) throw std::invalid_argument("--smooth must be between 0 and 20 particle spacings");
      }
      else if (a == "--field") o.field = value();
      else if (a == "--colormap") o.colormap = value();
      else if (a == "--range") {
        const auto r = numbers(a, value(), 2, 2);
        if (!(r[1] > r[0])) throw std::invalid_argument("--range needs LO < HI");
        o.range = std::array<double, 2>{r[0], r[1]};
      } else if (a == "--log") o.log_scale = true;
      else if (a == "--fringes") {
        const std::string m = value();
        const auto p = polariscope_from_name(m);
        if (!p) throw std::invalid_argument("--fringes must be dark, light, crossed, parallel or seed002");
        o.fringes = true;
        o.photo.mode = *p;
      } else if (a == "--white-light") o.photo.white_light = o.fringes = true;
      else if (a == "--thickness") thickness_mm = number(a, value()), thickness_given = true;
      else if (a == "--slice") slice = value();
      else if (a == "--opening-scale") {
        o.opening_scale = number(a, value());
        if (!(o.opening_scale > 0)) throw std::invalid_argument("--opening-scale must be positive (1: the opening as it is)");
      }
      else if (a == "--fringe-constant") {
        const std::string v = value();
        const bool kgf = v.ends_with(",kgf");  // kgf/mm/fringe, as many fringe-constant tables give it
        fringe_constant = number(a, kgf ? v.substr(0, v.size() - 4) : v) * (kgf ? 9.80665 : 1.0);
      } else if (a == "--load-scale") {
        o.load_scale = number(a, value());
        if (!(o.load_scale > 0)) throw std::invalid_argument("--load-scale must be positive");
      }
      else if (a == "--stress-optic") brewster = number(a, value());
      else if (a == "--wavelength") wavelength_nm = number(a, value());
      else if (a == "--polarizer") polarizer_deg = number(a, value());
      else if (a == "--kf") kf = number(a, value());
      else if (a == "--camera") o.camera = value();
      else if (a == "--view") coords.push_back({a, value()});
      else if (a == "--cod") cod_time = number(a, value());
      else if (a == "--front-time") {
        front.time = number(a, value());
        if (!(*front.time >= 0)) throw std::invalid_argument("--front-time must be a time >= 0 (s)");
      } else if (a == "--front-axis") {
        const std::string v = value();
        if (v == "s") front.axis = FrontAxis::ArcLength;
        else if (v == "phi") front.axis = FrontAxis::EllipseAngle;
        else throw std::invalid_argument("--front-axis must be s (arc length) or phi (ellipse angle), not '" + v + "'");
      } else if (a == "--front-nodes") front.nodes = node_indices(a, value());
      else if (a == "--movie") o.movie = std::filesystem::path(value());
      else if (a == "--fps") {
        o.fps = int(number(a, value()));
        if (o.fps < 1 || o.fps > 240) throw std::invalid_argument("--fps must be between 1 and 240");
      } else if (a == "--photo") photo = value();
      else if (a == "--points") points = value();
      else if (a == "--mask") mask = value();
      else if (a == "--map") map = value();
      else if (a == "--run") other_run = value();
      else if (a == "--out") out_prefix = value();
      else throw std::invalid_argument("unknown option '" + a + "'");
    }
    // Without --length-unit: the unit the run's scene was written in (run.json), m for older runs.
    if (!unit_given) L = std::max(0.0, length_factor(run_length_unit(o.series)));
    if (!(L > 0)) L = 1.0;
    for (const auto& [opt, v] : coords) {
      if (opt == "--roi") {
        const auto r = numbers(opt, v, 4, 4);
        if (!(r[2] > r[0] && r[3] > r[1])) throw std::invalid_argument("--roi needs X0 < X1 and Y0 < Y1");
        o.roi = std::array<double, 4>{r[0] * L, r[1] * L, r[2] * L, r[3] * L};
      } else if (opt == "--view") {
        const auto c = numbers(opt, v, 9, 9);
        o.view = std::array<double, 9>{c[0] * L, c[1] * L, c[2] * L, c[3] * L, c[4] * L, c[5] * L, c[6], c[7], c[8]};
      } else {
        const auto c = numbers(opt, v, 6, 6);
        o.cut_plane = std::array<double, 6>{c[0] * L, c[1] * L, c[2] * L, c[3], c[4], c[5]};
      }
    }
    if (slice) {
      const double t = number("--slice", *slice);
      if (!(t > 0)) throw std::invalid_argument("--slice must be a positive thickness");
      if (!o.cut_plane) throw std::invalid_argument("--slice needs --cut-plane (the slice is centred on that plane)");
      if (thickness_given)
        throw std::invalid_argument("--slice sets the specimen thickness of the fringes: leave out --thickness");
      o.slice = t * L;
    }
    if (!(thickness_mm > 0)) throw std::invalid_argument("--thickness must be positive (mm)");
    if (!(wavelength_nm > 0)) throw std::invalid_argument("--wavelength must be positive (nm)");
    o.photo.thickness = thickness_mm * 1e-3;
    o.photo.wavelength = wavelength_nm * 1e-9;
    o.photo.fringe_constant = fringe_constant * 1e3;  // N/mm -> N/m (Pa m)
    o.photo.stress_optic = brewster * 1e-12;
    o.photo.polarizer_angle = polarizer_deg * std::numbers::pi / 180;
    o.photo.k_f = kf * 1e-6;
    const bool needs_constant = o.fringes && o.photo.mode != Polariscope::Seed002;
    if (needs_constant && fringe_constant <= 0 && brewster <= 0)
      throw std::invalid_argument("fringes need --fringe-constant (N/mm/fringe) or --stress-optic (Brewster)");

    if (front.any() && cmd != "plot") throw std::invalid_argument(front_option + " is an option of cleave plot");
    if (cmd == "plot") {
      const auto dir = std::filesystem::is_directory(o.series) ? o.series : o.series.parent_path();
      const auto images = o.image_dir.empty() ? dir / "render" : o.image_dir;
      if (cod_time) {
        if (front.any())
          throw std::invalid_argument(front_option + " is for the K plots of 3D crack fronts; --cod draws only the "
                                      "crack-opening profile: leave out one of them");
        std::printf("%s\n", render_cod_profile(dir, images, *cod_time, o.width, o.height).string().c_str());
        return 0;
      }
      const auto files = render_plots(dir, images, o.width, o.height, front);
      if (files.empty())
        throw std::runtime_error(dir.string() + ": no global.csv, crack_tips.csv or crack_fronts.csv to plot");
      for (const auto& f : files) std::printf("%s\n", f.string().c_str());
      return 0;
    }
    if (cmd == "compare" && other_run) {
      if (!o.fringes) throw std::invalid_argument("compare --run needs --fringes MODE (and the photoelastic constants)");
      const RunComparison r = compare_runs(o, *other_run, out_prefix.empty() ? "" : out_prefix + "_difference.png");
      std::printf("fringe order: RMS difference %.4f, mean absolute %.4f over %zu pixels (t = %.6g s and %.6g s)\n",
                  r.rms, r.mean_abs, r.pixels, r.time_a, r.time_b);
      return 0;
    }
    if (cmd == "compare") {
      if (!photo || !map) throw std::invalid_argument("compare needs --photo IMG and --map X0,Y0,SCALE[,ANGLE] (or --run OTHER)");
      if (!o.fringes) throw std::invalid_argument("compare needs --fringes MODE (and the photoelastic constants)");
      const auto mv = numbers("--map", *map, 3, 4);
      if (!(mv[2] > 0)) throw std::invalid_argument("--map: SCALE must be positive");
      PhotoMap pm{mv[0] * L, mv[1] * L, mv[2] * L, mv.size() > 3 ? mv[3] * std::numbers::pi / 180 : 0.0};
      const auto dir = std::filesystem::is_directory(o.series) ? o.series : o.series.parent_path();
      const std::filesystem::path prefix = out_prefix.empty() ? dir / "compare" : std::filesystem::path(out_prefix);
      std::optional<std::vector<std::array<double, 3>>> pts;
      if (points) {
        pts = read_fringe_points(*points);
        for (auto& q : *pts) q[0] *= L, q[1] *= L;  // coordinates in --length-unit; orders unchanged
      }
      const CompareResult r = compare_with_photo(o, *photo, pm, pts, prefix,
                                                 mask ? std::optional<std::filesystem::path>(*mask) : std::nullopt);
      std::printf("agreement: normalised cross-correlation %.4f over %zu pixels\n", r.ncc, r.pixels);
      if (r.folded_ncc)
        std::printf("fringe order (folded to [0, 1/2]): correlation %.4f, RMS difference %.4f fringes\n", *r.folded_ncc,
                    *r.folded_rms);
      if (r.fringe_rms) std::printf("fringe order: RMS difference %.4f over %zu points\n", *r.fringe_rms, r.points_used);
      std::printf("images: %s_side_by_side.png, %s_overlay.png\n", prefix.string().c_str(), prefix.string().c_str());
      return 0;
    }
    const bool tty = isatty(fileno(stderr));
    const auto res = render_series(o, [&](std::size_t k, std::size_t n) {
      if (tty) std::fprintf(stderr, "\r\033[Krendered %zu / %zu frames", k, n);
    });
    if (tty) std::fprintf(stderr, "\n");
    std::printf("rendered %zu frame%s into %s%s%s\n", res.images.size(), res.images.size() == 1 ? "" : "s",
                res.images.front().parent_path().string().c_str(), res.movie ? "; movie " : "",
                res.movie ? res.movie->string().c_str() : "");
    return 0;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "cleave %s: %s\n(see cleave %s --help)\n", cmd.c_str(), e.what(), cmd.c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cleave %s: error: %s\n", cmd.c_str(), e.what());
    return 1;
  }
}

}  // namespace cleave::app
