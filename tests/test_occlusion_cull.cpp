// Hidden-particle culling (src/render/occlusion_cull.h): of particles behind one another in a pixel only the
// nearest is kept, particles outside the view or behind the camera are dropped, and at most one particle per
// pixel remains.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <set>
#include <vector>

#include <catch2/catch.hpp>

#include "render/occlusion_cull.h"

using sph::Vec3;
using namespace sph::render;

TEST_CASE("culling keeps the nearest particle of each pixel and nothing outside the view", "[render]") {
  // Camera on the z axis at z = 1 looking at the origin, 90 degrees of view, a 100 x 100 view.
  const Mat4 view = look_at(Vec3{0.0f, 0.0f, 1.0f}, Vec3{0.0f, 0.0f, 0.0f}, Vec3{0.0f, 1.0f, 0.0f});
  const Mat4 projection = perspective(3.14159265f / 2.0f, 1.0f, 0.01f, 10.0f);
  std::vector<Vec3> pos;
  // At depth 1 the view spans 2 m in 100 pixels: pixel centres at x = -0.99 + 0.02 k. A 10 x 10 block of
  // columns on every second pixel's centre, each column 5 particles deep along the view axis, 1 mm apart (so
  // the perspective moves the deeper ones by a hundredth of a pixel), the nearest (z = 0) stored last so that
  // the order of the input does not decide.
  for (int layer = 4; layer >= 0; --layer)
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 10; ++i)
        pos.push_back(Vec3{-0.19f + 0.04f * float(i), -0.19f + 0.04f * float(j), -0.001f * float(layer)});
  const std::size_t block = pos.size();
  pos.push_back(Vec3{5.0f, 0.0f, 0.0f});    // outside the view (90 degrees: |x| < 1 at the origin)
  pos.push_back(Vec3{0.0f, 0.0f, 2.0f});    // behind the camera
  CullBuffers scratch;
  std::vector<uint32_t> kept;
  front_particles(pos, view, projection, 100, 100, scratch, kept);
  std::set<uint32_t> front;
  for (std::size_t k = block - 100; k < block; ++k) front.insert(uint32_t(k));
  long front_kept = 0;
  for (uint32_t i : kept) {
    CHECK(i < block);  // neither the particle outside the view nor the one behind the camera
    front_kept += front.count(i) ? 1 : 0;
  }
  CHECK(front_kept == 100);
  CHECK(kept.size() == 100);  // every particle behind is hidden
  CHECK(std::is_sorted(kept.begin(), kept.end()));
  // Every particle in view is kept when none hides another: the front layer alone.
  const std::vector<Vec3> one_layer(pos.begin() + std::ptrdiff_t(block - 100), pos.begin() + std::ptrdiff_t(block));
  front_particles(one_layer, view, projection, 100, 100, scratch, kept);
  CHECK(kept.size() == 100);
}

TEST_CASE("a projected sphere's size is the shader's point size", "[render]") {
  const Mat4 projection = perspective(3.14159265f / 2.0f, 1.0f, 0.01f, 10.0f);
  // 90 degrees: the view's height at depth 1 m is 2 m, so a 0.02 m sphere (radius 0.01) is 1/100 of 800 px.
  CHECK(projected_diameter(projection, 800, 0.01f, 1.0f) == Approx(8.0f).epsilon(1e-5));
  CHECK(projected_diameter(projection, 800, 0.01f, 2.0f) == Approx(4.0f).epsilon(1e-5));
}
