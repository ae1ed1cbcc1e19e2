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
    } else if (fs::exists(in, ec)) {
      throw std::runtime_error(in + ": neither a frame file nor a folder");
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
  bool force = false, phi = false;
  CLI::App app{
      "sph_surface: the fluid's surface as a closed triangle mesh for each PLY frame of an sph_run (the particles\n"
      "rasterised as spheres into an OpenVDB level set, smoothed, eroded to the particles' volume and meshed).\n"
      "Writes surface_NNNNN.ply (binary PLY with the frame's time) next to each frame_NNNNN.ply, or into --out\n"
      "(another file name F.ply gives F_surface.ply). A frame that cannot be read is reported and skipped; the\n"
      "others are still meshed.\n"
      "Exit status: 0 done, 1 bad input (a missing or corrupt frame, options out of range, a mesh that exists\n"
      "without --force, a resolution needing more memory than a run may use), 4 a mesh or the output folder\n"
      "could not be written."};
  app.add_option("frames", inputs, "frame files (frame_NNNNN.ply) or sph_run output folders")->required();
  app.add_option("--out,-o", out, "folder for the meshes (default: next to each frame)");
  app.add_option("--resolution,-r", resolution, "voxels per particle spacing, a number in [1, 8] (default 2)");
  app.add_flag("--phi", phi,
               "mesh the seed's colour field Phi = sum d^3 W(r, 2 d) at 1/2 instead of the particles' spheres");
  app.add_flag("--force", force, "replace meshes that exist (without it an existing surface_NNNNN.ply is refused)");
  double voxels = 2.0;
  std::vector<std::string> files;
  try {
    app.parse(argc, argv);
    voxels = finite_option("--resolution", resolution, 1.0, 8.0, false, "voxels per spacing");
    files = frame_files(inputs);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  std::error_code ec;
  if (!out.empty() && !fs::create_directories(out, ec) && !fs::is_directory(out)) {
    std::cerr << "error: cannot create the output folder " << out << ": " << (ec ? ec.message() : "a file is in the way") << "\n";
    return 4;
  }
  // Two frames that would write the same mesh (the same name from two folders into --out) are refused
  // before anything is written, as is a mesh that exists, unless --force.
  std::vector<std::string> targets;
  for (const std::string& f : files) {
    const std::string t = surface_path(f, out);
    if (std::find(targets.begin(), targets.end(), t) != targets.end()) {
      std::cerr << "error: two frames would write " << t << " (give each folder its own --out)\n";
      return 1;
    }
    if (!force && fs::exists(t, ec)) {
      std::cerr << "error: " << t << " exists (a run's --surface-every meshes are numbered by time, not by frame); "
                   "--force replaces it, --out writes elsewhere\n";
      return 1;
    }
    targets.push_back(t);
  }
  const bool tty = isatty(STDERR_FILENO);
  int status = 0;
  for (std::size_t k = 0; k < files.size(); ++k) {
    const std::string& target = targets[k];
    const auto t0 = std::chrono::steady_clock::now();
    std::size_t triangles = 0, particles = 0;
    try {
      const Frame frame = read_ply_frame(files[k], 1e9);
      particles = frame.particles.size();
      if (!(frame.info.spacing > 0.0)) throw std::runtime_error(files[k] + ": the frame records no particle spacing");
      const std::vector<Vec3> pos(frame.particles.pos.begin(), frame.particles.pos.end());
      triangles = write_surface(target, pos, frame.info.spacing, voxels, frame.info.time, phi);
    } catch (const std::invalid_argument& e) {  // options: the same for every frame
      std::cerr << "error: " << e.what() << "\n";
      return 1;
    } catch (const std::runtime_error& e) {  // this frame: reported, the others still meshed
      std::cerr << "error: " << e.what() << "\n";
      status = std::max(status, std::string(e.what()).rfind("cannot write", 0) == 0 ? 4 : 1);
      continue;
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(tty ? stderr : stdout, "[%zu/%zu] %s: %zu particles -> %s, %zu triangles, %.2f s\n", k + 1, files.size(),
                 files[k].c_str(), particles, target.c_str(), triangles, s);
  }
  return status;
}
