#pragma once
/// \file
/// The scene programs behind `./physlab view NN [SCENE]`: views/NN_name/view.cpp lists its lab's
/// scenes and hands them to runView(), which records the one asked for into a replay file
/// (physlab/replay.hpp) that tools/view.py turns into a page.

#include <functional>
#include <string>
#include <vector>

#include "physlab/replay.hpp"

namespace physlab {

/// One scene a lab's view program can record.
struct ViewScene {
  std::string name;               ///< what `./physlab view NN SCENE` calls it (one word)
  std::string what;               ///< one line saying what it shows
  std::function<Replay()> record;  ///< runs the scene and returns its replay
};

/// The main of a view program: `view_NN [--scene NAME] [--out FILE] [--max-bytes N] [--list]`.
/// Records the scene (the first when none is named) into FILE (default NAME.replay) and prints its
/// path; with --max-bytes, thinReplay() to N bytes first (the recorded reference runs a student
/// copy ships, ./physlab publish). Exit codes:
/// 0 written; 2 an unknown scene or option (the known scenes are listed); 3 a function the scene
/// runs is not written yet (physlab::NotImplemented, its message on stderr, no file written);
/// 1 any other error, its message on stderr.
int runView(int argc, char** argv, const std::vector<ViewScene>& scenes);

}  // namespace physlab
