// `cleave plot` for 3D crack fronts (docs/rendering.md, "3D crack fronts: K along the front"): K_I,
// K_II and K_III along each front at one output time, and K_I against time at chosen front nodes,
// from OUT/crack_fronts.csv, with the reference solution's K dashed when the file carries it.
#pragma once
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "viz/render/headless.hpp"

namespace cleave::viz {

enum class FrontAxis {
  ArcLength,     // s_m, drawn in mm
  EllipseAngle,  // phi_rad (written only with an elliptical or penny reference), drawn in degrees
};

// The options of `cleave plot` for crack fronts, named as the command line names them.
struct FrontPlotOptions {
  std::optional<double> time;             // --front-time (s): the output time nearest; default the last
  std::optional<FrontAxis> axis;          // --front-axis s|phi; default s
  std::optional<std::vector<int>> nodes;  // --front-nodes: default node 0, n/2 and n-1 of each front
  bool any() const { return time || axis || nodes; }
};

// One row of crack_fronts.csv: one front node at one output time, SI units. Missing optional
// columns read as NaN (phi, the reference K), a missing flag as 0.
struct FrontRow {
  double time = 0;
  int crack = 0, front = 0, node = 0;
  double s = 0, phi = 0;
  std::array<double, 3> K{}, K_ref{};  // K_I, K_II, K_III (Pa m^1/2)
  int flag = 0;                        // 0: the node's contour was complete
};

struct FrontTable {
  std::filesystem::path file;
  std::vector<FrontRow> rows;
  bool has_phi = false;
  std::array<bool, 3> has_K{}, has_ref{};
};

// Reads crack_fronts.csv by its header's column names (with their units, "KI_Pa_sqrt_m", or bare,
// "KI"); an empty cell reads as NaN, a row with another number of cells than the header is left out
// (a line still being written). Throws std::runtime_error naming the file and the column when a
// column it needs (time_s, crack, front, node, s_m, KI) is missing or a cell is not a number.
FrontTable read_crack_fronts(const std::filesystem::path& csv);

// A plot: its series as render_plot draws them, with its title and axis labels, and its file name.
struct FrontPlot {
  std::string file;
  std::string title, xlabel, ylabel;
  std::vector<PlotSeries> series;
};

// K_I, K_II, K_III (MPa m^1/2) against s (mm) or phi (deg) at the output time nearest o.time (the
// last by default): per crack front one solid series per mode, the reference per mode dashed in the
// mode's colour ("... reference"). Nodes with flag != 0 break their curves (NaN) and are drawn as
// black crosses, one series "flagged (contour incomplete)". Throws std::invalid_argument naming
// --front-axis when phi is asked for and the file has no phi_rad column.
FrontPlot k_along_front(const FrontTable&, const FrontPlotOptions&);

// K_I (MPa m^1/2) against time (ms) at o.nodes of each front (default: 0, n/2, n-1), flagged nodes
// as above; the reference dashed per node in the node's colour, or one grey dashed "KI reference"
// when it is the same at every node drawn. Throws std::invalid_argument naming --front-nodes and the
// valid range when a node is beyond a front's last node.
FrontPlot k_against_time(const FrontTable&, const FrontPlotOptions&);

// The plots of out_dir/crack_fronts.csv: K_front.png (k_along_front) and K_front_time.png
// (k_against_time); none when there is no such file or it has no rows (std::invalid_argument, naming
// the option, when o has options then: they have nothing to act on). Made before anything is drawn,
// so that a bad option stops `cleave plot` before it writes any image.
std::vector<FrontPlot> front_plots(const std::filesystem::path& out_dir, const FrontPlotOptions& o);

// Draws the plots into image_dir (created if need be); their paths.
std::vector<std::filesystem::path> write_front_plots(HeadlessContext&, const std::filesystem::path& image_dir,
                                                     const std::vector<FrontPlot>& plots);

}  // namespace cleave::viz
