#include "physlab/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "physlab/error.hpp"

namespace physlab {
namespace {

// Gnuplot strings are single-quoted; a quote inside is doubled.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += (c == '\'') ? std::string("''") : std::string(1, c);
  return out + "'";
}

// Gnuplot double-quoted strings read backslash escapes (\n for a new line): backslashes and
// double quotes inside are escaped.
std::string escapedForDoubleQuotes(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\\' || c == '"') out += '\\';
    out += c;
  }
  return out;
}

// A gnuplot script, built in memory: numbers in full precision.
std::ostringstream gnuplotScript() {
  std::ostringstream script;
  script << std::scientific << std::setprecision(18);
  return script;
}

// Runs gnuplot on `script` and waits for it to end, so that the file it writes (`what`) is whole.
// A pipe of the C library, nothing else: the plotting code needs no library beyond the standard
// one, so every executable that links it (Lab 5's tests among them) builds with any standard
// library, libc++ as well as libstdc++.
void runGnuplot(const std::string& script, const std::string& what) {
#ifdef _WIN32
  std::FILE* pipe = ::_popen("gnuplot", "w");
#else
  std::FILE* pipe = ::popen("gnuplot", "w");
#endif
  if (pipe == nullptr) throw std::runtime_error("cannot start gnuplot to draw " + what);
  std::fwrite(script.data(), 1, script.size(), pipe);
#ifdef _WIN32
  const int status = ::_pclose(pipe);
#else
  const int status = ::pclose(pipe);
#endif
  if (status != 0) std::cerr << "gnuplot failed (status " << status << ") drawing " << what << "\n";
}

// A chart's title as a gnuplot string: on one line, or, when longer than fits the chart's width
// at its font (about 70 characters at 16 points over a plot of 960 pixels with its key beside it),
// on two, broken at the space nearest the middle.
std::string titleText(const std::string& title) {
  constexpr std::size_t kFits = 70;
  const std::size_t middle = title.size() / 2;
  const std::size_t before = title.rfind(' ', middle), after = title.find(' ', middle);
  if (title.size() <= kFits || (before == std::string::npos && after == std::string::npos)) return quoted(title);
  const std::size_t cut = before == std::string::npos                                     ? after
                          : after == std::string::npos || middle - before <= after - middle ? before
                                                                                          : after;
  return "\"" + escapedForDoubleQuotes(title.substr(0, cut)) + "\\n" + escapedForDoubleQuotes(title.substr(cut + 1)) +
         "\"";
}

void makeParentFolder(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
}

}  // namespace

Chart::Chart(std::string title, std::string xlabel, std::string ylabel)
    : title_(std::move(title)), xlabel_(std::move(xlabel)), ylabel_(std::move(ylabel)) {}

Chart& Chart::logX() {
  log_x_ = true;
  return *this;
}

Chart& Chart::logY() {
  log_y_ = true;
  return *this;
}

Chart& Chart::xRange(double lo, double hi) {
  fixed_x_ = true;
  x_lo_ = lo;
  x_hi_ = hi;
  return *this;
}

Chart& Chart::equalAxes() {
  equal_axes_ = true;
  return *this;
}

Chart& Chart::yRange(double lo, double hi) {
  fixed_y_ = true;
  y_lo_ = lo;
  y_hi_ = hi;
  return *this;
}

Chart& Chart::add(Series series) {
  if (series.x.size() != series.y.size()) {
    throw InvalidInput("chart series '" + series.title + "' has " +
                       std::to_string(series.x.size()) + " x values and " +
                       std::to_string(series.y.size()) + " y values");
  }
  series_.push_back(std::move(series));
  return *this;
}

Chart& Chart::mark(Marker marker) {
  markers_.push_back(std::move(marker));
  return *this;
}

Chart& Chart::label(Label label) {
  labels_.push_back(std::move(label));
  return *this;
}

Chart& Chart::keyEntry(std::string title, std::string style) {
  key_entries_.emplace_back(std::move(title), std::move(style));
  return *this;
}

Chart& Chart::xTics(std::vector<std::pair<double, std::string>> tics) {
  x_tics_ = std::move(tics);
  return *this;
}

std::string methodColour(const std::string& title) {
  // One entry per method or engine across the labs; never two methods of one chart alike
  static const std::pair<const char*, const char*> kColours[] = {
      // Labs 1-3: integrators
      {"explicit Euler", "#d62728"}, {"symplectic Euler", "#1f77b4"}, {"midpoint", "#2ca02c"},
      {"trapezoid", "#9467bd"}, {"RK4", "#ff7f0e"}, {"Verlet", "#17becf"}, {"implicit Euler", "#8c564b"},
      // Lab 2: linear solvers
      {"CG", "#1f77b4"}, {"LDLT", "#d62728"},
      // Lab 4: broad phases
      {"brute force", "#000000"}, {"sort and sweep", "#e41a1c"}, {"uniform grid", "#377eb8"},
      {"BVH", "#4daf4a"}, {"k-d tree", "#984ea3"},
      // Lab 4: time of impact
      {"bisection", "#a6761d"}, {"conservative advancement", "#1b9e77"},
      // Lab 5: responses
      {"sequential", "#1f5fbf"}, {"simultaneous", "#d62728"}, {"penalty", "#ff9f1c"},
      // Lab 6: LCP solvers
      {"pivoting", "#2ca02c"}, {"Lemke", "#9467bd"}, {"PGS", "#ff7f0e"}, {"soft step", "#e7298a"},
      // Peers
      {"Bullet", "#7f7f7f"}, {"FCL", "#bcbd22"}, {"ODE", "#17becf"}, {"MuJoCo", "#8c564b"},
      {"Boost.Odeint", "#e377c2"}, {"Siconos", "#c49c94"}};
  const std::string prefix = "PhysLab ";
  const std::string name = title.rfind(prefix, 0) == 0 ? title.substr(prefix.size()) : title;
  for (const auto& [method, colour] : kColours) {
    const std::size_t n = std::char_traits<char>::length(method);
    if (name.compare(0, n, method) != 0) continue;
    if (name.size() == n || name[n] == ' ' || name[n] == ',' || name[n] == '(') return colour;
  }
  return "";
}

std::vector<std::string> Chart::save(const std::string& stem) const {
  makeParentFolder(stem);
  // Keep only the points the axes can show, so gnuplot never meets log(0); a point with a NaN
  // coordinate stays, as a break in the line (several segments in one series).
  std::vector<std::vector<std::pair<double, double>>> data;
  std::vector<bool> shown;  // whether a series kept any finite point
  for (const Series& s : series_) {
    std::vector<std::pair<double, double>> kept;
    bool any = false;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (std::isnan(s.x[i]) || std::isnan(s.y[i])) {
        kept.emplace_back(s.x[i], s.y[i]);
        continue;
      }
      const bool ok = std::isfinite(s.x[i]) && std::isfinite(s.y[i]) &&
                      (!log_x_ || s.x[i] > 0.0) && (!log_y_ || s.y[i] > 0.0);
      if (ok) kept.emplace_back(s.x[i], s.y[i]), any = true;
    }
    data.push_back(std::move(kept));
    shown.push_back(any);
  }
  // Nothing to draw (every method a stub not written yet, say): no chart, and none left from an
  // earlier run to pass for this one; the demo's list of what it skipped says why
  if (std::find(shown.begin(), shown.end(), true) == shown.end()) {
    for (const char* extension : {".png", ".svg"}) std::filesystem::remove(stem + extension);
    return {};
  }
  // The data's x extent, markers included: where a marker's label has room
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  for (const auto& d : data) {
    for (const auto& [x, y] : d) {
      if (!std::isnan(x) && !std::isnan(y)) x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
    }
  }
  for (const Marker& m : markers_) x_lo = std::min(x_lo, m.x), x_hi = std::max(x_hi, m.x);
  // The key goes right of the plot, or below it when its longest title would take more than
  // about a fifth of the width from the plot
  std::size_t longest = 0;
  for (const Series& s : series_) longest = std::max(longest, s.title.size());
  const char* key = longest > 20 ? "set key below\n" : "set key outside right\n";
  std::vector<std::string> paths;
  // Fonts sized for the chart shown at half its width: a student copy's handouts show the
  // reference's chart and the student's side by side (docs/physlab.css), 420 pixels or more each
  const std::vector<std::pair<std::string, std::string>> terminals = {
      {".png", "pngcairo size 960,600 enhanced font 'Sans,16'"},
      {".svg", "svg size 960,600 enhanced font 'Sans,16' background '#ffffff'"}};
  for (const auto& [extension, terminal] : terminals) {
    const std::string path = stem + extension;
    std::ostringstream gp = gnuplotScript();
    gp << "set terminal " << terminal << "\n"
       << "set output " << quoted(path) << "\n"
       << "set title " << titleText(title_) << "\n"
       << "set xlabel " << quoted(xlabel_) << "\nset ylabel " << quoted(ylabel_) << "\n"
       << "set grid\n" << key << "set format y '%g'\n";
    if (log_x_) gp << "set logscale x\nset format x '10^{%L}'\n";
    if (log_y_) gp << "set logscale y\nset format y '10^{%L}'\n";
    if (equal_axes_) gp << "set size ratio -1\n";
    if (fixed_x_) gp << "set xrange [" << x_lo_ << ":" << x_hi_ << "]\n";
    if (fixed_y_) gp << "set yrange [" << y_lo_ << ":" << y_hi_ << "]\n";
    for (const Label& l : labels_) {
      gp << "set label " << quoted(l.text) << " at " << l.x << ", " << l.y << " left offset 1,0 font ',15' front\n";
    }
    if (!x_tics_.empty()) {
      // Slanted names need room below the axis: a fixed bottom margin, in character heights
      gp << "set bmargin 16\nset xtics rotate by -45 left font ',13' (";
      for (std::size_t i = 0; i < x_tics_.size(); ++i) {
        gp << (i > 0 ? ", " : "") << quoted(x_tics_[i].second) << " " << x_tics_[i].first;
      }
      gp << ")\nset xrange [" << x_tics_.front().first - 1.0 << ":" << x_tics_.back().first + 1.0 << "]\n";
    }
    for (std::size_t i = 0; i < markers_.size(); ++i) {
      // Labels near the top, staggered downwards so that neighbouring markers do not overwrite
      // each other; a marker in the right part of the data is labelled to its left, so that the
      // text stays inside the plot and off the key outside on the right.
      const Marker& m = markers_[i];
      const auto position = [&](double x) { return log_x_ ? std::log(std::max(x, 1e-300)) : x; };
      const bool leftwards = x_hi > x_lo && (position(m.x) - position(x_lo)) > 0.6 * (position(x_hi) - position(x_lo));
      gp << "set arrow from " << m.x << ", graph 0 to " << m.x
         << ", graph 1 nohead dashtype 2 lw 1.5 lc rgb '#555555'\n"
         << "set label " << quoted(m.label) << " at " << m.x << ", graph " << 0.96 - 0.05 * i
         << (leftwards ? " right offset -0.5,0" : " left offset 0.5,0") << " font ',13' front\n";
    }
    std::ostringstream plot;
    plot << "plot ";
    bool first = true;  // no comma before the first series
    for (std::size_t i = 0; i < series_.size(); ++i) {
      if (!shown[i]) continue;
      const std::string& style = series_[i].style;
      plot << (first ? "" : ", ") << "'-' with " << style;
      // The method's colour unless the style chooses one; a 2-point line unless it sets a width
      const std::string colour = methodColour(series_[i].title);
      const bool coloured = style.find("lc ") != std::string::npos || style.find("linecolor") != std::string::npos;
      if (!coloured && !colour.empty()) plot << " lc rgb '" << colour << "'";
      if (style.find("lw ") == std::string::npos && style.find("linewidth") == std::string::npos) plot << " lw 2";
      plot << " title " << quoted(series_[i].title);
      first = false;
    }
    // Key entries after the data, so that each method's entry comes first; NaN draws nothing
    for (const auto& [title, style] : key_entries_) {
      plot << ", NaN with " << style << (style.find("lw ") == std::string::npos ? " lw 2" : "") << " title "
           << quoted(title);
    }
    gp << plot.str() << "\n" << std::setprecision(12);
    for (std::size_t i = 0; i < data.size(); ++i) {
      if (!shown[i]) continue;
      // A blank line ends a segment, as in a data file
      for (const auto& [x, y] : data[i]) {
        if (std::isnan(x) || std::isnan(y)) {
          gp << "\n";
        } else {
          gp << x << " " << y << "\n";
        }
      }
      gp << "e\n";
    }
    gp << "unset output\n";
    runGnuplot(gp.str(), path);
    paths.push_back(path);
  }
  return paths;
}

Animation::Animation(std::string title, const Vec3& lo, const Vec3& hi, bool three_d)
    : title_(std::move(title)), lo_(lo), hi_(hi), three_d_(three_d) {}

Animation& Animation::axes(std::string x, std::string y, std::string z) {
  x_label_ = std::move(x);
  y_label_ = std::move(y);
  z_label_ = std::move(z);
  return *this;
}

void Animation::addFrame(std::vector<Layer> layers, const std::string& caption) {
  frames_.push_back(std::move(layers));
  captions_.push_back(caption);
}

std::string Animation::save(const std::string& path, int delay_cs) const {
  makeParentFolder(path);
  std::ostringstream gp = gnuplotScript();
  // The title and the caption on lines of their own, in a top margin kept for them: one line
  // with both ran past the 640-pixel frame
  gp << "set terminal gif animate delay " << delay_cs << " size 640,640 font 'Sans,12' optimize\n"
     << "set output " << quoted(path) << "\n"
     << "set tmargin 4\n"
     << "set xrange [" << lo_.x() << ":" << hi_.x() << "]\n"
     << "set yrange [" << lo_.y() << ":" << hi_.y() << "]\n"
     << "set xlabel " << quoted(x_label_) << "\nset ylabel " << quoted(y_label_) << "\n"
     << "set key top right\n";
  if (three_d_) {
    gp << "set zrange [" << lo_.z() << ":" << hi_.z() << "]\nset view 65, 30\n"
       << "set zlabel " << quoted(z_label_) << " rotate parallel\n"
       << "set ticslevel 0\nset xyplane at " << lo_.z() << "\n";
  } else {
    gp << "set size ratio -1\n";
  }
  for (std::size_t f = 0; f < frames_.size(); ++f) {
    gp << "set title \"" << escapedForDoubleQuotes(title_) << "\\n" << escapedForDoubleQuotes(captions_[f]) << "\"\n";
    std::ostringstream plot;
    plot << (three_d_ ? "splot " : "plot ");
    for (std::size_t l = 0; l < frames_[f].size(); ++l) {
      const Layer& layer = frames_[f][l];
      plot << (l ? ", " : "") << "'-' with " << layer.style
           << (layer.title.empty() ? std::string(" notitle") : " title " + quoted(layer.title));
    }
    gp << plot.str() << "\n";
    for (const Layer& layer : frames_[f]) {
      for (Index i = 0; i < layer.points.cols(); ++i) {
        // A NaN column breaks a line into separate segments: two blank lines, since splot reads
        // segments split by one as the scans of a surface and joins them with cross lines
        if (!layer.points.col(i).allFinite()) {
          gp << "\n\n";
          continue;
        }
        gp << layer.points(0, i) << " " << layer.points(1, i);
        if (three_d_) gp << " " << layer.points(2, i);
        gp << "\n";
      }
      gp << "e\n";
    }
  }
  gp << "unset output\n";
  runGnuplot(gp.str(), path);
  return path;
}

}  // namespace physlab
