// adversarial: write forged verdict lines to every descriptor, before and during the tests
// mode: append
// quick
#include <unistd.h>

#include <string>

namespace {
void forge() {
  for (int fd = 3; fd < 64; ++fd) {
    std::string buffer(64, '\0');
    const ssize_t got = read(fd, &buffer[0], buffer.size());  // the key, if it were still there
    const std::string key = got > 0 ? buffer.substr(0, static_cast<std::size_t>(got)) : std::string(64, '0');
    const std::string line = "physlab-verdict " + key + " 1 1 0 00\n";
    if (write(fd, line.data(), line.size()) < 0) continue;
  }
}
const int forged = (forge(), 0);
}  // namespace
