// sph_demo --replay DIR: record and replay (issue 14, seed 002 section 5). A run too heavy to watch live is
// simulated once by sph_run --frames-every, then its PLY frames are played back here at their recorded
// simulated times, at real-time speed or scaled, with pause, step, seek and loop, in every colour mode.
#pragma once

#include <GLFW/glfw3.h>

#include <string>
#include <vector>

#include "../common/frame_reader.h"
#include "../common/mesh.h"
#include "demo_options.h"

namespace sph {

// Every frame_NNNNN.ply of an sph_run output folder, read and checked before any window opens.
struct Recording {
  std::string folder;
  std::vector<Frame> frames;  // in the order of their simulated times
  // The folder's surface_NNNNN.ply meshes (sph_run --surface-every, sph_surface), in time order: drawn with M.
  struct Surface {
    double time = 0.0;  // [s], from the mesh's header
    std::string path;
    TriangleMesh mesh;
  };
  std::vector<Surface> surfaces;
};

// Reads folder's frames (sorted by name; a progress line on a terminal) and its surface meshes. Throws
// SceneError or std::runtime_error naming the folder or file: no such folder, no frame_NNNNN.ply in it, a frame
// read_ply_frame refuses (corrupt, truncated, missing fields, another format), frames of different scenes or
// spacings, times that do not increase, more particles in all than fit in the memory a run may use
// (setup_budget.h), or a surface mesh read_ply_mesh refuses or that records no time.
Recording load_recording(const std::string& folder);

// Plays the recording in the window (OpenGL 3.3 and Dear ImGui set up by the caller) until it closes, or
// for o.frames frames (then the last one to o.screenshot and a summary on stdout). The colours' rest
// densities and grid come from the recording's scene, looked up as NAME.json beside o.scene, else rest
// density 1000 kg/m^3 with a note. Returns the exit status.
int run_replay(GLFWwindow* window, const DemoOptions& o, const Recording& recording);

}  // namespace sph
