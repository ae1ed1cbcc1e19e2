// Emitters (thesis 4.1.4): instant box and sphere fills on a regular lattice, and continuous jets with a
// circular or square section that are fed through an inlet region (thesis 4.1.6).
#pragma once

#include <cstdint>
#include <vector>

#include "particle_state.h"
#include "scene.h"

namespace sph {

// Lattice points (spacing d) of an instant emitter: box cells are filled at their centres, spheres with
// the lattice points inside the radius.
std::vector<Vec3d> fill_emitter(const EmitterSpec& e, double d);

// A continuous jet. New particles are born at the start of an inlet of length L behind the outlet and move
// kinematically (age < 0) until they have travelled L; then they become ordinary fluid particles
// (thesis 4.1.6, after Lastiwka et al. 2008). Layers of the section lattice are emitted every d / speed.
class JetEmitter {
 public:
  JetEmitter(const EmitterSpec& spec, double spacing, double inlet_length, float density);

  // Particles to create during (t, t + dt]. ids are assigned from next_id, which is advanced.
  std::vector<Spawn> advance(double t, double dt, int32_t& next_id);
  // Particles that fill the inlet at start-up, so the flow is established from the first step.
  std::vector<Spawn> prefill(int32_t& next_id);

  std::size_t section_size() const { return section_.size(); }
  double inlet_length() const { return inlet_length_; }
  const EmitterSpec& spec() const { return spec_; }
  // Most particles this jet keeps alive at once (its lifetime plus the inlet), or 0 when unbounded.
  double steady_count(double run_time) const;
  // Distance moved since the last layer was born [m]: the emission accumulator a frame stores so a
  // continued run emits its layers at the same steps and places.
  double travelled() const { return travelled_; }
  void set_travelled(double distance) { travelled_ = distance; }

 private:
  void layer(double offset, std::vector<Spawn>& out, int32_t& next_id) const;

  EmitterSpec spec_;
  double spacing_;
  double inlet_length_;
  float density_;
  std::vector<Vec3d> section_;  // section lattice points, already in world orientation, relative to centre
  double travelled_ = 0.0;      // distance moved since the last layer was born
};

}  // namespace sph
