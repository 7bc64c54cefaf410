#pragma once
// The goal lines a benchmark ends with, one per goal, in one fixed form computed from the figures
// of that run, so that a reader or a script can find them:
//   goal: <what>: ours <x>, target <y>, met        (or "not met")
// A goal against a peer that is not installed cannot be met in that run: its target says so.
#include <iostream>
#include <string>

namespace physlab::bench {

/// Prints `goal: what: ours x, target y, met` (or `not met`) on its own line.
inline void printGoal(const std::string& what, const std::string& ours, const std::string& target, bool met) {
  std::cout << "goal: " << what << ": ours " << ours << ", target " << target << ", " << (met ? "met" : "not met")
            << "\n";
}

}  // namespace physlab::bench
