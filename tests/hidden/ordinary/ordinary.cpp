// Ordinary C++ a lab file may use (the Grading page, "What student code may use"): appended to a
// reference file by .ci/ordinary-cpp, which checks that the lab still compiles and scores in full.
#include <algorithm>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {
std::string ordinaryText(int n) {
  std::ostringstream out;
  out << "n = " << n;
  std::string text = "text " + std::string(out.str()) + '!';
  std::vector<int> values{3, 1, 2};
  std::sort(values.begin(), values.end());
  std::map<std::string, int> counts{{"a", 1}};
  std::mt19937 engine(static_cast<unsigned>(n));
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  try {
    if (uniform(engine) > 2.0) throw std::runtime_error(text);
  } catch (const std::exception& error) {
    text += error.what();
  }
  return text + std::to_string(values.front() + counts.at("a"));
}
[[maybe_unused]] const std::string kOrdinary = ordinaryText(7);
}  // namespace
