// Particle frames as binary little-endian PLY point clouds. ParaView and Blender open them directly, and
// they carry the full state a run needs to continue (frame_reader.h). The format, in this order:
//   ply / format binary_little_endian 1.0
//   comment sph frame, time T s        T: simulated time, %.17g (reads back to the same double)
//   comment scene NAME
//   comment step N
//   comment frame I                    index I of frame_IIIII.ply
//   comment next_id K
//   comment spacing D                  %.17g [m]
//   comment jets J
//   comment jet j travelled X          one line per jet, X %.17g [m] (its emission accumulator)
//   element vertex N
//   properties, one record per particle: float x y z vx vy vz density pressure, uchar fluid, int id,
//   float ax ay az age near_pressure   (near_pressure: WCSPH's near pressure, or DFSPH's divergence pressure
//                                       times dt [Pa s], its next warm start's source, particle_view.h)
//   end_header
#pragma once

#include <string>

#include "frame_format.h"
#include "particle_state.h"

namespace sph {

// Bytes of one particle record (the properties above).
constexpr std::size_t kFrameRecordBytes = 8 * 4 + 1 + 4 + 5 * 4;

// Writes path atomically: the frame goes to path + ".tmp", every write is checked, and only a complete
// file is renamed to path. Throws std::runtime_error naming the file and the reason; then no partial
// path is left (an older file of that name stays as it was) and the temporary file is removed.
void write_ply_frame(const std::string& path, const ParticleState& ps, const FrameInfo& info);

}  // namespace sph
