#include "frame_writer.h"

#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace sph {

void write_ply_frame(const std::string& path, const ParticleState& ps, double time) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write frame " + path);
  out << "ply\nformat binary_little_endian 1.0\ncomment sph frame, time " << time << " s\n"
      << "element vertex " << ps.size() << "\n"
      << "property float x\nproperty float y\nproperty float z\n"
      << "property float vx\nproperty float vy\nproperty float vz\n"
      << "property float density\nproperty float pressure\nproperty uchar fluid\nproperty int id\nend_header\n";
  constexpr std::size_t kRecord = 8 * 4 + 1 + 4;
  std::vector<char> buf(ps.size() * kRecord);
  char* w = buf.data();
  for (std::size_t i = 0; i < ps.size(); ++i) {  // x86-64 and every CUDA host are little-endian
    const float f[8] = {ps.pos[i].x, ps.pos[i].y, ps.pos[i].z, ps.vel[i].x, ps.vel[i].y, ps.vel[i].z,
                        ps.density[i], ps.pressure[i]};
    std::memcpy(w, f, sizeof f);
    w += sizeof f;
    *w++ = char(ps.fluid[i]);
    std::memcpy(w, &ps.id[i], 4);
    w += 4;
  }
  out.write(buf.data(), std::streamsize(buf.size()));
  if (!out) throw std::runtime_error("error while writing frame " + path);
}

}  // namespace sph
