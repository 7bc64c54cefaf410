/// \file plot.hpp
/// \brief Charts and animations drawn by gnuplot without a display (PNG, SVG, animated GIF).
///
/// \code
///   Chart chart("Energy drift", "time [s]", "|E - E0| / |E0|");
///   chart.logY().add({"RK4", t, err});
///   for (const std::string& path : chart.save("out/energy")) std::cout << path << '\n';
/// \endcode
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "physlab/math.hpp"

namespace physlab {

/// One line or point set of a chart.
struct Series {
  std::string title;        ///< legend entry; a method's name first gives it the method's colour
  std::vector<double> x;    ///< abscissae; a NaN (in x or y) breaks the line there
  std::vector<double> y;    ///< ordinates, same length as x
  std::string style = "linespoints";  ///< gnuplot style: "lines", "points", "linespoints", ... (lc and lw optional)
};

/// The colour ("#rrggbb") of a method or engine in every chart of every lab, so that RK4 is the
/// same orange wherever it appears: looked up by the name the labs print (methodName(),
/// responseMethodName(), lcpMethodName(), a broad phase's name(), "Bullet", "ODE", ...), at the
/// start of `title` and followed by its end, a space, a comma or a parenthesis; a leading
/// "PhysLab " is skipped. Empty for anything else (gnuplot then picks). Chart::save() applies it
/// to every series whose style names no colour.
std::string methodColour(const std::string& title);

/// A vertical marker line with a label (e.g. a stability boundary).
struct Marker {
  double x;           ///< where the line stands
  std::string label;  ///< text written beside it
};

/// Text written on a chart at a point of the data, e.g. a curve's name at its end.
struct Label {
  double x;          ///< abscissa of the point the text starts at
  double y;          ///< ordinate of that point
  std::string text;  ///< the text, left-aligned just right of the point
};

/// A 2D chart with optional logarithmic axes, written as PNG and SVG.
class Chart {
 public:
  /// A chart with a title and axis labels (gnuplot enhanced text: ^ and _ make super/subscripts).
  Chart(std::string title, std::string xlabel, std::string ylabel);
  Chart& logX();                         ///< logarithmic x axis
  Chart& logY();                         ///< logarithmic y axis
  Chart& equalAxes();                    ///< one metre is as long on both axes (a picture, not a graph)
  Chart& xRange(double lo, double hi);   ///< fixed x range (e.g. room for labels at the curves' ends)
  Chart& yRange(double lo, double hi);   ///< fixed y range
  Chart& add(Series series);             ///< adds a series; throws InvalidInput on x/y size mismatch
  Chart& mark(Marker marker);            ///< adds a vertical marker
  Chart& label(Label label);             ///< adds a text label at a data point
  /// Adds a key entry that no data carries, showing what a style means where several series
  /// share it (e.g. a dashed line for one scene, drawn in each method's colour).
  Chart& keyEntry(std::string title, std::string style);
  /// Names the x axis's tics, given in increasing x: each label at its x, slanted, in place of the
  /// numbers, and the x range is the tics' with 1 to spare on each side (a category chart: one
  /// tic per category at 1, 2, ...).
  Chart& xTics(std::vector<std::pair<double, std::string>> tics);
  /// Writes `stem`.png and `stem`.svg (creating the folder) and returns both paths. Points that
  /// a log axis cannot show (non-positive, infinite) are left out; a NaN breaks the line. When no
  /// series has a point to show (every method a stub not written yet), writes nothing, removes
  /// the files an earlier run left at `stem` and returns no paths.
  std::vector<std::string> save(const std::string& stem) const;

 private:
  std::string title_, xlabel_, ylabel_;
  bool log_x_ = false, log_y_ = false;
  bool equal_axes_ = false, fixed_x_ = false, fixed_y_ = false;
  double x_lo_ = 0.0, x_hi_ = 1.0, y_lo_ = 0.0, y_hi_ = 1.0;
  std::vector<Series> series_;
  std::vector<Marker> markers_;
  std::vector<Label> labels_;
  std::vector<std::pair<std::string, std::string>> key_entries_;  // title, style
  std::vector<std::pair<double, std::string>> x_tics_;
};

/// One drawable set of points in an animation frame.
struct Layer {
  Mat3X points;        ///< 3 x n points (z ignored in 2D)
  std::string style;   ///< gnuplot style, e.g. "points pt 7 ps 2" or "lines lw 2"
  std::string title;   ///< legend entry; empty for none
};

/// An animated GIF built frame by frame, in 2D (plot) or 3D (splot) with fixed axis ranges.
class Animation {
 public:
  /// \param title chart title
  /// \param lo,hi  lower and upper corners of the fixed view box (z used in 3D only)
  /// \param three_d draw with splot (3D view) instead of plot
  /// The axes are labelled "x [m]", "y [m]" and "z [m]" until axes() names them otherwise.
  Animation(std::string title, const Vec3& lo, const Vec3& hi, bool three_d);
  /// Labels the axes (z used in 3D only), with their units.
  Animation& axes(std::string x, std::string y, std::string z = "");
  /// Appends a frame; `caption` is written on a line under the title (e.g. the time).
  void addFrame(std::vector<Layer> layers, const std::string& caption);
  /// Writes the GIF (`delay_cs` hundredths of a second between frames) and returns its path.
  std::string save(const std::string& path, int delay_cs = 4) const;

 private:
  std::string title_;
  std::string x_label_ = "x [m]", y_label_ = "y [m]", z_label_ = "z [m]";
  Vec3 lo_, hi_;
  bool three_d_;
  std::vector<std::vector<Layer>> frames_;
  std::vector<std::string> captions_;
};

}  // namespace physlab
