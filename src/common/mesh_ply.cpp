// Binary PLY triangle meshes (mesh_ply.h).
#include "mesh_ply.h"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

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

TriangleMesh read_ply_mesh(const std::string& path, double& time) {
  auto refuse = [&](const std::string& why) { throw std::runtime_error(path + ": " + why); };
  std::ifstream in(path, std::ios::binary);
  if (!in) refuse(std::string("cannot read it: ") + std::strerror(errno));
  time = std::numeric_limits<double>::quiet_NaN();
  std::string line;
  long long vertices = -1, faces = -1;
  std::vector<std::string> properties;
  auto next = [&]() {
    if (!std::getline(in, line)) refuse("the header ends before end_header");
  };
  next();
  if (line != "ply") refuse("not a PLY file");
  next();
  if (line != "format binary_little_endian 1.0")
    refuse("\"" + line + "\": only binary_little_endian 1.0 meshes written by sph_surface can be read");
  for (next(); line != "end_header"; next()) {
    std::istringstream words(line);
    std::string word, name;
    words >> word;
    if (word == "comment") {
      std::string key;
      if (words >> key && key == "time" && !(words >> time)) refuse("a comment time without a number");
    } else if (word == "element") {
      long long count = -1;
      words >> name >> count;
      if (count < 0) refuse("\"" + line + "\": an element without a count");
      if (name == "vertex" && vertices < 0) vertices = count;
      else if (name == "face" && vertices >= 0 && faces < 0) faces = count;
      else refuse("\"" + line + "\": expected element vertex, then element face");
    } else if (word == "property") {
      properties.push_back(line);
    } else {
      refuse("\"" + line + "\": not a header line of a PLY mesh");
    }
  }
  const std::vector<std::string> expected = {"property float x", "property float y", "property float z",
                                             "property list uchar int vertex_indices"};
  if (vertices < 0 || faces < 0 || properties != expected)
    refuse("expected vertices of float x, y, z and faces of uchar-counted int vertex_indices");
  const std::streamoff start = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg() - start;
  if (size != std::streamoff(vertices * 12 + faces * 13))
    refuse("the file holds " + std::to_string(size) + " bytes after its header, its header says " +
           std::to_string(vertices * 12 + faces * 13));
  in.seekg(start);
  TriangleMesh mesh;
  mesh.vertices.resize(std::size_t(vertices));
  for (auto& v : mesh.vertices) {
    float xyz[3];
    in.read(reinterpret_cast<char*>(xyz), sizeof xyz);
    if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) refuse("a vertex is not finite");
    v = {double(xyz[0]), double(xyz[1]), double(xyz[2])};
  }
  mesh.triangles.resize(std::size_t(faces));
  for (auto& t : mesh.triangles) {
    unsigned char n = 0;
    int32_t idx[3];
    in.read(reinterpret_cast<char*>(&n), 1);
    in.read(reinterpret_cast<char*>(idx), sizeof idx);
    if (n != 3) refuse("a face with " + std::to_string(int(n)) + " vertices (only triangles)");
    for (int k = 0; k < 3; ++k)
      if (idx[k] < 0 || idx[k] >= vertices)
        refuse("a face names vertex " + std::to_string(idx[k]) + " of " + std::to_string(vertices));
    t = {idx[0], idx[1], idx[2]};
  }
  if (!in) refuse("read error");
  update_bounds(mesh);
  return mesh;
}

}  // namespace sph
