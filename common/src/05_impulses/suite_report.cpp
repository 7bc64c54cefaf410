// The contact suite's report: the table and the chart of scores of suite_report.hpp.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "physlab/demo.hpp"
#include "physlab/error.hpp"
#include "physlab/plot.hpp"
#include "physlab/suite_report.hpp"

namespace physlab {

namespace {

// Runs `scene` in a fresh engine of `column` (a chaotic scene: the median of its runs, each in a
// fresh engine); an engine that throws leaves every measure not finite (failed), and `note` says why.
std::vector<Measure> runColumn(SuiteScene& scene, const SuiteColumn& column, std::string& note) {
  try {
    if (scene.runs() > 1) {
      std::vector<Measure> medians;
      for (const SpreadMeasure& m : runSuiteSceneShaken(scene.name(), column.make, scene.runs())) {
        medians.push_back(m.median);
      }
      return medians;
    }
    const std::unique_ptr<SuiteEngine> engine = column.make(scene.scene());
    return runSuiteScene(scene, *engine);
  } catch (const std::exception& e) {
    note = column.label + ", " + scene.name() + ": " + e.what();
    std::vector<Measure> failed = scene.measures();
    for (Measure& m : failed) m.value = std::numeric_limits<double>::quiet_NaN();
    return failed;
  }
}

// The score drawn for a measure: |value - expected| / tolerance, inside the chart's log range
// (an exact hit at the floor, a value that is not finite at the ceiling).
constexpr double kScoreFloor = 1e-3, kScoreCeiling = 1e4;
double drawnScore(const Measure& m) {
  const double score = m.score();
  return std::isfinite(score) ? std::clamp(score, kScoreFloor, kScoreCeiling) : kScoreCeiling;
}

// InvalidInput, naming `what`, when there is no column or a column has no make function.
void requireColumns(const std::vector<SuiteColumn>& columns, const std::string& what) {
  if (columns.empty()) throw InvalidInput(what + ": no engine to run");
  for (const SuiteColumn& column : columns) {
    if (!column.make) throw InvalidInput(what + ": engine '" + column.label + "' has no make function");
  }
}

}  // namespace

SuiteReport contactSuiteReport(const std::vector<SuiteColumn>& columns, const std::string& heading,
                               const std::string& stem, std::ostream& out) {
  requireColumns(columns, "contact suite report");
  // results[c][s]: column c's measures of scene s, each column on a fresh suite
  std::vector<std::vector<std::vector<Measure>>> results(columns.size());
  std::vector<std::string> notes;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    for (const std::unique_ptr<SuiteScene>& scene : contactSuite()) {
      std::string note;
      results[c].push_back(runColumn(*scene, columns[c], note));
      if (!note.empty()) notes.push_back(note);
    }
  }
  std::vector<std::string> header = {"scene", "measure", "expected", "tolerance"};
  for (const SuiteColumn& column : columns) header.push_back(column.label);
  Table table(header);
  SuiteReport report;
  report.passed.assign(columns.size(), 0);
  std::vector<Series> series;
  for (const SuiteColumn& column : columns) series.push_back({column.label, {}, {}, column.style});
  std::vector<std::pair<double, std::string>> tics;
  const auto suite = contactSuite();
  for (std::size_t s = 0; s < suite.size(); ++s) {
    for (std::size_t k = 0; k < results[0][s].size(); ++k) {
      const Measure& truth = results[0][s][k];
      const int runs = suite[s]->runs();
      const std::string measure = truth.name + (runs > 1 ? ", median of " + std::to_string(runs) + " runs" : "");
      std::vector<std::string> row = {suite[s]->name(), measure, fmt(truth.expected, 4), fmt(truth.tolerance, 3)};
      const double x = static_cast<double>(tics.size() + 1);
      for (std::size_t c = 0; c < columns.size(); ++c) {
        const Measure& m = results[c][s][k];
        row.push_back(fmt(m.value, 4) + (m.pass() ? " pass" : " FAIL"));
        report.passed[c] += m.pass() ? 1 : 0;
        // Side by side within the measure's slot, in the columns' order
        series[c].x.push_back(x + 0.15 * (static_cast<double>(c) - 0.5 * static_cast<double>(columns.size() - 1)));
        series[c].y.push_back(drawnScore(m));
      }
      table.add(row);
      tics.emplace_back(x, suite[s]->name() + ": " + truth.name + (runs > 1 ? " (median)" : ""));
    }
  }
  std::vector<std::string> total = {"measures passed", "", "", ""};
  report.measures = static_cast<int>(tics.size());
  for (const int p : report.passed) total.push_back(std::to_string(p) + " of " + std::to_string(report.measures));
  table.add(total);

  out << "\n" << heading << "\n";
  for (const SuiteColumn& column : columns) out << "  " << column.label << ": " << column.name << "\n";
  table.print(out);
  for (const std::string& note : notes) out << "  failed: " << note << "\n";

  Chart chart("Textbook contact scenes, h = 1/60 s: below the dotted line passes (exact: 10^{-3})",
              "", "|value - expected| / tolerance");
  chart.logY().yRange(0.5 * kScoreFloor, 2.0 * kScoreCeiling).xTics(tics);
  for (Series& column : series) chart.add(std::move(column));
  chart.add({"passes below 1", {0.0, static_cast<double>(tics.size() + 1)}, {1.0, 1.0}, "lines dt 3 lc rgb '#000000'"});
  report.paths = {table.saveMarkdown(stem + ".md")};
  {
    std::ofstream file(report.paths.front(), std::ios::app);
    file << "\nEngines: ";
    for (std::size_t c = 0; c < columns.size(); ++c) file << (c > 0 ? "; " : "") << columns[c].label << ": " << columns[c].name;
    file << ".\n";
    for (const std::string& note : notes) file << "\nFailed: " << note << "\n";
  }
  for (const std::string& p : chart.save(stem)) report.paths.push_back(p);
  return report;
}

StackDrift stackDriftChart(const std::vector<SuiteColumn>& columns, const std::string& stem, std::ostream& out) {
  requireColumns(columns, "stack drift chart");
  constexpr double kFloor = 1e-10;  // [m]: below a tenth of a nanometre a stack stands exactly
  const std::unique_ptr<SuiteScene> stack = std::move(contactSuite({"stack of 10"}).front());
  const Scene start = stack->scene();
  const double duration = stack->duration();
  const std::size_t top = start.states.size() - 1;  // the stack's cubes rise in the Scene's order
  const int steps = static_cast<int>(std::lround(duration / kSuiteStep));
  Chart chart("A stack of 10 cubes, h = 1/60 s: its top's sideways drift (floor: 10^{-10} m)", "time [s]",
              "top's sideways drift [m]");
  chart.logY().yRange(0.5 * kFloor, 10.0).xRange(0.0, duration);
  StackDrift drift;
  for (const SuiteColumn& column : columns) {
    Series series{column.label, {}, {}, column.style};
    double largest = 0.0;
    try {
      const std::unique_ptr<SuiteEngine> engine = column.make(start);
      for (int k = 1; k <= steps; ++k) {
        engine->step(kSuiteStep);
        const double d = (engine->states()[top].x - start.states[top].x).head<2>().norm();
        largest = std::isfinite(d) ? std::max(largest, d) : std::numeric_limits<double>::quiet_NaN();
        series.x.push_back(k * kSuiteStep);
        series.y.push_back(std::isfinite(d) ? std::max(d, kFloor) : std::numeric_limits<double>::quiet_NaN());
      }
    } catch (const std::exception& e) {
      out << "  stack drift chart: " << column.label << " failed: " << e.what() << "\n";
      series.x.clear();
      series.y.clear();
      largest = std::numeric_limits<double>::quiet_NaN();
    }
    drift.largest.push_back(largest);
    if (!series.x.empty()) chart.add(std::move(series));
  }
  chart.add({"the suite's bar: 1 mm", {0.0, duration}, {1e-3, 1e-3}, "lines dt 3 lc rgb '#000000'"});
  if (std::any_of(drift.largest.begin(), drift.largest.end(), [](double d) { return !std::isnan(d); })) {
    drift.paths = chart.save(stem);
  }
  return drift;
}

}  // namespace physlab
