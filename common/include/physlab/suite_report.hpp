/// \file suite_report.hpp
/// \brief The contact suite's report: every textbook scene in several engines side by side, as a
/// table and a chart of each measure's error over its tolerance (the Lab 6 demo and benchmark).
#pragma once

#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "physlab/contact_suite.hpp"

namespace physlab {

/// One engine of the report: a column of the table and a series of the chart.
struct SuiteColumn {
  std::string name;   ///< what the engine is and its settings, one line (printed under the table)
  std::string label;  ///< the column's heading and the chart's legend entry (an engine's name gives its colour)
  std::string style;  ///< gnuplot point style of its series
  std::function<std::unique_ptr<SuiteEngine>(const Scene&)> make;  ///< a fresh engine holding a scene
};

/// What contactSuiteReport() wrote and counted.
struct SuiteReport {
  std::vector<std::string> paths;  ///< the table (.md) and the chart (.png, .svg)
  std::vector<int> passed;         ///< measures passed, per column
  int measures = 0;                ///< measures in the suite
};

/// Runs every scene of contactSuite() in every column's engine (a scene with SuiteScene::runs()
/// above 1 as the median of that many runs of runSuiteSceneShaken(); an engine that throws fails
/// that scene's measures and the reason is printed), prints the table to `out` under `heading`, and
/// writes `stem`.md (the table) and the chart `stem`.png and `stem`.svg. InvalidInput when there
/// is no column or a column has no make function.
SuiteReport contactSuiteReport(const std::vector<SuiteColumn>& columns, const std::string& heading,
                               const std::string& stem, std::ostream& out);

/// What stackDriftChart() drew.
struct StackDrift {
  std::vector<std::string> paths;  ///< the chart (.png, .svg); none when no engine ran
  std::vector<double> largest;     ///< per column, the top cube's largest sideways distance from its start [m] (NaN: the engine threw)
};

/// The suite's 10-cube stack ("stack of 10 cubes", 10 s) in every column's engine, once, as it is:
/// the top cube's sideways distance from where it started against time, on a log axis (a
/// distance under 1e-10 m is drawn at 1e-10 m), beside the suite's 1 mm bar. Each column's
/// `style` is a line style ("lines lw 2", "lines dt 2 lw 2"). An engine that throws draws no line
/// and `out` says why. Writes `stem`.png and `stem`.svg. InvalidInput when there is no column or
/// a column has no make function.
StackDrift stackDriftChart(const std::vector<SuiteColumn>& columns, const std::string& stem, std::ostream& out);

}  // namespace physlab
