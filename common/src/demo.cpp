#include "physlab/demo.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

#include "physlab/error.hpp"

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace physlab {

DemoOptions parseDemoOptions(int argc, char** argv, const std::string& what) {
  DemoOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::cout << what << "\n\nusage: " << argv[0] << " [--out DIR] [--quick]\n"
                << "  --out DIR  folder for charts and tables (default: charts)\n"
                << "  --quick    shorter runs, for CI\n";
      std::exit(0);
    } else if (arg == "--quick") {
      options.quick = true;
    } else if (arg == "--out") {
      if (i + 1 >= argc) throw InvalidInput("--out needs a folder");
      options.out = argv[++i];
    } else {
      throw InvalidInput("unknown option '" + arg + "' (try --help)");
    }
  }
  return options;
}

Table::Table(std::vector<std::string> header) : header_(std::move(header)) {}

void Table::add(std::vector<std::string> row) {
  requireSize(static_cast<Index>(row.size()), static_cast<Index>(header_.size()), "table row");
  rows_.push_back(std::move(row));
}

void Table::print(std::ostream& os) const {
  std::vector<std::size_t> width(header_.size());
  for (std::size_t c = 0; c < header_.size(); ++c) {
    width[c] = header_[c].size();
    for (const auto& row : rows_) width[c] = std::max(width[c], row[c].size());
  }
  auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t c = 0; c < cells.size(); ++c) {
      os << (c ? "  " : "") << std::setw(static_cast<int>(width[c])) << std::left << cells[c];
    }
    os << "\n";
  };
  line(header_);
  std::size_t total = 2 * (header_.size() - 1);
  for (std::size_t w : width) total += w;
  os << std::string(total, '-') << "\n";
  for (const auto& row : rows_) line(row);
}

std::string Table::saveMarkdown(const std::string& path) const {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  std::ofstream out(path);
  auto line = [&](const std::vector<std::string>& cells) {
    out << "|";
    for (const auto& cell : cells) out << " " << cell << " |";
    out << "\n";
  };
  line(header_);
  out << "|";
  for (std::size_t c = 0; c < header_.size(); ++c) out << "---|";
  out << "\n";
  for (const auto& row : rows_) line(row);
  return path;
}

namespace {

// What attempt() skipped, as (reason, what), for reportDemo(). A demo is one process that reports
// once at its end; threading a log through every chart function would say nothing more.
std::vector<std::pair<std::string, std::string>>& skipped() {
  static std::vector<std::pair<std::string, std::string>> log;
  return log;
}

}  // namespace

bool attempt(const std::string& what, const std::function<void()>& work) {
  try {
    work();
    return true;
  } catch (const std::exception& e) {
    std::cout << "  " << what << ": skipped (" << e.what() << ")\n";
    skipped().emplace_back(e.what(), what);
    return false;
  }
}

void reportDemo(const std::string& lab, const std::vector<std::string>& written, const Table& table,
                const std::string& summary_path) {
  std::cout << "\n" << lab << " charts:\n";
  for (const auto& path : written) std::cout << "  " << path << "\n";
  if (written.empty()) std::cout << "  none\n";
  std::cout << "\n" << lab << " summary:\n";
  table.print(std::cout);
  table.saveMarkdown(summary_path);
  if (skipped().empty()) return;
  // One paragraph per reason, in the order first met: a stub not written yet names its function
  std::vector<std::string> reasons;
  for (const auto& [reason, what] : skipped()) {
    if (std::find(reasons.begin(), reasons.end(), reason) == reasons.end()) reasons.push_back(reason);
  }
  std::cout << "\n" << lab << " skipped " << skipped().size() << " charts or parts of charts, for "
            << reasons.size() << (reasons.size() == 1 ? " reason" : " reasons") << ":\n";
  for (const std::string& reason : reasons) {
    std::cout << "  " << reason << "\n";
    for (const auto& [why, what] : skipped()) {
      if (why == reason) std::cout << "    - " << what << "\n";
    }
  }
}

std::string fmt(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

void keepFreedMemory() {
#ifdef __GLIBC__
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

}  // namespace physlab
