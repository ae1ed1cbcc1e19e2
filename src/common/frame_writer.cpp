#include "frame_writer.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace sph {
namespace {

// A name on one header line: control characters would end the line or the header.
std::string one_line(std::string s) {
  for (char& ch : s)
    if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ch = '_';
  return s;
}

std::string header(const ParticleState& ps, const FrameInfo& info) {
  std::string h = "ply\nformat binary_little_endian 1.0\n";
  char line[160];
  std::snprintf(line, sizeof line, "comment sph frame, time %.17g s\n", info.time);
  h += line;
  h += "comment scene " + one_line(info.scene) + "\n";
  if (!info.solver.empty()) h += "comment solver " + one_line(info.solver) + "\n";
  std::snprintf(line, sizeof line, "comment step %ld\ncomment frame %d\ncomment next_id %d\n", info.step,
                info.frame_index, int(info.next_id));
  h += line;
  std::snprintf(line, sizeof line, "comment spacing %.17g\ncomment jets %zu\n", info.spacing, info.jet_travelled.size());
  h += line;
  for (std::size_t j = 0; j < info.jet_travelled.size(); ++j) {
    std::snprintf(line, sizeof line, "comment jet %zu travelled %.17g\n", j, info.jet_travelled[j]);
    h += line;
  }
  if (info.has_energy) {
    std::snprintf(line, sizeof line, "comment energy_budget %.17g %.17g %.17g %.17g\n", info.energy_in, info.mass_in,
                  info.max_specific_in, info.potential_reference);
    h += line;
  }
  h += "element vertex " + std::to_string(ps.size()) + "\n";
  h += "property float x\nproperty float y\nproperty float z\n"
       "property float vx\nproperty float vy\nproperty float vz\n"
       "property float density\nproperty float pressure\nproperty uchar fluid\nproperty int id\n"
       "property float ax\nproperty float ay\nproperty float az\nproperty float age\nproperty float near_pressure\n"
       "end_header\n";
  return h;
}

std::vector<char> records(const ParticleState& ps) {
  std::vector<char> buf(ps.size() * kFrameRecordBytes);
  char* w = buf.data();
  for (std::size_t i = 0; i < ps.size(); ++i) {  // x86-64 and every CUDA host are little-endian
    const float f[8] = {ps.pos[i].x, ps.pos[i].y, ps.pos[i].z, ps.vel[i].x, ps.vel[i].y, ps.vel[i].z,
                        ps.density[i], ps.pressure[i]};
    std::memcpy(w, f, sizeof f);
    w += sizeof f;
    *w++ = char(ps.fluid[i]);
    std::memcpy(w, &ps.id[i], 4);
    w += 4;
    const float g[5] = {ps.acc[i].x, ps.acc[i].y, ps.acc[i].z, ps.age[i], ps.near_pressure[i]};
    std::memcpy(w, g, sizeof g);
    w += sizeof g;
  }
  return buf;
}

}  // namespace

void write_ply_frame(const std::string& path, const ParticleState& ps, const FrameInfo& info) {
  const std::string tmp = path + ".tmp";
  const std::string head = header(ps, info);
  const std::vector<char> body = records(ps);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write frame " + path + " (temporary file " + tmp + "): " + std::strerror(errno));
  // Each step can fail (disk full, quota, I/O error); the first failure is the one reported.
  bool ok = std::fwrite(head.data(), 1, head.size(), f) == head.size() &&
            std::fwrite(body.data(), 1, body.size(), f) == body.size() && std::fflush(f) == 0 &&
            fsync(fileno(f)) == 0;
  int err = ok ? 0 : errno;
  if (std::fclose(f) != 0 && ok) {
    ok = false;
    err = errno;
  }
  if (ok && std::rename(tmp.c_str(), path.c_str()) != 0) {
    ok = false;
    err = errno;
  }
  if (!ok) {
    std::remove(tmp.c_str());
    throw std::runtime_error("error while writing frame " + path + ": " + std::strerror(err) +
                             "; the frame was not written");
  }
}

}  // namespace sph
