// Triangle meshes as walls and obstacles (issue 13): loaded from Wavefront OBJ files, checked closed, and
// asked for a point's signed distance, which is all the boundary sampling needs (boundary_particles.cpp).
// Host code, run at set-up.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace sph {

using MeshPoint = std::array<double, 3>;

struct TriangleMesh {
  std::vector<MeshPoint> vertices;             // [m], after the scene's scale and translation
  std::vector<std::array<int, 3>> triangles;  // vertex indices, counter-clockwise seen from outside
  MeshPoint lo{}, hi{};                        // bounding box
};

// Reads an OBJ file with tinyobjloader (Debian's libtinyobjloader-dev, used header-only so that no shared
// library has to travel with the binaries: the GPU machine has no Debian packages). Polygons are
// triangulated; vertices are scaled per axis by `scale`, then moved by `translate`. Throws
// std::runtime_error naming the file: missing or unreadable, malformed, or without a triangle.
// Why OBJ and tinyobjloader: the project makes and ships its models as OBJ, and tinyobjloader is a small,
// well-kept loader of exactly that format; assimp would read PLY too, at the price of a shared library with
// a dozen dependencies to carry to the GPU machine.
TriangleMesh load_obj_mesh(const std::string& path, const MeshPoint& scale, const MeshPoint& translate);

// Sets mesh.lo and mesh.hi to the bounding box of the vertices its triangles use.
void update_bounds(TriangleMesh& mesh);

// The first reason the mesh does not bound a solid, or "" when it does: every edge must be shared by exactly
// two triangles that run along it in opposite directions (closed, manifold, consistently oriented), no
// triangle may be degenerate (zero area), and the faces must turn counter-clockwise seen from outside
// (positive signed volume).
std::string mesh_closure_problem(const TriangleMesh& mesh);

// Signed distance [m] from p to the mesh's surface: negative inside the solid it bounds (generalized
// winding number above 1/2, [Jacobson et al. 2013]), positive outside. Brute force over the triangles.
double mesh_signed_distance(const TriangleMesh& mesh, const MeshPoint& p);

// Volume [m^3], centroid [m] and inertia tensor about the centroid per unit density [m^5] of the solid a
// closed, outward-oriented mesh bounds: the sum over its triangles of the signed tetrahedra they span with
// the origin (divergence theorem; the covariance form of Tonon 2004 / Blow & Binstock 2004: each tetrahedron
// adds det(A) A C A^T, A = [a b c], C = [[2,1,1],[1,2,1],[1,1,2]] / 120, to the second moments, and the
// inertia is trace(S) 1 - S with S taken about the centroid).
struct MeshMassProperties {
  double volume = 0.0;
  MeshPoint centroid{};
  std::array<std::array<double, 3>, 3> inertia{};
};
MeshMassProperties mesh_mass_properties(const TriangleMesh& mesh);

}  // namespace sph
