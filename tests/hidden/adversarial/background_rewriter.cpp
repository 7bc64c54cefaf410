// adversarial: a daemon that outlives its test and keeps rewriting results.json for 20 s
// mode: append
// quick
#include <dirent.h>
#include <unistd.h>

#include <fstream>
#include <string>

namespace {
std::string outFolder() {
  DIR* proc = opendir("/proc");
  std::string found;
  while (dirent* e = proc ? readdir(proc) : nullptr) {
    std::ifstream cmdline(std::string("/proc/") + e->d_name + "/cmdline");
    std::string arg, previous;
    while (std::getline(cmdline, arg, '\0')) {
      if (previous == "--out") found = arg;
      previous = arg;
    }
  }
  if (proc) closedir(proc);
  return found;
}

const int daemonised = [] {
  if (fork() != 0) return 0;
  setsid();
  if (fork() != 0) _exit(0);
  const std::string out = outFolder();
  for (int i = 0; i < 200; ++i) {
    std::ofstream(out + "/results.json") << R"({"score": 1000, "max_score": 1000, "tests": []})";
    usleep(100000);
  }
  _exit(0);
}();
}  // namespace
