// sph_surface: surface meshes (binary PLY, OpenVDB) of the PLY frames an sph_run wrote, for Blender and
// ParaView: OUT/surface_NNNNN.ply next to each frame_NNNNN.ply, or in --out.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "../common/frame_reader.h"
#include "option_values.h"
#include "surface_output.h"

namespace fs = std::filesystem;
using namespace sph;

namespace {

// The frames to mesh: the files named, and every frame_NNNNN.ply of the folders named, in name order.
std::vector<std::string> frame_files(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const std::string& in : inputs) {
    std::error_code ec;
    if (fs::is_directory(in, ec)) {
      std::vector<std::string> found;
      for (const auto& e : fs::directory_iterator(in)) {
        const std::string name = e.path().filename().string();
        if (name.rfind("frame_", 0) == 0 && e.path().extension() == ".ply") found.push_back(e.path().string());
      }
      if (found.empty()) throw std::runtime_error("no frame_NNNNN.ply in the folder " + in);
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(in, ec)) {
      files.push_back(in);
    } else {
      throw std::runtime_error(in + ": no such file or folder");
    }
  }
  return files;
}

// surface_NNNNN.ply for frame_NNNNN.ply (other names: NAME_surface.ply), in out or next to the frame.
std::string surface_path(const std::string& frame, const std::string& out) {
  const fs::path p(frame);
  std::string name = p.filename().string();
  name = name.rfind("frame_", 0) == 0 ? "surface_" + name.substr(6) : p.stem().string() + "_surface.ply";
  return ((out.empty() ? p.parent_path() : fs::path(out)) / name).string();
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> inputs;
  std::string out, resolution = "2";
  CLI::App app{
      "sph_surface: the fluid's surface as a closed triangle mesh for each PLY frame of an sph_run (the particles\n"
      "rasterised as spheres into an OpenVDB level set, smoothed, eroded to the particles' volume and meshed).\n"
      "Writes surface_NNNNN.ply (binary PLY with the frame's time) next to each frame_NNNNN.ply, or into --out.\n"
      "Exit status: 0 done, 1 bad input (a missing or corrupt frame, options out of range, a resolution\n"
      "needing more memory than the machine has), 4 a mesh could not be written."};
  app.add_option("frames", inputs, "frame files (frame_NNNNN.ply) or sph_run output folders")->required();
  app.add_option("--out,-o", out, "folder for the meshes (default: next to each frame)");
  app.add_option("--resolution,-r", resolution, "voxels per particle spacing, in [1, 8] (default 2)");
  double voxels = 2.0;
  std::vector<std::string> files;
  try {
    app.parse(argc, argv);
    voxels = finite_option("--resolution", resolution, 1.0, 8.0, false, "voxels per spacing");
    files = frame_files(inputs);
    if (!out.empty()) fs::create_directories(out);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  const bool tty = isatty(STDERR_FILENO);
  for (std::size_t k = 0; k < files.size(); ++k) {
    const std::string target = surface_path(files[k], out);
    const auto t0 = std::chrono::steady_clock::now();
    std::size_t triangles = 0, particles = 0;
    try {
      const Frame frame = read_ply_frame(files[k], 1e9);
      particles = frame.particles.size();
      if (!(frame.info.spacing > 0.0)) throw std::runtime_error(files[k] + ": the frame records no particle spacing");
      const std::vector<Vec3> pos(frame.particles.pos.begin(), frame.particles.pos.end());
      triangles = write_surface(target, pos, frame.info.spacing, voxels, frame.info.time);
    } catch (const std::invalid_argument& e) {
      std::cerr << "error: " << e.what() << "\n";
      return 1;
    } catch (const std::runtime_error& e) {
      std::cerr << "error: " << e.what() << "\n";
      return std::string(e.what()).rfind("cannot write", 0) == 0 ? 4 : 1;
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(tty ? stderr : stdout, "[%zu/%zu] %s: %zu particles -> %s, %zu triangles, %.2f s\n", k + 1, files.size(),
                 files[k].c_str(), particles, target.c_str(), triangles, s);
  }
  return 0;
}
