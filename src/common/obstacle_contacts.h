// Obstacles in contact with a wall or with each other (issue 10, item 4): a box resting on the floor must
// not let fluid under it. The bottom fluid layer sits exactly on the floor (the floor's penalty response
// puts it there) and a point on a face counts as outside a box obstacle, so without this a particle could
// slide along the floor under the box: 2% of a dam break's water did.
// A face of a box obstacle that lies on a wall (a box container's face, an axis-aligned plane) or on the
// face of another box obstacle that covers it is not an exit: the obstacle's solid is extended through it,
// to infinity behind a wall (where fluid never is), to the far side of the obstacle underneath.
// "Lies on" means closer than half a particle spacing: no particle layer fits in a narrower gap, which the
// fluid could cross only along the wall's surface. Host code, run once at set-up.
#pragma once

#include <algorithm>
#include <cmath>

#include "boundaries.h"
#include "params.h"

namespace sph {

namespace contacts_detail {
constexpr float kBehindWall = 1e30f;  // reach through a wall: the whole half-space behind it is solid

// Whether box b's face across `axis` covers box a's face across the same axis (the other two axes).
inline bool face_covered(const Shape& a, const Shape& b, int axis, float gap) {
  for (int j = 0; j < 3; ++j)
    if (j != axis && (axis_of(a.a, j) < axis_of(b.a, j) - gap || axis_of(a.b, j) > axis_of(b.b, j) + gap))
      return false;
  return true;
}
}  // namespace contacts_detail

// Sets reach_lo and reach_hi of every box obstacle among shapes[0, count); gap: half the particle spacing [m].
inline void seal_obstacle_contacts(Shape* shapes, int32_t count, float gap) {
  using namespace contacts_detail;
  for (int32_t o = 0; o < count; ++o) {
    Shape& ob = shapes[o];
    if (ob.type != ShapeType::Box || ob.keep_inside) continue;
    for (int axis = 0; axis < 3; ++axis) {
      const float lo = axis_of(ob.a, axis), hi = axis_of(ob.b, axis);
      float& reach_lo = axis_of(ob.reach_lo, axis);
      float& reach_hi = axis_of(ob.reach_hi, axis);
      for (int32_t w = 0; w < count; ++w) {
        const Shape& other = shapes[w];
        if (w == o) continue;
        if (other.type == ShapeType::Box && other.keep_inside) {  // container walls (no ceiling when open)
          if (lo <= axis_of(other.a, axis) + gap) reach_lo = kBehindWall;
          if (hi >= axis_of(other.b, axis) - gap && !(axis == 1 && other.open_top)) reach_hi = kBehindWall;
        } else if (other.type == ShapeType::Plane) {  // a plane whose normal is this axis
          const float nc = axis_of(other.b, axis), at = axis_of(other.a, axis);
          if (nc > 0.9999f && lo <= at + gap) reach_lo = kBehindWall;
          if (nc < -0.9999f && hi >= at - gap) reach_hi = kBehindWall;
        } else if (other.type == ShapeType::Box && face_covered(ob, other, axis, gap)) {  // stacked obstacles
          const float other_lo = axis_of(other.a, axis), other_hi = axis_of(other.b, axis);
          if (std::fabs(lo - other_hi) <= gap) reach_lo = std::max(reach_lo, lo - other_lo);
          if (std::fabs(hi - other_lo) <= gap) reach_hi = std::max(reach_hi, other_hi - hi);
        }
      }
    }
  }
}

}  // namespace sph
