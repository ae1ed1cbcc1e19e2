#include "scene_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "scene.h"

namespace sph {

namespace {
constexpr long long kMaxSceneBytes = 16ll << 20;  // the shipped scenes have a few kB
}  // namespace

// Opened without blocking (a FIFO would wait for a writer) and checked on the open descriptor, so a file
// swapped after the check cannot slip through.
std::string read_scene_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw SceneError(path + ": cannot open the scene file: " + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw SceneError(path + ": cannot read the scene file: " + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw SceneError(path + ": is a directory; give a scene file (JSON)");
  if (!S_ISREG(st.st_mode))
    throw SceneError(path + ": is not a regular file (a device, FIFO or socket); give a scene file (JSON)");
  if (st.st_size > kMaxSceneBytes)
    throw SceneError(path + ": the file has " + std::to_string(st.st_size) +
                     " bytes; a scene file may have at most 16 MiB (16777216 bytes)");
  std::string text;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw SceneError(path + ": error while reading the scene file: " + std::strerror(errno));
    if (n == 0) return text;
    text.append(buf, std::size_t(n));
    if (text.size() > std::size_t(kMaxSceneBytes))  // grown since fstat
      throw SceneError(path + ": the file has more than 16 MiB; a scene file may have at most 16 MiB");
  }
}

}  // namespace sph
