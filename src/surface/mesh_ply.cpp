// Binary PLY triangle meshes (particle_surface.h, write_ply_mesh).
#include <cerrno>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "particle_surface.h"

namespace sph {

void write_ply_mesh(const std::string& path, const TriangleMesh& mesh, double time) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write surface mesh " + path + " (temporary file " + tmp + "): " + std::strerror(errno));
  bool ok = std::fprintf(f,
                         "ply\nformat binary_little_endian 1.0\ncomment sph surface mesh (OpenVDB), metres\ncomment time %.17g\n"
                         "element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n"
                         "element face %zu\nproperty list uchar int vertex_indices\nend_header\n",
                         time, mesh.vertices.size(), mesh.triangles.size()) > 0;
  for (const MeshPoint& v : mesh.vertices) {
    const float xyz[3] = {float(v[0]), float(v[1]), float(v[2])};
    ok = ok && std::fwrite(xyz, sizeof xyz, 1, f) == 1;
  }
  for (const auto& t : mesh.triangles) {
    const unsigned char three = 3;
    const int32_t idx[3] = {t[0], t[1], t[2]};
    ok = ok && std::fwrite(&three, 1, 1, f) == 1 && std::fwrite(idx, sizeof idx, 1, f) == 1;
  }
  ok = std::fclose(f) == 0 && ok;
  if (ok && std::rename(tmp.c_str(), path.c_str()) != 0) ok = false;
  if (!ok) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write surface mesh " + path + ": " + why);
  }
}

}  // namespace sph
