#pragma once
// The goal lines a benchmark ends with, one per goal, in one fixed form computed from the figures
// of that run, so that a reader or a script can find them:
//   goal: <what>: ours <x>, target <y>, met        (or "not met")
// A goal against a peer that is not installed cannot be met in that run: its target says so.
// Where the run cannot tell at all (a quick run, a missing peer), the verdict says why instead.
#include <iostream>
#include <string>

namespace physlab::bench {

/// `goal: what: ours x, target y, verdict`, without the newline: the form printGoal() prints, for a
/// benchmark that also writes its goal lines to a file, or whose verdict is neither met nor not met.
inline std::string goalLine(const std::string& what, const std::string& ours, const std::string& target,
                            const std::string& verdict) {
  return "goal: " + what + ": ours " + ours + ", target " + target + ", " + verdict;
}

/// Prints `goal: what: ours x, target y, met` (or `not met`) on its own line.
inline void printGoal(const std::string& what, const std::string& ours, const std::string& target, bool met) {
  std::cout << goalLine(what, ours, target, met ? "met" : "not met") << "\n";
}

}  // namespace physlab::bench
