// Reading a scene file from disk, with the checks that keep a wrong path from hanging or exhausting memory.
#pragma once

#include <string>

namespace sph {

// The whole text of the scene file at path. Throws SceneError naming the file unless it is a regular file
// of at most 16 MiB: a device such as /dev/zero would be read forever, a FIFO would block and a directory
// would fail with a puzzling message. Answers in well under a second for every kind of path.
std::string read_scene_file(const std::string& path);

}  // namespace sph
