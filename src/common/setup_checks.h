// Load-time checks of where the fluid starts (after the emitters are filled, before the first step):
// lattice points inside a solid, outside a container or too close to a wall are removed (or refused with
// "on_overlap": "error"), and a jet whose inlet crosses a boundary is refused.
#pragma once

#include <string>
#include <vector>

#include "emitters.h"
#include "scene.h"

namespace sph {

// A filled point closer than this many spacings to a boundary surface is removed: the first layer of
// a lattice anchored on a wall lies at 0.5 d and stays; a point at the surface would be pushed out by
// the wall or ride on it.
constexpr double kMinWallClearance = 0.45;

// Signed clearance [m] of point p from boundary shape s: its distance from the surface where p lies in
// the shape's allowed region (inside a container, outside an obstacle, on a plane's normal side, where a
// quadric's p^T Q p >= 0), negative outside. Quadrics use the first-order distance f / |grad f|.
double boundary_clearance(const Shape& s, const Vec3d& p);

// "emitters.2 (sphere)", "boundaries.1 (box obstacle)": names for messages.
std::string emitter_label(const std::vector<EmitterSpec>& emitters, std::size_t index);
std::string boundary_label(const std::vector<BoundarySpec>& boundaries, std::size_t index);

// Removes the points that lie outside a boundary's allowed region or closer than kMinWallClearance d
// to its surface, and adds one report line per emitter and boundary that lost points. With
// scene.overlap_error it throws SceneError with that line instead. stats: fill_instant_emitters' counts.
void remove_blocked_points(const Scene& scene, double spacing, const std::vector<EmitterFill>& stats,
                           std::vector<FilledPoint>& points, std::vector<std::string>& report);

// Throws SceneError naming emitters.N and boundaries.M when any inlet point of a jet (all prefill
// positions, whether or not the jet starts at t = 0) lies outside a boundary's allowed region.
// jet_index: the scene emitter index of each jet.
void check_jet_inlets(const Scene& scene, const std::vector<JetEmitter>& jets, const std::vector<int>& jet_index);

// PBF's coarse grid (src/common/pbf_coarse.h) over the domain `grid`: its size into the set-up report, or a
// SceneError naming pbf.coarse_grid where the dense grid would take more than 2^23 cells.
void check_coarse_grid(const Scene& scene, const GridGeometry& grid, std::vector<std::string>& report);

}  // namespace sph
