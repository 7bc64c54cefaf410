/// \file demo.hpp
/// \brief What every lab's demo and benchmark shares: command-line options, a stopwatch and a
/// plain-text table.
#pragma once

#include <chrono>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace physlab {

/// Options of a demo or benchmark executable:
/// `--out DIR` (where charts go, default "charts"), `--quick` (smaller runs, for CI),
/// `--help`. Unknown options are an error naming the option.
struct DemoOptions {
  std::string out = "charts";  ///< output folder for charts and tables
  bool quick = false;          ///< shorter runs (CI, smoke tests)
};

/// Parses argv; prints usage and exits 0 on --help; throws InvalidInput on an unknown option
/// or a missing value. `what` is a one-line description printed by --help.
DemoOptions parseDemoOptions(int argc, char** argv, const std::string& what);

/// Keeps freed memory in the process (glibc's malloc only; a no-op elsewhere). A step that
/// allocates and frees large buffers (an implicit cloth step's matrix and factorisation) would
/// otherwise return the pages to the kernel and fault them in again on the next step, which on
/// the development machine cost more than the solve itself (an LDLT step of a 12x12 cloth ran
/// 3.5 times slower, and whichever run came first was penalised). Timings then measure the solver.
void keepFreedMemory();

/// Wall-clock stopwatch (steady clock).
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  /// Seconds since construction or the last restart().
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  /// Starts counting again from zero.
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

/// A table printed with aligned columns, and writable as Markdown for the docs.
class Table {
 public:
  /// A table with these column headings.
  explicit Table(std::vector<std::string> header);
  /// Adds a row; throws InvalidInput when its length differs from the header's.
  void add(std::vector<std::string> row);
  /// Aligned plain text.
  void print(std::ostream& os) const;
  /// Writes a Markdown table to `path` (creating the folder) and returns the path.
  std::string saveMarkdown(const std::string& path) const;

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

/// Runs `work`. If it throws (a stub not yet written, a method that broke down), prints `what`
/// and the reason, notes both for reportDemo() and returns false, so that one failure costs a
/// demo one chart (or one part of a chart), not every chart. Give each chart, or each part that
/// needs functions of its own, an attempt of its own.
bool attempt(const std::string& what, const std::function<void()>& work);

/// Prints the paths a demo wrote and its summary table, then what the attempts skipped, grouped
/// by the reason (for a stub: the function not written yet), and saves the table as Markdown at
/// `summary_path`.
void reportDemo(const std::string& lab, const std::vector<std::string>& written, const Table& table,
                const std::string& summary_path);

/// Formats a number in `%.*g` style with `digits` significant digits.
std::string fmt(double value, int digits = 3);

}  // namespace physlab
